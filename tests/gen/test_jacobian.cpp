// Derivative kernels (`#pragma jacobian`, cgagen --jacobian; expand/jacobian.cpp): every bundled script's
// outputs differentiated with respect to every input coefficient (the scalar inputs only where the multivector
// inputs have more than 24 coefficients), optimized at -O2 and evaluated in double,
// against central differences of the script's own values (Richardson-extrapolated) at seeded random points
// (relative 1e-6); the
// pragma's forms and its located errors; a select differentiates its taken branch.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "expand/expand.hpp"
#include "expand_error.hpp"
#include "front/diagnostics.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"

using namespace cgagen;

namespace {

using Values = std::map<std::string, double>;  // "OUTPUT BLADE" -> value

Values run(const opt::Program& p, const opt::InputValues& in) {
  Values out;
  for (const auto& l : opt::evaluate(p, in)) out[l.output + " " + l.blade_name] = l.value;
  return out;
}

std::string read(const std::filesystem::path& p) {
  std::ifstream f(p);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

std::vector<std::filesystem::path> bundled_scripts() {
  std::vector<std::filesystem::path> out;
  for (const char* dir : {"runtime/scripts", "runtime/scripts/skin", "tests/gen/scripts", "tests/kernels/scripts", "bench/ik_arm"})
    for (const auto& e : std::filesystem::directory_iterator(std::filesystem::path(CGA_SOURCE_DIR) / dir))
      if (e.path().extension() == ".clu") out.push_back(e.path());
  std::sort(out.begin(), out.end());
  return out;
}

// Every bundled script's Jacobian in the given order (CGAGEN_JACOBIAN_ORDER: forward or reverse; the
// expander picks one per request by its size, so both are held to the same differences here).
void check_bundled(const char* order) {
  setenv("CGAGEN_JACOBIAN_ORDER", order, 1);
  std::mt19937 rng(20261128u);
  std::uniform_real_distribution<double> u(-0.9, 0.9);
  int scripts = 0, compared = 0;
  for (const auto& path : bundled_scripts()) {
    if (path.stem() == "circle3" || path.stem() == "paper_a1") continue;  // the two largest: minutes, not seconds
    INFO("script " << path.filename().string());
    const front::SourceFile file(path.filename().string(), read(path));
    const front::Script script = front::parse(file);
    const Kernel plain = expand(script, "k");
    // With respect to every input; where the multivector inputs have more than 24 coefficients together (the
    // skinning blends: four palette entries), the scalar inputs only, which keeps the test in seconds.
    size_t mv_coefficients = 0;
    for (const auto& in : plain.inputs) mv_coefficients += in.is_multivector ? in.symbols.size() : 0;
    std::vector<std::string> wrt;
    for (const auto& in : plain.inputs)
      if (!in.is_multivector || mv_coefficients <= 24) wrt.push_back(in.name);
    const Kernel with = expand(script, "k", nullptr, wrt);
    const opt::Program value = opt::optimize(plain, opt::Level::O2), jac = opt::optimize(with, opt::Level::O2);
    // A point where every value is finite (the scripts' own domains: acos of a cosine, a reachable target).
    opt::InputValues at;
    Values base;
    bool finite = false;
    for (int tries = 0; tries < 50 && !finite; ++tries) {
      for (const auto& in : plain.inputs) {
        at[in.name].clear();
        for (size_t k = 0; k < in.symbols.size(); ++k) at[in.name].push_back(u(rng));
      }
      base = run(jac, at);
      finite = std::all_of(base.begin(), base.end(), [](const auto& kv) { return std::isfinite(kv.second); });
    }
    REQUIRE(finite);
    ++scripts;
    // A script's own derivative outputs (its #pragma jacobian: OUT_d_IN...) get no derivatives of their own;
    // the expansion's OUT_d_IN for the same input, compared below, is the same value.
    const auto derivative_output = [&](const std::string& name) {
      for (const auto& o : plain.outputs)
        for (const auto& in : plain.inputs)
          if (name.rfind(o.name + "_d_" + in.name, 0) == 0) return true;
      return false;
    };
    for (const auto& in : plain.inputs)
      for (size_t k = 0; k < in.symbols.size() && std::find(wrt.begin(), wrt.end(), in.name) != wrt.end(); ++k) {
        const std::string x = in.is_multivector ? in.name + "_" + algebra::blade_ident(in.blades[k]) : in.name;
        // Central differences at steps h and h/2, combined by Richardson extrapolation: the error is O(h^4)
        // in truncation and about 1e-13 |f| / h in rounding.
        const double h = 1e-3;
        auto differences = [&](double step) {
          opt::InputValues lo = at, hi = at;
          lo[in.name][k] -= step;
          hi[in.name][k] += step;
          const Values vl = run(value, lo), vh = run(value, hi);
          Values d;
          for (const auto& [key, v] : vh) d[key] = (v - vl.at(key)) / (2 * step);
          return d;
        };
        const Values d1 = differences(h), d2 = differences(h / 2);
        for (const auto& o : plain.outputs)
          for (const auto& [key, v] : d1) {
            if (key.rfind(o.name + " ", 0) != 0 || derivative_output(o.name)) continue;
            const std::string blade = key.substr(o.name.size() + 1);
            const double central = (4 * d2.at(key) - v) / 3;
            const auto it = base.find(o.name + "_d_" + x + " " + blade);
            REQUIRE(it != base.end());
            INFO("d " << key << " / d " << x << ": kernel " << it->second << ", central difference " << central);
            CHECK(std::abs(it->second - central) <= 1e-6 * std::max(1.0, std::abs(central)));
            ++compared;
          }
      }
  }
  unsetenv("CGAGEN_JACOBIAN_ORDER");
  CHECK(scripts >= 20);
  WARN("Jacobians of " << scripts << " scripts in " << order << " order: " << compared
                        << " partial derivatives against central differences");
}

}  // namespace

TEST_CASE("every bundled script's Jacobian in forward order agrees with central differences of its values") {
  check_bundled("forward");
}

TEST_CASE("every bundled script's Jacobian in reverse order agrees with central differences of its values") {
  check_bundled("reverse");
}

TEST_CASE("jacobian pragma: named outputs, every output, a multivector input's coefficients") {
  const std::string body = "R = cos(t/2) - sin(t/2)*e1^e2;\n?p = R*(x*e1)*~R;\n?s = x*t;\n";
  auto outputs = [](const std::string& script) {
    const front::SourceFile file("j.clu", script);
    std::vector<std::string> names;
    for (const auto& o : expand(front::parse(file), "j").outputs) names.push_back(o.name);
    return names;
  };
  CHECK(outputs("#pragma jacobian s wrt t\n" + body) == std::vector<std::string>{"p", "s", "s_d_t"});
  CHECK(outputs("#pragma jacobian wrt t x\n" + body) ==
        std::vector<std::string>{"p", "s", "p_d_t", "s_d_t", "p_d_x", "s_d_x"});
  CHECK(outputs("#pragma input M 1 e1^e2\n#pragma jacobian wrt M\n?q = M*e1*~M;\n") ==
        std::vector<std::string>{"q", "q_d_M_s", "q_d_M_e12"});
  CHECK(error_of("cga", "#pragma jacobian p wrt\n" + body) == "bad.clu:1:1: error: '#pragma jacobian ... wrt' names no input");
  CHECK(error_of("cga", "#pragma jacobian p t\n" + body) == "bad.clu:1:1: error: '#pragma jacobian' expects [OUTPUT...] wrt INPUT...");
  CHECK(error_of("cga", "#pragma jacobian q wrt t\n" + body) == "bad.clu:1:18: error: '#pragma jacobian' names 'q', which is not an output");
  CHECK(error_of("cga", "#pragma jacobian wrt u\n" + body) ==
        "bad.clu:1:22: error: 'jacobian' with respect to 'u', which is not an input of the script");
}

TEST_CASE("jacobian: a select differentiates its taken branch") {
  const front::SourceFile file("sel.clu", "#pragma jacobian wrt x\nif (x < 0) { y = -x*x; } else { y = 3*x; }\n?y = y;\n");
  const opt::Program p = opt::optimize(expand(front::parse(file), "sel"), opt::Level::O2);
  CHECK(run(p, {{"x", {-2.0}}}).at("y_d_x 1") == 4.0);
  CHECK(run(p, {{"x", {2.0}}}).at("y_d_x 1") == 3.0);
}
