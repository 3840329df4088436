// The differential fuzzer's driver: generates programs (generator.hpp), evaluates each through cgagen's own
// pipeline at -O0, -O1 and -O2 (parse, expand, optimize, and the evaluator that computes what the emitted
// code computes: the same path as `cgagen --eval`) and through the oracle interpreter (interpreter.hpp),
// and requires agreement to 1e-9 relative (to the output's largest coefficient) or a refusal by both.
// Refusals for cgagen's work budget are counted, not failures (the budget is a deliberate limit). Every
// --compile-every'th program's emitted C++ is compiled with the system compiler and its GLSL with glslangValidator
// (one run each at the end).
// Committed regressions (--regressions DIR, *.clu whose first line is "// inputs: a=1 b=-0.5 ...") are
// replayed first. Exit 0 when everything agrees; the failing scripts are printed (and, with --work-dir,
// written to WORK/finds/).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>
#include <set>
#include <string>

#include "algebra/blade.hpp"
#include "emit/emit.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "generator.hpp"
#include "interpreter.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"

namespace fs = std::filesystem;

namespace {

struct Result {
  bool refused = false;
  bool budget = false;  // refused for cgagen's work budget
  std::string message;
  struct Coeffs : std::array<double, oracle::kBlades> {
    std::array<bool, oracle::kBlades> present{};  // cgagen: the blades it returned
  };
  std::map<std::string, Coeffs> outputs;  // null-basis coefficients (Gaalop order)
};

std::map<std::string, unsigned> null_index() {
  std::map<std::string, unsigned> m;
  const auto& names = oracle::null_blade_names();
  for (unsigned k = 0; k < oracle::kBlades; ++k) m[names[k]] = k;
  return m;
}

Result run_cgagen(const cgagen::front::Script& script, const std::map<std::string, double>& inputs,
                  cgagen::opt::Level level, std::string* cpp, std::string* glsl, const std::string& name) {
  static const std::map<std::string, unsigned> index = null_index();
  Result r;
  try {
    cgagen::Kernel k = cgagen::expand(script, name);
    cgagen::opt::Program p = cgagen::opt::optimize(k, level);
    cgagen::opt::InputValues in;
    for (const auto& ki : k.inputs) {
      auto it = inputs.find(ki.name);
      if (it == inputs.end()) throw std::runtime_error("no value for input " + ki.name);
      in[ki.name] = {it->second};
    }
    for (const auto& line : cgagen::opt::evaluate(p, in)) {
      auto& o = r.outputs[line.output];
      auto ix = index.find(cgagen::algebra::blade_name(line.blade));
      if (ix == index.end()) throw std::runtime_error("blade name not in the oracle: " + cgagen::algebra::blade_name(line.blade));
      o[ix->second] = line.value;
      o.present[ix->second] = true;
    }
    if (cpp) {
      cgagen::emit::EmitOptions eo;
      *cpp = cgagen::emit::emit(p, eo);
    }
    if (glsl) {
      cgagen::emit::EmitOptions eo;
      eo.target = cgagen::emit::Target::Glsl;
      *glsl = cgagen::emit::emit(p, eo);
    }
  } catch (const cgagen::front::CompileError& e) {
    r.refused = true;
    r.message = e.what();
    r.budget = r.message.find("work budget") != std::string::npos;
  } catch (const std::exception& e) {
    r.refused = true;
    r.message = std::string("internal: ") + e.what();  // never acceptable: a library message escaped
  }
  return r;
}

Result run_oracle(const cgagen::front::Script& script, const std::map<std::string, double>& inputs) {
  Result r;
  try {
    diff::Outputs o = diff::interpret(script, inputs);
    for (const auto& n : o.order) {
      const auto c = oracle::to_null_basis(o.values.at(n));
      std::copy(c.begin(), c.end(), r.outputs[n].begin());
    }
  } catch (const std::exception& e) {
    r.refused = true;
    r.message = e.what();
  }
  return r;
}

// "" when a and b agree; else what differs. Outputs named in `pragma_outputs` have a '#pragma output'
// blade list: cgagen returns only those blades, so only the blades it returns are compared. A value below
// 1e-7 of the output's scale counts as zero (a square root of a rounded zero is ~1e-8, where the exact
// pipeline gives 0).
std::string compare(const Result& cg, const Result& ref, const std::set<std::string>& pragma_outputs) {
  if (cg.refused || ref.refused) {
    if (cg.refused && ref.refused) return "";
    return cg.refused ? "cgagen refused (" + cg.message + "), the oracle gives values"
                      : "the oracle refused (" + ref.message + "), cgagen gives values";
  }
  if (cg.outputs.size() != ref.outputs.size()) return "different numbers of outputs";
  for (const auto& [name, want] : ref.outputs) {
    auto it = cg.outputs.find(name);
    if (it == cg.outputs.end()) return "cgagen lacks output " + name;
    double scale = 1;
    for (double v : want) scale = std::max(scale, std::abs(v));
    for (unsigned k = 0; k < oracle::kBlades; ++k) {
      const double got = it->second[k], w = want[k];
      if (std::isnan(got) && std::isnan(w)) continue;
      if (pragma_outputs.count(name) && !it->second.present[k]) continue;
      if (std::abs(got) < 1e-7 * scale && std::abs(w) < 1e-7 * scale) continue;
      if (!(std::abs(got - w) <= 1e-9 * scale)) {
        std::ostringstream s;
        s.precision(17);
        s << name << " " << oracle::null_blade_names()[k] << ": cgagen " << got << ", oracle " << w;
        return s.str();
      }
    }
  }
  return "";
}

struct Stats {
  int programs = 0, agreed_values = 0, both_refused = 0, budget = 0, failures = 0;
  long derivatives = 0, kinks = 0;  // partial derivatives compared; left out where the values are not smooth
};

// The Jacobian (expand's `jacobian` with respect to every input, -O2) against central differences of the
// interpreter's values at steps h and h/2, Richardson-extrapolated. Where the two steps disagree, where
// cgagen's derivative jumps within the step, or where the value is 0 up to rounding, the values are not smooth
// there (a select's switch, abs or a square root at 0): that derivative is counted, not compared. "" or what
// differs.
std::string check_jacobian(const cgagen::front::Script& script, const std::map<std::string, double>& inputs,
                           const std::string& name, Stats& st) {
  static const std::map<std::string, unsigned> index = null_index();
  std::vector<std::string> wrt;  // the script's inputs (the generator's inputs map may hold unused names)
  using Table = std::map<std::string, std::array<double, oracle::kBlades>>;
  std::map<std::string, std::array<bool, oracle::kBlades>> present;  // a '#pragma output' returns its blades only
  std::optional<cgagen::opt::Program> program;
  try {
    for (const auto& ki : cgagen::expand(script, name).inputs) wrt.push_back(ki.name);
    if (wrt.empty()) return "";
    program.emplace(cgagen::opt::optimize(cgagen::expand(script, name, nullptr, wrt), cgagen::opt::Level::O2));
  } catch (const std::exception& e) {
    return std::string("the Jacobian of a program with values is refused: ") + e.what();
  }
  auto jacobian_at = [&](const std::map<std::string, double>& at) {
    cgagen::opt::InputValues in;
    for (const auto& x : wrt) in[x] = {at.at(x)};
    Table t;
    for (const auto& line : cgagen::opt::evaluate(*program, in)) {
      const unsigned c = index.at(cgagen::algebra::blade_name(line.blade));
      t[line.output][c] = line.value;
      present[line.output][c] = true;
    }
    return t;
  };
  const Table jac = jacobian_at(inputs);
  for (const auto& x : wrt) {
    auto differences = [&](double h) {
      std::map<std::string, double> lo = inputs, hi = inputs;
      lo[x] -= h;
      hi[x] += h;
      const Result a = run_oracle(script, lo), b = run_oracle(script, hi);
      Table d;
      if (a.refused || b.refused) return d;
      for (const auto& [o, vb] : b.outputs)
        for (unsigned c = 0; c < oracle::kBlades; ++c) d[o][c] = (vb[c] - a.outputs.at(o)[c]) / (2 * h);
      return d;
    };
    const double h = 1e-3 * std::max(1.0, std::abs(inputs.at(x)));
    const Table d1 = differences(h), d2 = differences(h / 2);
    // cgagen's own derivative half a step either side: where it jumps, the point is not smooth (abs or a square
    // root of a value that is 0 up to rounding, a select switching).
    std::map<std::string, double> lo = inputs, hi = inputs;
    lo[x] -= h / 2;
    hi[x] += h / 2;
    const Table jl = jacobian_at(lo), jh = jacobian_at(hi);
    const Result ref = run_oracle(script, inputs);
    for (const auto& [o, v1] : d1) {
      const std::string out = o + "_d_" + x;
      const auto it = jac.find(out);
      if (it == jac.end()) return "no derivative output " + out;
      if (!d2.count(o) || ref.refused) continue;
      double scale = 1;  // the output's magnitude: its values agree with the oracle's to 1e-9 of it
      for (double v : ref.outputs.at(o)) scale = std::max(scale, std::abs(v));
      for (unsigned c = 0; c < oracle::kBlades; ++c) {
        if (!present[out][c]) continue;
        const double a = v1[c], b = d2.at(o)[c], got = it->second[c];
        const double around = std::abs(jh.at(out)[c] - jl.at(out)[c]);
        // A value that is 0 up to rounding (as compare() treats it) may be the square root of a rounded zero,
        // whose difference quotients are noise: not compared either.
        const bool rounded_zero = std::abs(ref.outputs.at(o)[c]) < 1e-7 * scale;
        if (rounded_zero || !std::isfinite(a) || !std::isfinite(b) || std::abs(a - b) > 1e-3 * std::max(1.0, std::abs(b)) ||
            !(around <= 1e-2 * std::max(1.0, std::abs(got)))) {
          ++st.kinks;
          continue;
        }
        const double want = (4 * b - a) / 3;
        ++st.derivatives;
        // Rounding: the difference quotients carry the values' rounding (about 1e-12 of the output's scale)
        // divided by the step.
        if (!(std::abs(got - want) <= 1e-6 * std::max(1.0, std::abs(want)) + 1e-12 * scale / h)) {
          std::ostringstream s;
          s.precision(17);
          s << "d " << o << " " << oracle::null_blade_names()[c] << " / d " << x << ": cgagen " << got
            << ", central differences of the oracle " << want;
          return s.str();
        }
      }
    }
  }
  return "";
}

// Checks one script; returns "" or the failure.
std::string check(const std::string& text, const std::map<std::string, double>& inputs, const std::string& name,
                  Stats& st, std::string* cpp, std::string* glsl = nullptr) {
  cgagen::front::SourceFile file(name + ".clu", text);
  cgagen::front::Script script;
  try {
    script = cgagen::front::parse(file);
  } catch (const cgagen::front::CompileError& e) {
    return std::string("the generator wrote a script that does not parse: ") + e.what();
  }
  const Result ref = run_oracle(script, inputs);
  std::set<std::string> pragma_outputs;
  for (const auto& s : script.statements)
    if (s->kind == cgagen::front::Stmt::Kind::Pragma && s->words.size() > 1 && s->words[0] == "output")
      pragma_outputs.insert(s->words[1]);
  bool any_budget = false;
  std::string failure;
  for (auto level : {cgagen::opt::Level::O0, cgagen::opt::Level::O1, cgagen::opt::Level::O2}) {
    const bool o2 = level == cgagen::opt::Level::O2;
    const Result cg = run_cgagen(script, inputs, level, o2 ? cpp : nullptr, o2 ? glsl : nullptr, name);
    if (cg.budget) {
      any_budget = true;
      continue;
    }
    if (cg.message.rfind("internal:", 0) == 0) failure = "-O" + std::to_string(static_cast<int>(level)) + ": " + cg.message;
    else if (std::string d = compare(cg, ref, pragma_outputs); !d.empty()) failure = "-O" + std::to_string(static_cast<int>(level)) + ": " + d;
    if (!failure.empty()) break;
  }
  if (failure.empty() && !any_budget && !ref.refused && !inputs.empty()) failure = check_jacobian(script, inputs, name, st);
  ++st.programs;
  if (!failure.empty()) ++st.failures;
  else if (any_budget) ++st.budget;
  else if (ref.refused) ++st.both_refused;
  else ++st.agreed_values;
  return failure;
}

std::string inputs_line(const std::map<std::string, double>& in) {
  std::ostringstream s;
  s.precision(17);
  s << "// inputs:";
  for (const auto& [k, v] : in) s << " " << k << "=" << v;
  return s.str();
}

}  // namespace

