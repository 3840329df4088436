// exp and log of rotors and motors (gen/expand/exponential.cpp) against the any-signature oracle: exp(B)
// equals the oracle's power series sum_k B^k / k! for rotations, translations, dilations and their sums
// (screws; CGA's rotation with dilation) in CGA, 3D PGA and 3D, at large, small and zero angles; log(exp(B)) gives B back and
// exp(log(M)) gives M back; what is not supported is a located error.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "algebra/algebra.hpp"
#include "front/diagnostics.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "expand_error.hpp"
#include "oracle_algebras.hpp"

using namespace cgagen;

namespace {

// The bivector blades a screw generator uses: the rotation planes and the translation (or PGA's e0) planes.
struct Model {
  std::string algebra;
  std::vector<std::string> rotation, translation, dilation;
};

const std::vector<Model>& models() {
  static const std::vector<Model> m = {
      {"cga", {"e1^e2", "e1^e3", "e2^e3"}, {"e1^einf", "e2^einf", "e3^einf"}, {"einf^e0"}},
      {"3dpga", {"e1^e2", "e1^e3", "e2^e3"}, {"e0^e1", "e0^e2", "e0^e3"}, {}},
      {"3d", {"e1^e2", "e1^e3", "e2^e3"}, {}, {}},
  };
  return m;
}

og::MV oracle_exp(const og::Algebra& alg, const og::MV& b) {
  og::MV sum{{0u, 1.0}}, term{{0u, 1.0}};
  for (int k = 1; k < 60; ++k) {
    term = og::scaled(og::product(alg, term, b, og::Op::Geometric), 1.0 / k);
    sum = og::sum(sum, term);
  }
  return sum;
}

// Expands and optimizes (-O2) `script` once.
opt::Program compile(const std::string& algebra, const std::string& script) {
  front::SourceFile file("exp.clu", script);
  return opt::optimize(expand(front::parse(file), "exp", algebra::builtin(algebra)), opt::Level::O2);
}

// The program's outputs at `values` (scalar inputs): output -> blade -> value.
std::map<std::string, Named> run(const opt::Program& p, const std::map<std::string, double>& values) {
  opt::InputValues in;
  for (const auto& [n, v] : values) in[n] = {v};
  std::map<std::string, Named> out;
  for (const auto& line : opt::evaluate(p, in)) out[line.output][line.blade_name] += line.value;
  return out;
}

}  // namespace

TEST_CASE("exp of rotations, translations and screws matches the oracle's series, and log inverts it") {
  for (const Model& m : models()) {
    INFO("algebra " << m.algebra);
    algebra::Using use(algebra::builtin(m.algebra));
    const og::Algebra alg = oracle_algebra(m.algebra);
    std::vector<std::string> blades = m.rotation;
    blades.insert(blades.end(), m.translation.begin(), m.translation.end());
    blades.insert(blades.end(), m.dilation.begin(), m.dilation.end());
    auto generator = [&](size_t count) {
      std::string text;
      for (size_t i = 0; i < count; ++i)
        text += (i ? " + " : "") + std::string("b") + std::to_string(i) + "*(" + blades[i] + ")";
      return "B = " + text + ";\n?M = exp(B);\n?L = log(M);\n";
    };
    // Without a dilation also exp(log(M)) (with one, exp's sign test does not see through log's expressions).
    const size_t screw = m.rotation.size() + m.translation.size();
    const opt::Program full = compile(m.algebra, generator(blades.size())),
                       round_trip = compile(m.algebra, generator(screw) + "N = M;\n?E = exp(log(N));\n");
    std::mt19937 rng(4242u);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    // Rotation scales: ordinary, small (the Taylor branch), tiny, and none (a pure translation, or 0); the
    // same for a dilation where the algebra has one.
    const std::vector<double> dilations = m.dilation.empty() ? std::vector<double>{0.0} : std::vector<double>{0.7, 1e-3, 0.0};
    for (double rot : {1.0, 0.05, 1e-6, 0.0})
      for (double tr : {1.5, 0.0})
        for (double dil : dilations)
        for (int trial = 0; trial < 2; ++trial) {
          std::map<std::string, double> values;
          og::MV b;
          for (size_t i = 0; i < blades.size(); ++i) {
            const size_t r = m.rotation.size(), t = r + m.translation.size();
            const double v = (i < r ? rot : i < t ? tr : dil) * u(rng);
            if (i < screw || dil != 0.0) values["b" + std::to_string(i)] = v;
            for (const auto& [x, cx] : og::user_blade(alg, blades[i])) og::add(b, x, v * cx);
          }
          INFO("rotation scale " << rot << ", translation scale " << tr << ", dilation scale " << dil);
          const auto got = run(dil == 0.0 ? round_trip : full, values);
          auto get = [&](const std::string& o) { return got.count(o) ? got.at(o) : Named{}; };
          const Named want_m = from_oracle(alg, oracle_exp(alg, b)), want_b = from_oracle(alg, b);
          CHECK(max_diff(get("M"), want_m) < 1e-12);
          CHECK(max_diff(get("L"), want_b) < 1e-9);
          if (dil == 0.0) CHECK(max_diff(get("E"), want_m) < 1e-9);
        }
  }
}