int main(int argc, char** argv) {
  std::uint64_t seed = 1;
  int count = 300, compile_every = 0;
  std::string work;
  std::vector<std::string> regressions;  // directories of *.clu, or single scripts
  for (int i = 1; i < argc; ++i) {
    std::string a = argv[i];
    auto val = [&]() -> std::string {
      if (i + 1 >= argc) { std::cerr << "diff_fuzz: " << a << " needs a value\n"; std::exit(2); }
      return argv[++i];
    };
    if (a == "--seed") seed = std::stoull(val());
    else if (a == "--count") count = std::stoi(val());
    else if (a == "--compile-every") compile_every = std::stoi(val());
    else if (a == "--work-dir") work = val();
    else if (a == "--regressions") regressions.push_back(val());
    else { std::cerr << "usage: diff_fuzz [--seed S] [--count N] [--compile-every K] [--work-dir D] [--regressions DIR|FILE]...\n"; return 2; }
  }
  const auto start = std::chrono::steady_clock::now();
  Stats st;
  int failures = 0;
  if (!work.empty()) fs::create_directories(fs::path(work) / "finds");
  // Committed finds first, then single scripts (the benchmarks' algorithms). Each leading "// inputs: ..." line
  // of a script is one check.
  std::vector<fs::path> files;
  for (const auto& r : regressions) {
    if (fs::is_regular_file(r)) {
      files.push_back(r);
    } else if (fs::is_directory(r)) {
      std::vector<fs::path> in_dir;
      for (const auto& e : fs::directory_iterator(r))
        if (e.path().extension() == ".clu") in_dir.push_back(e.path());
      std::sort(in_dir.begin(), in_dir.end());
      files.insert(files.end(), in_dir.begin(), in_dir.end());
    } else {
      std::cerr << "diff_fuzz: no such regression file or directory: " << r << "\n";
      return 2;
    }
  }
  for (const auto& f : files) {
    std::ifstream in(f);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    std::istringstream lines(text);
    std::string line;
    int checks = 0;
    while (std::getline(lines, line) && line.rfind("// inputs:", 0) == 0) {
      ++checks;
      std::map<std::string, double> inputs;
      std::istringstream words(line);
      std::string word;
      words >> word >> word;  // "//" "inputs:"
      while (words >> word) inputs[word.substr(0, word.find('='))] = std::stod(word.substr(word.find('=') + 1));
      std::string fail = check(text, inputs, "regression", st, nullptr);
      if (!fail.empty()) {
        ++failures;
        std::cout << "REGRESSION " << f.filename().string() << " (" << line << "): " << fail << "\n";
      }
    }
    if (checks == 0) {
      ++failures;
      std::cout << "REGRESSION " << f.filename().string() << ": no leading '// inputs: ...' line\n";
    }
  }
  std::string compile_unit = "#include <cmath>\n";
  std::string shader = "#version 330\n";  // the sampled kernels' GLSL, in one vertex shader for glslang
  int compiled = 0, if_sampled = 0;
  for (int i = 0; i < count; ++i) {
    const std::uint64_t s = seed * 1000003ull + static_cast<std::uint64_t>(i);
    diff::Program p = diff::generate(s);
    std::string cpp, glsl;
    // Every compile_every'th program, and the first five with an if/else (their selects in both languages).
    const bool with_if = p.text.find("if (") != std::string::npos && if_sampled < 5;
    const bool sample = compile_every > 0 && (i % compile_every == 0 || with_if);
    if (sample && with_if) ++if_sampled;
    const std::string name = "diff_" + std::to_string(i);
    std::string fail = check(p.text, p.inputs, name, st, sample ? &cpp : nullptr, sample ? &glsl : nullptr);
    if (!fail.empty()) {
      ++failures;
      const std::string script = inputs_line(p.inputs) + "\n" + p.text;
      std::cout << "FIND (seed " << s << "): " << fail << "\n" << script << "\n";
      if (!work.empty()) std::ofstream(fs::path(work) / "finds" / ("seed_" + std::to_string(s) + ".clu")) << script;
    }
    if (sample && !cpp.empty()) {
      // Each kernel header has its own #pragma once; a unit of several includes them as text.
      std::string body = cpp;
      auto at = body.find("#pragma once");
      if (at != std::string::npos) body.erase(at, 12);
      compile_unit += body;
      shader += glsl;
      ++compiled;
    }
  }
  if (compiled > 0 && !work.empty()) {
    const fs::path unit = fs::path(work) / "sample.cpp";
    std::ofstream(unit) << compile_unit;
    const std::string cmd = "c++ -std=c++20 -fsyntax-only -Wall -Werror " + unit.string() + " 2>&1";
    const int rc = std::system(cmd.c_str());
    if (rc != 0) {
      ++failures;
      std::cout << "the emitted C++ of " << compiled << " sampled programs does not compile: " << unit << "\n";
    }
    // The same programs' GLSL: the emitted shader code must compile too, not only the C++.
    const fs::path vert = fs::path(work) / "sample.vert";
    std::ofstream(vert) << shader << "\nvoid main() { gl_Position = vec4(0.0); }\n";
    const std::string glsl_cmd = std::string(GLSLANG_VALIDATOR) + " " + vert.string() + " > " + vert.string() + ".log 2>&1";
    if (std::system(glsl_cmd.c_str()) != 0) {
      ++failures;
      std::cout << "the emitted GLSL of " << compiled << " sampled programs does not compile: " << vert << " (log: "
                << vert.string() << ".log)\n";
    }
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  std::cout << "diff_fuzz: " << st.programs << " programs (seed " << seed << "): " << st.agreed_values
            << " agree on values, " << st.both_refused << " refused by both, " << st.budget
            << " over cgagen's work budget, " << failures << " failures; " << st.derivatives
            << " partial derivatives against central differences of the oracle (" << st.kinks
            << " left out where the values are not smooth); " << compiled
            << " emitted kernels compiled (C++ and GLSL); " << seconds << " s\n";
  return failures == 0 ? 0 : 1;
}