TEST_CASE("exp and log refuse what they have no closed form for, at their argument") {
  using Catch::Matchers::StartsWith;
  // Two commuting rotation planes (e1^e2 and e3^e+, e+ = e0 - einf/2): no closed form here; a rotation with a
  // dilation, or STA's rotation with a boost, has one.
  CHECK_THAT(error_of("cga", "?x = exp(a*(e1^e2) + b*(e3^e0) - 0.5*b*(e3^einf));\n"),
             StartsWith("bad.clu:1:32: error: 'exp' of a bivector B of two commuting planes is supported where"));
  CHECK(error_of("sta", "?x = exp(a*(e0^e1) + b*(e2^e3));\n") == "no error");
  CHECK(error_of("cga", "?x = exp(a*(e1^e2) + b*(einf^e0));\n") == "no error");
  CHECK(error_of("cga", "?x = exp(e1);\n") == "bad.clu:1:10: error: 'exp' takes a scalar or a bivector, got a "
                                                "multivector with blades e1");
  CHECK_THAT(error_of("cga", "?x = log(a + b*e1);\n"),
             StartsWith("bad.clu:1:12: error: 'log' takes a positive scalar, or a rotor or motor"));
  CHECK(error_of("cga", "?x = log(a + b*(e1^e2) + c*(einf^e0) + b*c*(e1^e2^einf^e0));\n") == "no error");
  CHECK(error_of("cga", "?x = log(a + b*(e1^e2) + c*(e3^einf));\n") == "no error");
}

TEST_CASE("exp of a bivector whose square has no visible sign chooses rotation, boost or null at run time") {
  // B = x e1^e2 + y e1^em: e1^e2 and e1^em anticommute, so B*B = y^2 - x^2, a rotation for |x| > |y|, a boost
  // for |y| > |x|, null for |x| = |y| (then exp(B) = 1 + B). And (a*b + c) e1^em: a boost whose square,
  // (ab + c)^2 expanded, is not visibly >= 0.
  const opt::Program p = compile("cga", "?v = exp(x*(e1^e2) + y*(e1^em));\n?w = exp((a*b + c)*(e1^em));\n");
  for (const auto& [x, y] : std::vector<std::pair<double, double>>{{0.9, 0.4}, {0.3, 1.2}, {0.7, 0.7}, {0.7, -0.7}, {0, 0}}) {
    INFO("x = " << x << ", y = " << y);
    const auto got = run(p, {{"x", x}, {"y", y}, {"a", 1}, {"b", 0}, {"c", 0}});
    const double sq = y * y - x * x, t = std::sqrt(std::abs(sq));
    const double c = sq < 0 ? std::cos(t) : sq > 0 ? std::cosh(t) : 1.0;
    const double s = sq < 0 ? std::sin(t) / t : sq > 0 ? std::sinh(t) / t : 1.0;
    const Named v = got.count("v") ? got.at("v") : Named{};
    auto at = [&](const std::string& blade) { return v.count(blade) ? v.at(blade) : 0.0; };
    CHECK(at("1") == Approx(c).margin(1e-12));
    CHECK(at("e1^e2") == Approx(s * x).margin(1e-12));
    // e1^em = e1^e0 + e1^einf / 2 (em = e0 + einf/2).
    CHECK(at("e1^e0") == Approx(s * y).margin(1e-12));
    CHECK(at("e1^einf") == Approx(s * y / 2).margin(1e-12));
  }
  const auto got = run(p, {{"x", 0}, {"y", 0}, {"a", 1}, {"b", 0.5}, {"c", 0.2}});
  CHECK(got.at("w").at("1") == Approx(std::cosh(0.7)).epsilon(1e-12));
  CHECK(got.at("w").at("e1^e0") == Approx(std::sinh(0.7)).epsilon(1e-12));
}
