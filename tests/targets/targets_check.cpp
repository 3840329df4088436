// targets_check LANG GENDIR WORKDIR SCRIPT...: runs the kernels cgagen emitted for LANG (GENDIR/NAME<ext>,
// made by cgagen_generate() at build time) on random inputs with the language's own compiler or
// interpreter, and compares every output blade with the reference.
//
// Reference: the script's -O0 program (its statements as written, no optimizer) evaluated in double by
// opt::evaluate, the evaluator behind `cgagen --eval`. The fixture (LANG = reference) holds that reference
// itself to the oracle: every sample is also run by the AST interpreter over the dense R(4,1) oracle of
// tests/diff (no code shared with gen/ beyond the parser), and the two must agree to 1e-9 of each output's
// size, or the fixture fails and with it every language. The targets print the -O2 program, so an optimizer
// or printer fault in any language shows up as a difference.
//
// Inputs: uniform in [-1, 1], rounded to float (the same values go to float and double code). Samples at
// which the script is ill-conditioned are redrawn: each input is perturbed by a relative 2^-20 and the sample
// is kept only if no output moves by more than 1e-5 of its scale (an amplification <= ~10), and if every
// reference value is finite. Error of one blade: |got - ref| / max(1, max |ref| over that output's blades),
// i.e. relative to the output's size, absolute below 1. Tolerances: 1e-5 in float, 1e-12 in double (sin/cos
// in the browser APIs: see kTolGpuTrig).
//
// wgsl and glsl-es run in headless Chromium (WebGPU, WebGL 2): one page per language with every script,
// written here, run by browser_run.py, the page's half in browser_harness.js.
//
// Staged kernels: a script with `#pragma uniform`, or an argument PATH@NAME@U1,U2 (the script
// generated as NAME with --uniform U1,U2, see CMakeLists.txt), is emitted as NAME_prepare(uniforms) ->
// prepared[K] and NAME(prepared, per-element inputs). Every driver then calls the two in a row in the
// language itself (the prepared values stay in the language's precision) and the outputs are held to the
// same unstaged -O0 reference and tolerances as any kernel.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <hwy/targets.h>

#include "algebra/blade.hpp"
#include "emit/emit.hpp"
#include "emit/names.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "opt/stage.hpp"
#include "interpreter.hpp"  // tests/diff: CluScript over the oracle
#include "simd_driver.hpp"

using namespace cgagen;
namespace fs = std::filesystem;

namespace {

constexpr int kSamples = 1000;
constexpr double kTolFloat = 1e-5, kTolDouble = 1e-12;
std::string g_refdir;  // WORKDIR/../reference

struct Case {
  std::string name, path;
  std::vector<std::string> uniforms;  // staged: the uniform inputs (else empty)
  std::vector<bool> is_uniform;       // per input
  size_t prepared = 0;                // staged: K, the number of prepared values (else 0)
  size_t graph_nodes = 0;             // the dot graph's nodes: input blades + temporaries + output blades
                                      // (staged: both programs', the prepared values once)
  opt::Program prog;  // -O2: the interface the targets print
  opt::Program ref;   // -O0: the reference
  std::set<std::string> names;    // every name the emitted file spells (emit/names.hpp): its programs' own
  int samples = 0;                // random inputs: 1000, 100 for the names scripts (tests/targets/names)
  std::vector<size_t> in_sizes;   // 0: scalar
  std::vector<size_t> out_sizes;
  size_t nin = 0, nout = 0;
  std::vector<std::vector<double>> inputs, expected;
  int redrawn = 0;
};

uint64_t fnv(const std::string& s) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : s) h = (h ^ c) * 1099511628211ull;
  return h;
}

std::vector<double> reference(const Case& c, const std::vector<double>& flat) {
  opt::InputValues v;
  size_t off = 0;
  for (size_t i = 0; i < c.prog.inputs.size(); ++i) {
    size_t n = std::max<size_t>(1, c.in_sizes[i]);
    v[c.prog.inputs[i].name] = std::vector<double>(flat.begin() + off, flat.begin() + off + n);
    off += n;
  }
  std::vector<double> out;
  for (const auto& l : opt::evaluate(c.ref, v)) out.push_back(l.value);
  return out;
}

// Error of each blade relative to its output's scale; returns the largest.
double max_error(const Case& c, const std::vector<double>& got, const std::vector<double>& ref) {
  double worst = 0;
  size_t off = 0;
  for (size_t n : c.out_sizes) {
    double scale = 1;
    for (size_t k = 0; k < n; ++k) scale = std::max(scale, std::abs(ref[off + k]));
    for (size_t k = 0; k < n; ++k) {
      double e = std::abs(got[off + k] - ref[off + k]) / scale;
      if (!(e == e)) e = INFINITY;
      worst = std::max(worst, e);
    }
    off += n;
  }
  return worst;
}

// How target LANG spells name RAW of case c (the function NAME, NAME_prepare): as the emitter does.
std::string spelt(const Case& c, const std::string& lang, const std::string& raw) {
  std::set<std::string> names = c.names;
  names.insert(raw);
  return emit::spellings(emit::syntax(lang), names).at(raw);
}

// PATH, or PATH@NAME@U1,U2,... for a script generated under another name with --uniform U1,U2,...
Case load(const std::string& arg, bool numeric) {
  Case c;
  std::vector<std::string> cli_uniforms;
  const size_t at = arg.find('@');
  c.path = arg.substr(0, at);
  c.name = emit::c_identifier(fs::path(c.path).stem().string());  // as cgagen_generate() names it
  c.samples = c.path.find("/names/") != std::string::npos ? 100 : kSamples;
  if (at != std::string::npos) {
    const size_t at2 = arg.find('@', at + 1);
    if (at2 == std::string::npos) throw std::runtime_error("bad script argument " + arg + " (PATH@NAME@U1,U2)");
    c.name = arg.substr(at + 1, at2 - at - 1);
    std::istringstream list(arg.substr(at2 + 1));
    for (std::string u; std::getline(list, u, ',');) cli_uniforms.push_back(u);
  }
  front::SourceFile file = front::SourceFile::load(c.path);
  Kernel k = expand(front::parse(file), c.name);
  c.prog = opt::optimize(k, opt::Level::O2);
  c.ref = opt::optimize(k, opt::Level::O0);
  c.uniforms = opt::uniform_inputs(k, cli_uniforms);
  auto add_names = [&c](const opt::Program& p) {
    c.names.insert(p.name);
    for (const auto& in : p.inputs) c.names.insert(in.name);
    for (const auto& o : p.outputs) c.names.insert(o.name);
    for (const auto& t : p.temps) c.names.insert(t.name);
  };
  if (c.uniforms.empty()) add_names(c.prog);
  for (const auto& in : c.prog.inputs)
    c.is_uniform.push_back(std::find(c.uniforms.begin(), c.uniforms.end(), in.name) != c.uniforms.end());
  if (!c.uniforms.empty()) {
    const opt::StagedProgram st = opt::stage(c.prog, c.uniforms);
    add_names(st.prepare);
    add_names(st.body);
    c.prepared = st.prepare.outputs.at(0).slots.size();
    for (const opt::Program* p : {&st.prepare, &st.body}) {
      for (const auto& in : p->inputs)
        if (p == &st.prepare || in.name != "prepared") c.graph_nodes += in.is_multivector ? in.symbols.size() : 1;
      c.graph_nodes += p->temps.size();
    }
  }
  for (const auto& in : c.prog.inputs) {
    c.in_sizes.push_back(in.is_multivector ? in.symbols.size() : 0);
    c.nin += in.is_multivector ? in.symbols.size() : 1;
  }
  for (const auto& o : c.prog.outputs) {
    c.out_sizes.push_back(o.slots.size());
    c.nout += o.slots.size();
  }
  // The reference is computed once per build (ctest fixture targets/reference) and read by every language.
  // It is the unstaged kernel's: a staged case is held to the same values.
  const std::string cache = g_refdir + "/" + c.name + ".ref";
  if (numeric && fs::exists(cache)) {
    std::ifstream in(cache);
    size_t n = 0;
    in >> c.redrawn >> n;
    c.inputs.assign(n, std::vector<double>(c.nin));
    c.expected.assign(n, std::vector<double>(c.nout));
    for (auto& r : c.inputs)
      for (auto& v : r) in >> v;
    for (auto& r : c.expected)
      for (auto& v : r) in >> v;
    if (in) return c;
    c.inputs.clear(), c.expected.clear();
  }
  std::mt19937_64 rng(fnv(c.name));
  std::uniform_real_distribution<double> u(-1, 1);
  std::bernoulli_distribution coin;
  int attempts = 0;
  while (numeric && static_cast<int>(c.inputs.size()) < c.samples) {
    if (++attempts > 50 * c.samples) throw std::runtime_error(c.name + ": too few well-conditioned samples");
    std::vector<double> x(c.nin);
    for (auto& v : x) v = static_cast<float>(u(rng));
    std::vector<double> r = reference(c, x);
    bool ok = true;
    for (double v : r) ok &= std::isfinite(v) && std::abs(v) < 1e6;
    if (ok) {
      std::vector<double> xp = x;
      for (auto& v : xp) v *= 1 + (coin(rng) ? 1 : -1) * std::ldexp(1.0, -20);
      ok = max_error(c, reference(c, xp), r) <= 1e-5;
    }
    if (!ok) {
      ++c.redrawn;
      continue;
    }
    c.inputs.push_back(x);
    c.expected.push_back(r);
  }
  if (numeric) {
    std::ostringstream os;
    char buf[64];
    os << c.redrawn << " " << c.inputs.size() << "\n";
    for (const auto* rows : {&c.inputs, &c.expected})
      for (const auto& r : *rows) {
        for (double v : r) {
          std::snprintf(buf, sizeof buf, "%.17g ", v);
          os << buf;
        }
        os << "\n";
      }
    fs::create_directories(g_refdir);
    std::string tmp = cache + ".tmp" + std::to_string(::getpid());
    std::ofstream(tmp) << os.str();
    fs::rename(tmp, cache);
  }
  return c;
}

// A derivative output of `#pragma jacobian` (OUT_d_IN, OUT_d_IN_BLADE, docs/generator.md "Derivatives"),
// which the interpreter does not compute: OUT and the key of IN's coefficient in the interpreter's inputs.
struct DerivativeOf {
  std::string output, input;
};
std::optional<DerivativeOf> derivative_of(const Case& c, const std::string& name) {
  for (const auto& o : c.prog.outputs)
    for (const auto& in : c.prog.inputs) {
      const std::string stem = o.name + "_d_" + in.name;
      if (!in.is_multivector && name == stem) return DerivativeOf{o.name, in.name};
      if (in.is_multivector)
        for (size_t k = 0; k < in.blades.size(); ++k)
          if (name == stem + "_" + algebra::blade_ident(in.blades[k]))
            return DerivativeOf{o.name, in.name + "[" + std::to_string(k) + "]"};
    }
  return std::nullopt;
}

// The reference against the oracle (see the top): the largest disagreement over a case's samples, or
// infinity when the interpreter refuses the script (said on stderr). Derivative outputs are compared with
// Richardson-extrapolated central differences of the interpreter's values (steps 1e-3 and 5e-4).
double oracle_disagreement(const Case& c) {
  static const std::map<std::string, unsigned> index = [] {
    std::map<std::string, unsigned> m;
    for (unsigned k = 0; k < oracle::kBlades; ++k) m[oracle::null_blade_names()[k]] = k;
    return m;
  }();
  front::SourceFile file = front::SourceFile::load(c.path);
  const front::Script script = front::parse(file);
  double worst = 0;
  for (size_t row = 0; row < c.inputs.size(); ++row) {
    std::map<std::string, double> in;
    size_t off = 0;
    for (size_t i = 0; i < c.prog.inputs.size(); ++i) {
      const auto& ki = c.prog.inputs[i];
      if (!ki.is_multivector) in[ki.name] = c.inputs[row][off++];
      else
        for (size_t k = 0; k < ki.symbols.size(); ++k) in[ki.name + "[" + std::to_string(k) + "]"] = c.inputs[row][off++];
    }
    std::vector<double> got;
    try {
      const diff::Outputs out = diff::interpret(script, in);
      // Blade `blade` of output `name` at the inputs `at`.
      const auto coefficient = [&](const diff::Outputs& values, const std::string& name, algebra::BladeIndex blade) {
        auto v = values.values.find(name);
        if (v == values.values.end()) throw diff::Refused("no output " + name);
        return static_cast<double>(oracle::to_null_basis(v->second).at(index.at(algebra::blade_name(blade))));
      };
      for (const auto& o : c.prog.outputs) {
        const std::optional<DerivativeOf> d = out.values.count(o.name) ? std::nullopt : derivative_of(c, o.name);
        if (!d) {
          for (const auto& slot : o.slots) got.push_back(coefficient(out, o.name, slot.blade));
          continue;
        }
        const auto central = [&](double h) {
          std::map<std::string, double> lo = in, hi = in;
          lo[d->input] -= h, hi[d->input] += h;
          const diff::Outputs vl = diff::interpret(script, lo), vh = diff::interpret(script, hi);
          std::vector<double> r;
          for (const auto& slot : o.slots)
            r.push_back((coefficient(vh, d->output, slot.blade) - coefficient(vl, d->output, slot.blade)) / (2 * h));
          return r;
        };
        const std::vector<double> d1 = central(1e-3), d2 = central(5e-4);
        for (size_t k = 0; k < d1.size(); ++k) got.push_back((4 * d2[k] - d1[k]) / 3);
      }
    } catch (const std::exception& e) {
      std::fprintf(stderr, "%s: the oracle interpreter refuses the script: %s\n", c.name.c_str(), e.what());
      return INFINITY;
    }
    worst = std::max(worst, max_error(c, got, c.expected[row]));
  }
  return worst;
}

void write_rows(const std::string& path, const std::vector<std::vector<double>>& rows) {
  std::ofstream out(path);
  char buf[64];
  for (const auto& r : rows) {
    for (size_t i = 0; i < r.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%.17g", r[i]);
      out << (i ? " " : "") << buf;
    }
    out << "\n";
  }
}

std::vector<std::vector<double>> read_rows(const std::string& path) {
  std::ifstream in(path);
  std::vector<std::vector<double>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    std::vector<double> r;
    std::istringstream ss(line);
    std::string tok;
    while (ss >> tok) r.push_back(std::strtod(tok.c_str(), nullptr));  // strtod reads nan/inf
    rows.push_back(r);
  }
  return rows;
}

int sh(const std::string& cmd) {
  int s = std::system(cmd.c_str());
  return WIFEXITED(s) ? WEXITSTATUS(s) : -1;
}

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

int failures = 0;

// Runs a case's toolchain commands in order; the first that fails is reported with its log (and counted).
template <class Steps>
bool run_steps(const std::string& name, const Steps& steps, const std::string& log) {
  for (const std::string& s : steps)
    if (sh(s) != 0) {
      std::printf("FAIL %-20s %s\n%s\n", name.c_str(), s.c_str(), slurp(log).c_str());
      ++failures;
      return false;
    }
  return true;
}

// Compares a driver's output file with the reference (the first `rows` samples, all when 0).
void check(const Case& c, const std::string& what, const std::string& path, double tol, size_t rows = 0) {
  auto got = read_rows(path);
  size_t n = rows ? rows : c.inputs.size();
  if (got.size() != n) {
    std::printf("FAIL %-20s %-22s %zu rows of output, expected %zu\n", c.name.c_str(), what.c_str(), got.size(), n);
    ++failures;
    return;
  }
  double worst = 0;
  for (size_t i = 0; i < n; ++i) {
    if (got[i].size() != c.nout) {
      std::printf("FAIL %-20s %-22s row %zu has %zu values, expected %zu\n", c.name.c_str(), what.c_str(), i,
                  got[i].size(), c.nout);
      ++failures;
      return;
    }
    worst = std::max(worst, max_error(c, got[i], c.expected[i]));
  }
  bool ok = worst <= tol;
  failures += !ok;
  std::printf("%s %-20s %-22s %zu inputs (%d redrawn), max error %.3g (tolerance %g)\n", ok ? "ok  " : "FAIL",
              c.name.c_str(), what.c_str(), n, c.redrawn, worst, tol);
}

// fn, prepare: the functions as LANG spells them.
std::string meta_json(const Case& c, const std::string& lang) {
  std::string s = "{\"name\": \"" + c.name + "\", \"fn\": \"" + spelt(c, lang, c.name) + "\", \"prepare\": \"" +
                  spelt(c, lang, c.name + "_prepare") + "\", \"inputs\": [";
  for (size_t i = 0; i < c.in_sizes.size(); ++i) s += (i ? ", " : "") + std::to_string(c.in_sizes[i]);
  // Staged: which inputs go to NAME_prepare, and K (the drivers call NAME_prepare, then NAME).
  s += "], \"uniform\": [";
  for (size_t i = 0; i < c.is_uniform.size(); ++i) s += std::string(i ? ", " : "") + (c.is_uniform[i] ? "1" : "0");
  s += "], \"prepared\": " + std::to_string(c.prepared) + ", \"outputs\": [";
  for (size_t i = 0; i < c.out_sizes.size(); ++i) s += (i ? ", " : "") + std::to_string(c.out_sizes[i]);
  return s + "]}\n";
}

// ---- C-family glue: a call of NAME with inputs taken from a flat row `src` and outputs into `dst`.
// decl(type, name, n) declares an array; element(src, k) reads input value k.
struct CCall {
  std::string decls, call, copy_out;
};
// A staged case's call: NAME_prepare(uniform args, prepared) then NAME(prepared, per-element args, outputs).
// fn: the function as LANG spells it, with PREFIX before and SUFFIX after (a namespace, _f32).
CCall c_call(const Case& c, const std::string& T, const std::string& lang, const std::string& prefix,
             const std::string& suffix, const std::string& src, const std::string& dst, bool arrays_by_ref = false) {
  const std::string fn = prefix + spelt(c, lang, c.name) + suffix;
  CCall r;
  size_t off = 0;
  std::string args, uargs;
  for (size_t i = 0; i < c.in_sizes.size(); ++i) {
    std::string a;
    if (c.in_sizes[i] == 0) {
      a = "(" + T + ")" + src + "[" + std::to_string(off++) + "]";
    } else {
      std::string v = "in" + std::to_string(i);
      r.decls += "  " + T + " " + v + "[" + std::to_string(c.in_sizes[i]) + "];\n";
      r.decls += "  for (int k = 0; k < " + std::to_string(c.in_sizes[i]) + "; ++k) " + v + "[k] = (" + T + ")" +
                 src + "[" + std::to_string(off) + " + k];\n";
      off += c.in_sizes[i];
      a = (arrays_by_ref ? "&" : "") + v;
    }
    std::string& list = c.prepared && c.is_uniform[i] ? uargs : args;
    list += (list.empty() ? "" : ", ") + a;
  }
  std::string prepare;
  if (c.prepared) {
    r.decls += "  " + T + " prep[" + std::to_string(c.prepared) + "];\n";
    prepare = "  " + prefix + spelt(c, lang, c.name + "_prepare") + suffix + "(" + uargs + ", prep);\n";
    args = std::string(arrays_by_ref ? "&" : "") + "prep" + (args.empty() ? "" : ", ") + args;
  }
  off = 0;
  for (size_t i = 0; i < c.out_sizes.size(); ++i) {
    std::string v = "out" + std::to_string(i);
    r.decls += "  " + T + " " + v + "[" + std::to_string(c.out_sizes[i]) + "];\n";
    r.copy_out += "  for (int k = 0; k < " + std::to_string(c.out_sizes[i]) + "; ++k) " + dst + "[" +
                  std::to_string(off) + " + k] = " + v + "[k];\n";
    off += c.out_sizes[i];
    args += ", " + v;
  }
  r.call = prepare + "  " + fn + "(" + args + ");\n";
  return r;
}

// The C++ double kernel on n random inputs: nanoseconds per kernel call.
double cpp_bench(const Case& c, const std::string& gendir, const std::string& work, long n) {
  CCall k = c_call(c, "double", "cpp", "cga::kernels::", "", "a", "o");
  std::string src = "#include <chrono>\n#include <cstdio>\n#include <random>\n#include <vector>\n#include \"" + gendir +
                    "/" + c.name + ".hpp\"\n"
                    "int main() {\n  const long n = " + std::to_string(n) + ";\n"
                    "  std::vector<double> in(n * " + std::to_string(c.nin) + "), out(n * " + std::to_string(c.nout) +
                    ");\n  std::mt19937_64 g(1);\n  std::uniform_real_distribution<double> u(-1, 1);\n"
                    "  for (auto& v : in) v = u(g);\n  auto t0 = std::chrono::steady_clock::now();\n"
                    "  for (long i = 0; i < n; ++i) {\n  const double* a = &in[i * " + std::to_string(c.nin) + "];\n"
                    "  double* o = &out[i * " + std::to_string(c.nout) + "];\n" + k.decls + k.call + k.copy_out +
                    "  }\n  auto t1 = std::chrono::steady_clock::now();\n  double s = 0;\n  for (double v : out) s += v;\n"
                    "  std::printf(\"%.3f %g\\n\", std::chrono::duration<double, std::nano>(t1 - t0).count() / n, s);\n}\n";
  std::ofstream(work + "/bench_" + c.name + ".cpp") << src;
  std::string exe = work + "/bench_" + c.name;
  if (sh(std::string(CXX_COMPILER) + " -O2 -std=c++17 -o " + exe + " " + exe + ".cpp") != 0) return -1;
  if (sh(exe + " > " + exe + ".txt") != 0) return -1;
  return std::strtod(slurp(exe + ".txt").c_str(), nullptr);
}

void run_python(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    std::ofstream(base + ".json") << meta_json(c, "python");
    write_rows(base + ".in", c.inputs);
    std::string cmd = std::string(PYTHON) + " " + TARGETS_DIR + "/drive.py " + base + ".json " + gendir + "/" + c.name +
                      ".py " + base + ".in " + base + ".py64 " + base + ".py32 " + base + ".pyscalar";
    if (sh(cmd) != 0) {
      std::printf("FAIL %-20s python driver failed: %s\n", c.name.c_str(), cmd.c_str());
      ++failures;
      continue;
    }
    check(c, "numpy float64 arrays", base + ".py64", kTolDouble);
    check(c, "numpy float32 arrays", base + ".py32", kTolFloat);
    check(c, "python floats", base + ".pyscalar", kTolDouble, 50);
  }
  // Speed on 10^6 inputs: the NumPy kernel (one call on arrays) against the compiled C++ double kernel.
  for (const auto& c : cases) {
    if (c.name != "transform_point" && c.name != "motor_mul") continue;
    const long n = 1000000;
    std::string base = work + "/" + c.name;
    std::string cmd = std::string(PYTHON) + " " + TARGETS_DIR + "/drive.py --bench " + std::to_string(n) + " " +
                      base + ".json " + gendir + "/" + c.name + ".py > " + base + ".bench";
    double py = sh(cmd) == 0 ? std::strtod(slurp(base + ".bench").c_str(), nullptr) : -1;
    double cpp = cpp_bench(c, gendir, work, n);
    std::printf("speed %-20s %ld inputs: NumPy float64 %.1f ns/input, C++ double (-O2, one core) %.1f ns/input, "
                "ratio %.1fx\n", c.name.c_str(), n, py, cpp, cpp > 0 ? py / cpp : 0.0);
    if (py <= 0 || cpp <= 0) ++failures;
  }
}

void run_javascript(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    std::ofstream(base + ".json") << meta_json(c, "javascript");
    write_rows(base + ".in", c.inputs);
    std::string cmd = std::string(NODE) + " " + TARGETS_DIR + "/drive.mjs " + base + ".json " + gendir + "/" +
                      c.name + ".mjs " + base + ".in " + base + ".js64";
    if (sh(cmd) != 0) {
      std::printf("FAIL %-20s javascript driver failed: %s\n", c.name.c_str(), cmd.c_str());
      ++failures;
      continue;
    }
    check(c, "node (double)", base + ".js64", kTolDouble);
  }
}

// OpenCL: every script's emitted file plus wrapper kernels (one work item per row) in one program, built
// once and run by opencl_host.
void run_opencl(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  std::string src, args;
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    src += slurp(gendir + "/" + c.name + ".cl");
    for (std::string T : {"float", "double"}) {
      std::string suffix = T == "float" ? "_f32" : "_f64";
      CCall k = c_call(c, T, "opencl", "", suffix, "a", "o");
      src += std::string(T == "double" ? "\n#ifdef cl_khr_fp64\n" : "\n") + "__kernel void run_" + c.name + suffix +
             "(__global const " + T + "* in_all, __global " + T + "* out_all) {\n" +
             "  const size_t i = get_global_id(0);\n  __global const " + T + "* a = in_all + i * " +
             std::to_string(c.nin) + ";\n  __global " + T + "* o = out_all + i * " + std::to_string(c.nout) + ";\n" +
             k.decls + k.call + k.copy_out + "}\n" + (T == "double" ? "#endif\n" : "");
    }
    src += "\n";
    write_rows(base + ".in", c.inputs);
    args += " " + c.name + " " + std::to_string(c.nin) + " " + std::to_string(c.nout) + " " + base + ".in " + base +
            ".cl32 " + base + ".cl64";
  }
  std::ofstream(work + "/all.cl") << src;
  auto t0 = std::chrono::steady_clock::now();
  std::string cmd = std::string(OPENCL_HOST) + " " + work + "/all.cl" + args + " > " + work + "/device.txt";
  if (sh(cmd) != 0) {
    std::printf("FAIL opencl host failed: %s\n", cmd.c_str());
    ++failures;
    return;
  }
  std::printf("OpenCL build + runs in %.1f s on %s", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              slurp(work + "/device.txt").c_str());
  for (const auto& c : cases) {
    check(c, "opencl float", work + "/" + c.name + ".cl32", kTolFloat);
    check(c, "opencl double", work + "/" + c.name + ".cl64", kTolDouble);
  }
}

// HLSL: the emitted file plus a compute-shader wrapper (HLSL, one group per row, RWStructuredBuffers u0/u1)
// -> glslangValidator's HLSL front end (-D) to SPIR-V -> spirv-val -> spirv-cross to GLSL 4.50 -> run by
// gl_compute_runner on the headless GL 4.5 context (Mesa llvmpipe). Float only (HLSL's target precision).
void run_hlsl(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    CCall k = c_call(c, "float", "hlsl", "", "", "In", "Out");
    // c_call reads src[off + k]; make the row offset part of the buffer index.
    std::string body = k.decls + k.call + k.copy_out;
    auto replace_all = [](std::string s, const std::string& a, const std::string& b) {
      for (size_t p = 0; (p = s.find(a, p)) != std::string::npos; p += b.size()) s.replace(p, a.size(), b);
      return s;
    };
    body = replace_all(body, "In[", "In[row * " + std::to_string(c.nin) + " + ");
    body = replace_all(body, "Out[", "Out[row * " + std::to_string(c.nout) + " + ");
    std::string src = slurp(gendir + "/" + c.name + ".hlsl") +
                      "\nRWStructuredBuffer<float> In : register(u0);\nRWStructuredBuffer<float> Out : register(u1);\n"
                      "[numthreads(1, 1, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) {\n  uint row = id.x;\n" +
                      body + "}\n";
    std::ofstream(base + ".hlsl") << src;
    write_rows(base + ".in", c.inputs);
    std::string steps[] = {
        std::string(GLSLANG_VALIDATOR) + " -D -V -S comp -e main -o " + base + ".spv " + base + ".hlsl > " + base + ".log 2>&1",
        std::string(SPIRV_VAL) + " " + base + ".spv >> " + base + ".log 2>&1",
        std::string(SPIRV_CROSS) + " --version 450 --no-es --output " + base + ".comp " + base + ".spv >> " + base + ".log 2>&1",
        std::string(GL_RUNNER) + " " + base + ".comp " + std::to_string(c.nin) + " " + std::to_string(c.nout) + " " +
            base + ".in " + base + ".hl32 > " + base + ".device 2>> " + base + ".log"};
    if (!run_steps(c.name, steps, base + ".log")) continue;
    if (&c == &cases.front()) std::printf("HLSL -> SPIR-V (glslang -D, spirv-val ok) -> GLSL 4.50 (spirv-cross) on %s", slurp(base + ".device").c_str());
    check(c, "hlsl->spirv->gl float", base + ".hl32", kTolFloat);
  }
}

// cpp and cuda (tests/targets/names only; tests/kernels runs the bundled scripts): every script's header in
// one C++ program, run per script in float and double. cuda: the .cuh compiled by the host compiler with its
// qualifiers defined away (nvcc is not on the CI machine), which checks its names as C++ names.
void run_native(const std::vector<Case>& cases, const std::string& gendir, const std::string& work,
                const std::string& lang) {
  const std::string ext = emit::syntax(lang).extension;
  std::string src = "#include <cstdio>\n#include <cstdlib>\n#include <vector>\n";
  for (const auto& c : cases) src += "#include \"" + gendir + "/" + c.name + ext + "\"\n";
  std::string table;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    for (std::string T : {"float", "double"}) {
      CCall k = c_call(c, T, lang, "cga::kernels::", "", "a", "o");
      src += "static void run" + std::to_string(i) + "_" + T + "(const double* a, double* o) {\n" + k.decls + k.call +
             k.copy_out + "}\n";
    }
    table += "  {run" + std::to_string(i) + "_float, run" + std::to_string(i) + "_double, " + std::to_string(c.nin) +
             ", " + std::to_string(c.nout) + "},\n";
  }
  src += "struct K { void (*f)(const double*, double*); void (*d)(const double*, double*); int nin, nout; };\n"
         "static const K kernels[] = {\n" + table + "};\n"
         "int main(int, char** argv) {\n  const K& k = kernels[std::atoi(argv[1])];\n"
         "  const bool single = argv[2][0] == 'f';\n  std::vector<double> a(k.nin), o(k.nout);\n"
         "  while (true) {\n    for (auto& v : a) if (std::scanf(\"%lf\", &v) != 1) return 0;\n"
         "    (single ? k.f : k.d)(a.data(), o.data());\n"
         "    for (int j = 0; j < k.nout; ++j) std::printf(j ? \" %.17g\" : \"%.17g\", o[j]);\n"
         "    std::printf(\"\\n\");\n  }\n}\n";
  const std::string base = work + "/drive_" + lang;
  std::ofstream(base + ".cpp") << src;
  const std::string flags = lang == "cuda" ? " -x c++ -D__host__= -D__device__= -D__forceinline__=inline" : "";
  const std::string cmd = std::string(CXX_COMPILER) + " -std=c++17 -O0 -Wall -Werror" + flags + " -o " + base + " " +
                          base + ".cpp > " + base + ".log 2>&1";
  const bool built = sh(cmd) == 0;
  std::printf("%s (%s%s) %s\n%s", CXX_COMPILER, lang.c_str(), flags.c_str(), built ? "ok" : "FAILED",
              built ? "" : slurp(base + ".log").c_str());
  if (!built) {
    ++failures;
    return;
  }
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const std::string in = work + "/" + c.name + ".in";
    write_rows(in, c.inputs);
    for (std::string T : {"float", "double"}) {
      const std::string out = work + "/" + c.name + "." + lang + "." + T;
      if (sh(base + " " + std::to_string(i) + " " + T + " < " + in + " > " + out) != 0) {
        std::printf("FAIL %-20s %s driver failed (%s)\n", c.name.c_str(), lang.c_str(), T.c_str());
        ++failures;
        continue;
      }
      check(c, lang + " " + T, out, T == "float" ? kTolFloat : kTolDouble);
    }
  }
}

// simd: every script's NAME.simd.hpp in one driver (simd_driver.hpp), built once, run per case in every
// instruction set the build has and the CPU runs, with varied layouts and with broadcast inputs. `cross`:
// built for aarch64 (NEON, Highway's static target) by CROSS_CXX and run under QEMU_AARCH64.
void run_simd(const std::vector<Case>& cases, const std::string& gendir, const std::string& work, bool cross) {
  std::vector<targets::SimdCase> sc;
  std::string all;
  for (const auto& c : cases) {
    const std::string header = gendir + "/" + c.name + ".simd.hpp";
    all += "#include \"" + header + "\"\n";
    std::vector<bool> uniform = c.prepared ? c.is_uniform : std::vector<bool>(c.in_sizes.size(), false);
    sc.push_back({header, spelt(c, "simd", c.name), spelt(c, "simd", c.name + "_prepare"), c.in_sizes, uniform,
                  c.prepared, c.out_sizes});
  }
  // Re-included once per instruction set by Highway (no include guard).
  std::ofstream(work + "/all.simd.hpp") << all;
  const std::string base = work + "/drive_simd";
  // x86 targets this CPU cannot run are not compiled (each costs about a fifth of the driver's build, and code
  // that only compiles is not tested); the runtime's build compiles every one.
  const long long x86 = HWY_AVX3_DL | HWY_AVX3 | HWY_AVX2 | HWY_SSE4 | HWY_SSSE3;
  const long long not_run = cross ? 0 : x86 & ~static_cast<long long>(hwy::SupportedTargets());
  std::ofstream(base + ".cpp") << targets::simd_driver_source(sc, !cross, not_run);
  if (not_run) std::printf("not compiled (this CPU lacks them): Highway targets 0x%llx\n", not_run);
  std::string cmd, run;
  if (cross && (std::string(CROSS_CXX).find("NOTFOUND") != std::string::npos ||
                std::string(QEMU_AARCH64).find("NOTFOUND") != std::string::npos)) {
    std::printf("FAIL aarch64-linux-gnu-g++ or qemu-aarch64 not found (apt-get install g++-aarch64-linux-gnu "
                "qemu-user; scripts/setup.sh installs them)\n");
    ++failures;
    return;
  }
  if (cross) {
    // The cross compiler's sysroot has no /usr/include: Highway's headers (architecture-independent) by a link.
    fs::create_directories(work + "/include");
    fs::remove(work + "/include/hwy");
    fs::create_directory_symlink("/usr/include/hwy", work + "/include/hwy");
    cmd = std::string(CROSS_CXX) + " -std=c++17 -O1 -static -Wall -Wextra -Werror -I" + work + " -I" + work +
          "/include -o " + base + " " + base + ".cpp > " + base + ".log 2>&1";
    run = std::string(QEMU_AARCH64) + " " + base;
  } else {
    cmd = std::string(CXX_COMPILER) + " -std=c++17 -O1 -Wall -Wextra -Werror -I" + work + " -o " + base + " " +
          base + ".cpp -lhwy > " + base + ".log 2>&1";
    run = base;
  }
  const auto t0 = std::chrono::steady_clock::now();
  const bool built = sh(cmd) == 0;
  std::printf("%s %s in %.1f s\n%s", cross ? CROSS_CXX : CXX_COMPILER, built ? "ok" : "FAILED",
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              built ? "" : slurp(base + ".log").c_str());
  if (!built) {
    ++failures;
    return;
  }
  if (sh(run + " list > " + base + ".isa") != 0) {
    std::printf("FAIL the driver cannot list its instruction sets\n");
    ++failures;
    return;
  }
  std::vector<std::pair<std::string, std::string>> isas;  // bits, name
  std::istringstream list(slurp(base + ".isa"));
  for (std::string bits, name; list >> bits >> name;) isas.emplace_back(bits, name);
  std::printf("instruction sets:");
  for (const auto& [bits, name] : isas) std::printf(" %s", name.c_str());
  std::printf("\n");
  if (isas.empty()) ++failures;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    const std::string in = work + "/" + c.name + ".in";
    write_rows(in, c.inputs);
    for (const auto& [bits, name] : isas)
      for (const std::string mode : {"layouts", "broadcast"}) {
        const std::string out = work + "/" + c.name + "." + name + "." + mode;
        if (sh(run + " " + std::to_string(i) + " " + bits + " " + mode + " < " + in + " > " + out) != 0) {
          std::printf("FAIL %-20s simd driver failed (%s, %s)\n", c.name.c_str(), name.c_str(), mode.c_str());
          ++failures;
          continue;
        }
        if (mode == "layouts") {
          check(c, "simd " + name, out, kTolFloat);
        } else {  // every row is the first row's value
          Case first = c;
          first.expected.assign(c.expected.size(), c.expected.front());
          check(first, "simd " + name + " broadcast", out, kTolFloat);
        }
      }
  }
}

// glsl (tests/targets/names only; tests/gpu runs the bundled kernels): the file in a GLSL 4.30 compute shader,
// validated by glslang and run by gl_compute_runner on the headless GL 4.5 context.
void run_glsl(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  auto replace_all = [](std::string s, const std::string& a, const std::string& b) {
    for (size_t p = 0; (p = s.find(a, p)) != std::string::npos; p += b.size()) s.replace(p, a.size(), b);
    return s;
  };
  for (const auto& c : cases) {
    const std::string base = work + "/" + c.name;
    CCall k = c_call(c, "float", "glsl", "", "", "In", "Out");
    std::string body = replace_all(k.decls + k.call + k.copy_out, "(float)", "");
    body = replace_all(body, "In[", "In_.data[row * " + std::to_string(c.nin) + " + ");
    body = replace_all(body, "Out[", "Out_.data[row * " + std::to_string(c.nout) + " + ");
    std::ofstream(base + ".comp") << "#version 430\nlayout(local_size_x = 1) in;\n"
                                     "layout(std430, binding = 0) readonly buffer In { float data[]; } In_;\n"
                                     "layout(std430, binding = 1) buffer Out { float data[]; } Out_;\n"
                                  << slurp(gendir + "/" + c.name + ".glsl")
                                  << "\nvoid main() {\n  int row = int(gl_GlobalInvocationID.x);\n" << body << "}\n";
    write_rows(base + ".in", c.inputs);
    std::string steps[] = {
        std::string(GLSLANG_VALIDATOR) + " " + base + ".comp > " + base + ".log 2>&1",
        std::string(GL_RUNNER) + " " + base + ".comp " + std::to_string(c.nin) + " " + std::to_string(c.nout) + " " +
            base + ".in " + base + ".gl32 > " + base + ".device 2>> " + base + ".log"};
    if (!run_steps(c.name, steps, base + ".log")) continue;
    check(c, "glsl compute float", base + ".gl32", kTolFloat);
  }
}

// ---- Browser checks (wgsl, glsl-es): all scripts in one page (tests/targets/browser_harness.js), one
// Chromium launch per language, driven by browser_run.py. The GPU APIs run on SwiftShader, Chromium's CPU
// implementation: its timings are CPU emulation, printed as such, never GPU speed.
constexpr int kBrowserTimeout = 120;  // seconds; a hung browser fails the test instead of hanging it

std::string base64(const std::vector<float>& v) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = reinterpret_cast<const unsigned char*>(v.data());  // little-endian, as Float32Array reads it
  const size_t n = v.size() * sizeof(float);
  std::string out;
  for (size_t i = 0; i < n; i += 3) {
    unsigned x = b[i] << 16 | (i + 1 < n ? b[i + 1] << 8 : 0) | (i + 2 < n ? b[i + 2] : 0);
    out += abc[x >> 18 & 63];
    out += abc[x >> 12 & 63];
    out += i + 1 < n ? abc[x >> 6 & 63] : '=';
    out += i + 2 < n ? abc[x & 63] : '=';
  }
  return out;
}

std::vector<float> unbase64(const std::string& s) {
  std::string bytes;
  unsigned x = 0;
  int bits = 0;
  for (char ch : s) {
    int d = ch >= 'A' && ch <= 'Z' ? ch - 'A' : ch >= 'a' && ch <= 'z' ? ch - 'a' + 26
          : ch >= '0' && ch <= '9' ? ch - '0' + 52 : ch == '+' ? 62 : ch == '/' ? 63 : -1;
    if (d < 0) continue;  // '=' padding
    x = x << 6 | d;
    bits += 6;
    if (bits >= 8) bytes += static_cast<char>(x >> (bits -= 8) & 255);
  }
  std::vector<float> v(bytes.size() / sizeof(float));
  std::copy(bytes.begin(), bytes.begin() + v.size() * sizeof(float), reinterpret_cast<char*>(v.data()));
  return v;
}

// A JavaScript string literal; '<' escaped so that no "</script>" can end the page's script early.
std::string js_string(const std::string& s) {
  std::string out = "\"";
  char buf[8];
  for (unsigned char ch : s) {
    if (ch == '"' || ch == '\\') out += std::string("\\") + static_cast<char>(ch);
    else if (ch == '\n') out += "\\n";
    else if (ch < 0x20 || ch == '<') std::snprintf(buf, sizeof buf, "\\u%04x", ch), out += buf;
    else out += static_cast<char>(ch);
  }
  return out + "\"";
}

// Sine and cosine on the GPU APIs: WGSL and Vulkan (SwiftShader's, under both WebGPU and WebGL 2) promise
// only an absolute error <= 2^-11 on [-pi, pi], and SwiftShader uses that room (errors ~4e-4 seen), which a
// float tolerance of 1e-5 cannot hold. So a script that calls sin or cos runs twice: as emitted, held to
// 4 * 2^-11 (the API's bound, with room for the few products each value enters), and with sin/cos replaced
// by accurate float versions (Cephes' sinf/cosf: Cody-Waite reduction by pi/2, minimax polynomials on
// [-pi/4, pi/4], ~1 ulp) held to the usual 1e-5: the emitted code itself is checked at float precision.
constexpr double kTolGpuTrig = 4 * 0x1p-11;
const char* kSinCosWgsl =
    "fn cgagen_sincos(x: f32) -> vec2<f32> {  // (sin x, cos x)\n"
    "  let k = round(x * 0.63661977236758134);\n"
    "  let r = ((x - k * 1.5703125) - k * 4.837512969970703125e-4) - k * 7.54978995489188216e-8;\n"
    "  let z = r * r;\n"
    "  let s = r + r * z * (-1.6666654611e-1 + z * (8.3321608736e-3 + z * -1.9515295891e-4));\n"
    "  let c = 1.0 - 0.5 * z + z * z * (4.166664568298827e-2 + z * (-1.388731625493765e-3 + z * 2.443315711809948e-5));\n"
    "  let q = i32(k) & 3;\n"
    "  if (q == 0) { return vec2(s, c); }\n  if (q == 1) { return vec2(c, -s); }\n"
    "  if (q == 2) { return vec2(-s, -c); }\n  return vec2(-c, s);\n}\n"
    "fn cgagen_sin(x: f32) -> f32 { return cgagen_sincos(x).x; }\n"
    "fn cgagen_cos(x: f32) -> f32 { return cgagen_sincos(x).y; }\n";
const char* kSinCosEssl =
    "vec2 cgagen_sincos(float x) {  // (sin x, cos x)\n"
    "  float k = floor(x * 0.63661977236758134 + 0.5);\n"
    "  float r = ((x - k * 1.5703125) - k * 4.837512969970703125e-4) - k * 7.54978995489188216e-8;\n"
    "  float z = r * r;\n"
    "  float s = r + r * z * (-1.6666654611e-1 + z * (8.3321608736e-3 + z * -1.9515295891e-4));\n"
    "  float c = 1.0 - 0.5 * z + z * z * (4.166664568298827e-2 + z * (-1.388731625493765e-3 + z * 2.443315711809948e-5));\n"
    "  int q = int(k) & 3;\n"
    "  if (q == 0) return vec2(s, c);\n  if (q == 1) return vec2(c, -s);\n"
    "  if (q == 2) return vec2(-s, -c);\n  return vec2(-c, s);\n}\n"
    "float cgagen_sin(float x) { return cgagen_sincos(x).x; }\n"
    "float cgagen_cos(float x) { return cgagen_sincos(x).y; }\n";
const std::regex kSinCosCall("\\b(sin|cos)\\(");

// One kernel run in the page: a case, its whole shader, its tolerance and label.
struct BrowserRun {
  const Case* c;
  std::string id, code, what;
  double tol;
};

// Adds the runs of one script: as emitted, and (if it calls sin/cos) with accurate sin/cos, the second shader
// made by shader(definitions, code with sin/cos renamed).
template <class Shader>
void add_runs(std::vector<BrowserRun>& runs, const Case& c, const std::string& code, const std::string& what,
              const char* sincos, const Shader& shader) {
  if (!std::regex_search(code, kSinCosCall)) {
    runs.push_back({&c, c.name, shader("", code), what, kTolFloat});
    return;
  }
  runs.push_back({&c, c.name, shader("", code), what + " (API sin/cos)", kTolGpuTrig});
  runs.push_back({&c, c.name + "+sincos", shader(sincos, std::regex_replace(code, kSinCosCall, "cgagen_$1(")),
                  what + " (float sin/cos)", kTolFloat});
}

// Runs every shader in one page for `api` (webgpu or webgl2) and checks the outputs (rows in WORK/ID.EXT).
void run_browser(const std::string& api, const std::vector<BrowserRun>& runs, const std::string& work,
                 const std::string& ext) {
  // CGA_TEST_CHROMIUM overrides the configured path (the test targets/browser_missing_fails sets a bad one).
  const std::string chromium = std::getenv("CGA_TEST_CHROMIUM") ? std::getenv("CGA_TEST_CHROMIUM") : CHROMIUM;
  if (!fs::exists(chromium)) {
    std::printf("FAIL chromium-headless-shell not found (configured: %s). The %s checks run in headless\n"
                "     Chromium: install Debian's chromium-headless-shell (scripts/setup.sh does) and configure again.\n",
                chromium.c_str(), api.c_str());
    ++failures;
    return;
  }
  std::string page = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>cgagen " + api +
                     "</title></head><body>\n<script>\nconst CGAGEN_API = \"" + api + "\";\nconst CGAGEN_CASES = [\n";
  for (const auto& r : runs) {
    std::vector<float> in;
    for (const auto& row : r.c->inputs) in.insert(in.end(), row.begin(), row.end());  // floats already (see load)
    page += "{name: \"" + r.id + "\", rows: " + std::to_string(r.c->inputs.size()) + ", nin: " +
            std::to_string(r.c->nin) + ", nout: " + std::to_string(r.c->nout) + ",\n input: \"" + base64(in) +
            "\",\n code: " + js_string(r.code) + "},\n";
  }
  page += "];\n</script>\n<script>\n" + slurp(std::string(TARGETS_DIR) + "/browser_harness.js") + "</script>\n</body></html>\n";
  const std::string html = work + "/" + api + ".html", out = work + "/" + api + ".txt", err = work + "/" + api + ".err";
  std::ofstream(html) << page;
  fs::remove(out);
  auto t0 = std::chrono::steady_clock::now();
  int rc = sh(std::string(PYTHON) + " " + TARGETS_DIR + "/browser_run.py " + chromium + " " + api + " " + html + " " +
              out + " " + std::to_string(kBrowserTimeout) + " 2> " + err);
  double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0) {
    std::printf("FAIL %s in Chromium (%s): browser_run.py exit status %d after %.1f s:\n%s", api.c_str(), html.c_str(),
                rc, wall, slurp(err).c_str());
    ++failures;
    return;
  }
  std::map<std::string, std::string> result;  // run id -> its line
  std::istringstream lines(slurp(out));
  std::string line, device, total;
  while (std::getline(lines, line)) {
    std::istringstream ls(line);
    std::string kind, id;
    ls >> kind;
    if (kind == "device") device = line.substr(7);
    else if (kind == "total") ls >> total;
    else if (kind == "case" || kind == "fail") {
      ls >> id;
      result[id] = line;
      if (kind == "fail") {
        std::printf("FAIL %-20s %s: %s\n", id.c_str(), api.c_str(), line.substr(6 + id.size()).c_str());
        ++failures;
      }
    }
  }
  std::printf("%s in headless Chromium on %s\n  page %s ms, Chromium launch to exit %.1f s (SwiftShader: CPU emulation, "
              "not GPU speed)\n", api.c_str(), device.c_str(), total.c_str(), wall);
  for (const auto& r : runs) {
    const Case& c = *r.c;
    auto it = result.find(r.id);
    if (it == result.end()) {
      std::printf("FAIL %-20s %s: no result from the page\n", r.id.c_str(), r.what.c_str());
      ++failures;
      continue;
    }
    if (it->second.rfind("case ", 0) != 0) continue;  // a fail line, reported above
    std::istringstream ls(it->second);
    std::string kind, id, compile_ms, run_ms, data;
    ls >> kind >> id >> compile_ms >> run_ms >> data;
    std::vector<float> v = unbase64(data);
    std::vector<std::vector<double>> rows;
    for (size_t k = 0; c.nout && (k + 1) * c.nout <= v.size(); ++k)
      rows.emplace_back(v.begin() + k * c.nout, v.begin() + (k + 1) * c.nout);
    write_rows(work + "/" + r.id + "." + ext, rows);
    std::printf("time %-20s compile %s ms, %zu rows %s ms (SwiftShader CPU emulation)\n", r.id.c_str(),
                compile_ms.c_str(), c.inputs.size(), run_ms.c_str());
    check(c, r.what, work + "/" + r.id + "." + ext, r.tol);
  }
}

// The WebGL 2 vertex shader for case c around its GLSL ES `code` (functions `defs` first): reads row
// gl_VertexID of the R32F texture cgagen_in (nin wide), writes the outputs to vec4 varyings cgagen_r0.. (zero
// padded), which the page captures with transform feedback.
std::string webgl_vertex_shader(const Case& c, const std::string& defs, const std::string& code) {
  std::string vs = "#version 300 es\n" + (defs.empty() ? "" : "precision highp float;\n" + defs) + code +
                   "\nuniform highp sampler2D cgagen_in;\n";
  const size_t vec4s = (c.nout + 3) / 4;
  for (size_t i = 0; i < vec4s; ++i) vs += "out vec4 cgagen_r" + std::to_string(i) + ";\n";
  vs += "float cgagen_x(int k) { return texelFetch(cgagen_in, ivec2(k, gl_VertexID), 0).r; }\nvoid main() {\n";
  std::string args, uargs;
  size_t off = 0;
  for (size_t i = 0; i < c.in_sizes.size(); ++i) {
    const std::string n = std::to_string(c.in_sizes[i]), v = "cgagen_i" + std::to_string(i);
    std::string& list = c.prepared && c.is_uniform[i] ? uargs : args;
    if (c.in_sizes[i] == 0) {
      list += (list.empty() ? "" : ", ") + std::string("cgagen_x(") + std::to_string(off++) + ")";
      continue;
    }
    vs += "  float " + v + "[" + n + "];\n  for (int k = 0; k < " + n + "; ++k) " + v + "[k] = cgagen_x(" +
          std::to_string(off) + " + k);\n";
    off += c.in_sizes[i];
    list += (list.empty() ? "" : ", ") + v;
  }
  if (c.prepared) {  // staged: NAME_prepare, then NAME on its values
    vs += "  float cgagen_prep[" + std::to_string(c.prepared) + "];\n  " + spelt(c, "glsl-es", c.name + "_prepare") + "(" + uargs +
          ", cgagen_prep);\n";
    args = "cgagen_prep" + (args.empty() ? "" : ", " + args);
  }
  for (size_t i = 0; i < c.out_sizes.size(); ++i) {
    vs += "  float cgagen_o" + std::to_string(i) + "[" + std::to_string(c.out_sizes[i]) + "];\n";
    args += ", cgagen_o" + std::to_string(i);
  }
  vs += "  " + spelt(c, "glsl-es", c.name) + "(" + args + ");\n";
  for (size_t i = 0; i < vec4s; ++i) vs += "  cgagen_r" + std::to_string(i) + " = vec4(0.0);\n";
  for (size_t i = 0, g = 0; i < c.out_sizes.size(); ++i)
    for (size_t k = 0; k < c.out_sizes[i]; ++k, ++g)
      vs += "  cgagen_r" + std::to_string(g / 4) + "[" + std::to_string(g % 4) + "] = cgagen_o" + std::to_string(i) +
            "[" + std::to_string(k) + "];\n";
  vs += "  gl_Position = vec4(0.0);\n}\n";
  return vs;
}

// GLSL ES: each file, inside the WebGL 2 vertex shader above, checked by glslang (ES profile: `#version 300
// es`), then run in headless Chromium's WebGL 2: row gl_VertexID of an R32F texture in, the outputs out
// through vec4 varyings captured by transform feedback (WebGL 2 has no compute shaders). Also run in a
// `#version 310 es` compute wrapper (SSBOs 0/1, one group per row) on the headless GL 4.5 context, whose ES
// 3.1 compatibility compiles ES shaders with the ES rules (llvmpipe in CI). Float only.
void run_glsl_es(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  auto replace_all = [](std::string s, const std::string& a, const std::string& b) {
    for (size_t p = 0; (p = s.find(a, p)) != std::string::npos; p += b.size()) s.replace(p, a.size(), b);
    return s;
  };
  std::vector<BrowserRun> webgl;
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    std::string code = slurp(gendir + "/" + c.name + ".essl");
    auto vertex_shader = [&c](const std::string& defs, const std::string& text) {
      return webgl_vertex_shader(c, defs, text);
    };
    std::ofstream(base + ".vert") << vertex_shader("", code);
    add_runs(webgl, c, code, "glsl-es WebGL2 float", kSinCosEssl, vertex_shader);
    // The ES 3.10 compute wrapper for the desktop GL context.
    CCall k = c_call(c, "float", "glsl-es", "", "", "In", "Out");
    std::string body = replace_all(k.decls + k.call + k.copy_out, "(float)", "");
    body = replace_all(body, "In[", "In_.data[row * " + std::to_string(c.nin) + " + ");
    body = replace_all(body, "Out[", "Out_.data[row * " + std::to_string(c.nout) + " + ");
    std::ofstream(base + ".comp") << "#version 310 es\nlayout(local_size_x = 1) in;\n"
                                     "layout(std430, binding = 0) readonly buffer In { float data[]; } In_;\n"
                                     "layout(std430, binding = 1) buffer Out { float data[]; } Out_;\n"
                                  << code << "\nvoid main() {\n  int row = int(gl_GlobalInvocationID.x);\n" << body
                                  << "}\n";
    write_rows(base + ".in", c.inputs);
    std::string steps[] = {
        std::string(GLSLANG_VALIDATOR) + " " + base + ".vert > " + base + ".log 2>&1",
        std::string(GLSLANG_VALIDATOR) + " " + base + ".comp >> " + base + ".log 2>&1",
        std::string(GL_RUNNER) + " " + base + ".comp " + std::to_string(c.nin) + " " + std::to_string(c.nout) + " " +
            base + ".in " + base + ".es32 > " + base + ".device 2>> " + base + ".log"};
    if (!run_steps(c.name, steps, base + ".log")) continue;
    if (&c == &cases.front())
      std::printf("GLSL ES 3.00 (glslang, the WebGL 2 vertex shader) + ES 3.10 compute on %s", slurp(base + ".device").c_str());
    check(c, "glsl-es compute float", base + ".es32", kTolFloat);
  }
  run_browser("webgl2", webgl, work, "webgl32");
}

// WGSL: each file plus a compute entry point (storage buffers 0: inputs, 1: outputs, one thread per row) run
// in headless Chromium's WebGPU (Dawn on SwiftShader's Vulkan); Dawn's WGSL compiler (Tint) is the validator:
// its errors fail the script. f32 only: WGSL has no f64.
void run_wgsl(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  std::vector<BrowserRun> runs;
  for (const auto& c : cases) {
    const std::string fn = spelt(c, "wgsl", c.name);  // the emitter renames WGSL's reserved words
    std::string main = "\n@group(0) @binding(0) var<storage, read> cgagen_in: array<f32>;\n"
                       "@group(0) @binding(1) var<storage, read_write> cgagen_out: array<f32>;\n\n"
                       "@compute @workgroup_size(64)\nfn cgagen_main(@builtin(global_invocation_id) cgagen_id: vec3<u32>) {\n"
                       "  let cgagen_row = cgagen_id.x;\n  if (cgagen_row >= " + std::to_string(c.inputs.size()) +
                       "u) { return; }\n  let cgagen_a = cgagen_row * " + std::to_string(c.nin) +
                       "u;\n  let cgagen_b = cgagen_row * " + std::to_string(c.nout) + "u;\n";
    std::string args, uargs;
    size_t off = 0;
    for (size_t i = 0; i < c.in_sizes.size(); ++i) {
      const std::string n = std::to_string(c.in_sizes[i]), v = "cgagen_i" + std::to_string(i);
      std::string& list = c.prepared && c.is_uniform[i] ? uargs : args;
      if (c.in_sizes[i] == 0) {
        list += (list.empty() ? "" : ", ") + std::string("cgagen_in[cgagen_a + ") + std::to_string(off++) + "u]";
        continue;
      }
      main += "  var " + v + ": array<f32, " + n + ">;\n  for (var k = 0u; k < " + n + "u; k++) { " + v +
              "[k] = cgagen_in[cgagen_a + " + std::to_string(off) + "u + k]; }\n";
      off += c.in_sizes[i];
      list += (list.empty() ? "" : ", ") + v;
    }
    if (c.prepared) {  // staged: NAME_prepare, then NAME on its values
      main += "  var cgagen_prep: array<f32, " + std::to_string(c.prepared) + ">;\n  " +
              spelt(c, "wgsl", c.name + "_prepare") + "(" + uargs + ", &cgagen_prep);\n";
      args = "cgagen_prep" + (args.empty() ? "" : ", " + args);
    }
    std::string copy_out;
    off = 0;
    for (size_t i = 0; i < c.out_sizes.size(); ++i) {
      const std::string n = std::to_string(c.out_sizes[i]), v = "cgagen_o" + std::to_string(i);
      main += "  var " + v + ": array<f32, " + n + ">;\n";
      args += ", &" + v;
      copy_out += "  for (var k = 0u; k < " + n + "u; k++) { cgagen_out[cgagen_b + " + std::to_string(off) +
                  "u + k] = " + v + "[k]; }\n";
      off += c.out_sizes[i];
    }
    main += "  " + fn + "(" + args + ");\n" + copy_out + "}\n";
    auto shader = [&](const std::string& defs, const std::string& code) { return defs + code + main; };
    const std::string code = slurp(gendir + "/" + c.name + ".wgsl");
    std::ofstream(work + "/" + c.name + ".wgsl") << shader("", code);
    add_runs(runs, c, code, "wgsl WebGPU f32", kSinCosWgsl, shader);
  }
  run_browser("webgpu", runs, work, "wgsl32");
}

// LaTeX: pdflatex (nonstop, halt on error) must make a PDF from every emitted document.
void run_latex(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  for (const auto& c : cases) {
    std::string pdf = work + "/" + c.name + ".pdf";
    fs::remove(pdf);
    std::string cmd = std::string(PDFLATEX) + " -interaction=nonstopmode -halt-on-error -output-directory " + work +
                      " " + gendir + "/" + c.name + ".tex > " + work + "/" + c.name + ".out 2>&1";
    bool ok = sh(cmd) == 0 && fs::exists(pdf) && fs::file_size(pdf) > 1000;
    std::string log = slurp(work + "/" + c.name + ".log");
    size_t pages = log.find("Output written on");
    std::printf("%s %-20s pdflatex: %s\n", ok ? "ok  " : "FAIL", c.name.c_str(),
                pages == std::string::npos ? "no output" : log.substr(pages, log.find('\n', pages) - pages).c_str());
    failures += !ok;
  }
}

// dot: Graphviz must lay out every emitted graph, with one node per input blade, temporary and output blade.
void run_dot(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    std::string in = gendir + "/" + c.name + ".dot";
    bool ok = sh(std::string(DOT) + " -Tsvg -o " + base + ".svg " + in + " 2> " + base + ".err") == 0 &&
              sh(std::string(DOT) + " -Tplain -o " + base + ".plain " + in + " 2>> " + base + ".err") == 0;
    size_t nodes = 0, edges = 0;
    std::istringstream plain(slurp(base + ".plain"));
    std::string line;
    while (std::getline(plain, line)) {
      nodes += line.rfind("node ", 0) == 0;
      edges += line.rfind("edge ", 0) == 0;
    }
    size_t expected = c.prepared ? c.graph_nodes + c.prepared + c.nout : c.nin + c.prog.temps.size() + c.nout;
    ok &= nodes == expected && slurp(base + ".svg").find("<svg") != std::string::npos && slurp(base + ".err").empty();
    std::printf("%s %-20s dot: %zu nodes (expected %zu: inputs + temporaries + output blades), %zu edges\n",
                ok ? "ok  " : "FAIL", c.name.c_str(), nodes, expected, edges);
    failures += !ok;
  }
}

// Rust: one crate over every script's module (#[path]), one rustc run; `drive NAME f32|f64` reads rows on stdin.
// Outputs are copied by plain loops: a closure per output (the names scripts have about 50) took rustc minutes.
void run_rust(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  std::string src = "use std::io::{self, BufRead, Write};\n\n";
  // Modules and functions by index: a script's name may start with _ (a stem with a leading digit).
  for (size_t i = 0; i < cases.size(); ++i)
    src += "#[path = \"" + gendir + "/" + cases[i].name + ".rs\"]\nmod k" + std::to_string(i) + ";\n";
  for (size_t ci = 0; ci < cases.size(); ++ci) {
    const Case& c = cases[ci];
    const std::string mod = "k" + std::to_string(ci);
    src += "\nfn run" + std::to_string(ci) + "(single: bool, a: &[f64]) -> Vec<f64> {\n  let mut r = Vec::new();\n";
    for (std::string T : {"f32", "f64"}) {
      src += std::string(T == "f32" ? "  if single {\n" : "  } else {\n");
      std::string args, uargs;
      size_t off = 0;
      for (size_t i = 0; i < c.in_sizes.size(); ++i) {
        size_t n = c.in_sizes[i];
        std::string& list = c.prepared && c.is_uniform[i] ? uargs : args;
        if (n == 0) {
          list += (list.empty() ? "" : ", ") + std::string("a[") + std::to_string(off++) + "] as " + T;
          continue;
        }
        std::string v = "i" + std::to_string(i);
        src += "    let mut " + v + " = [0.0 as " + T + "; " + std::to_string(n) + "];\n    for k in 0.." +
               std::to_string(n) + " { " + v + "[k] = a[" + std::to_string(off) + " + k] as " + T + "; }\n";
        off += n;
        list += (list.empty() ? "" : ", ") + std::string("&") + v;
      }
      if (c.prepared) {  // staged: NAME_prepare, then NAME on its values
        src += "    let mut prep = [0.0 as " + T + "; " + std::to_string(c.prepared) + "];\n    " + mod +
               "::" + spelt(c, "rust", c.name + "_prepare") + "_" + T + "(" + uargs + ", &mut prep);\n";
        args = "&prep" + (args.empty() ? "" : ", " + args);
      }
      std::string outs;
      for (size_t i = 0; i < c.out_sizes.size(); ++i) {
        std::string v = "o" + std::to_string(i);
        src += "    let mut " + v + " = [0.0 as " + T + "; " + std::to_string(c.out_sizes[i]) + "];\n";
        args += ", &mut " + v;
        outs += "    for &x in " + v + ".iter() { r.push(x as f64); }\n";  // no closure type per output
      }
      src += "    " + mod + "::" + spelt(c, "rust", c.name) + "_" + T + "(" + args + ");\n" + outs;
    }
    src += "  }\n  r\n}\n";
  }
  src += "\nfn main() {\n  let args: Vec<String> = std::env::args().collect();\n  let single = args[2] == \"f32\";\n"
         "  let f: fn(bool, &[f64]) -> Vec<f64> = match args[1].as_str() {\n";
  for (size_t i = 0; i < cases.size(); ++i) src += "    \"" + cases[i].name + "\" => run" + std::to_string(i) + ",\n";
  src += "    _ => panic!(\"unknown kernel\"),\n  };\n  let stdin = io::stdin();\n"
         "  let mut out = io::BufWriter::new(io::stdout());\n  for line in stdin.lock().lines() {\n"
         "    let line = line.unwrap();\n    if line.is_empty() { continue; }\n"
         "    let a: Vec<f64> = line.split_whitespace().map(|s| s.parse().unwrap()).collect();\n"
         "    let v: Vec<String> = f(single, &a).iter().map(|x| format!(\"{:?}\", x)).collect();\n"
         "    writeln!(out, \"{}\", v.join(\" \")).unwrap();\n  }\n}\n";
  std::ofstream(work + "/drive.rs") << src;
  auto t0 = std::chrono::steady_clock::now();
  std::string cmd = std::string(RUSTC) + " --edition 2021 -C opt-level=1 -o " + work + "/drive " + work +
                    "/drive.rs 2> " + work + "/rustc.log";
  int rc = sh(cmd);
  std::string log = slurp(work + "/rustc.log");
  std::printf("rustc (%s) in %.1f s, %s\n%s", RUSTC, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count(),
              rc == 0 ? "ok" : "FAILED", log.c_str());
  if (log.find("warning") != std::string::npos) ++failures;  // the generated code compiles without warnings
  if (rc != 0) {
    ++failures;
    return;
  }
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    write_rows(base + ".in", c.inputs);
    for (std::string T : {"f32", "f64"}) {
      if (sh(work + "/drive " + c.name + " " + T + " < " + base + ".in > " + base + "." + T) != 0) {
        std::printf("FAIL %-20s rust driver failed (%s)\n", c.name.c_str(), T.c_str());
        ++failures;
        continue;
      }
      check(c, "rustc " + T, base + "." + T, T == "f32" ? kTolFloat : kTolDouble);
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: targets_check LANG GENDIR WORKDIR SCRIPT...\n");
    return 2;
  }
  std::string lang = argv[1], gendir = argv[2], work = argv[3];
  fs::create_directories(work);
  g_refdir = (fs::path(work).parent_path() / "reference").string();
  std::vector<Case> cases;
  auto t0 = std::chrono::steady_clock::now();
  const bool numeric = lang != "latex" && lang != "dot";  // those two are only compiled / laid out
  if (lang == "reference") fs::remove_all((fs::path(work).parent_path() / "reference"));
  for (int i = 4; i < argc; ++i) cases.push_back(load(argv[i], numeric));
  auto t1 = std::chrono::steady_clock::now();
  if (numeric)
    std::printf("%zu scripts, %d inputs each, reference (-O0, opt::evaluate; cached by targets/reference) in %.2f s\n", cases.size(), kSamples,
                std::chrono::duration<double>(t1 - t0).count());
  if (lang == "reference") {
    bool ok = true;
    for (const Case& c : cases) {
      const double d = oracle_disagreement(c);
      std::printf("reference %-22s vs the oracle interpreter on %zu inputs: max %.3g %s\n", c.name.c_str(), c.inputs.size(), d,
                  d <= 1e-9 ? "ok" : "FAIL");
      ok &= d <= 1e-9;
    }
    if (!ok) return 1;
  } else if (lang == "python") run_python(cases, gendir, work);
  else if (lang == "javascript") run_javascript(cases, gendir, work);
  else if (lang == "rust") run_rust(cases, gendir, work);
  else if (lang == "opencl") run_opencl(cases, gendir, work);
  else if (lang == "hlsl") run_hlsl(cases, gendir, work);
  else if (lang == "glsl-es") run_glsl_es(cases, gendir, work);
  else if (lang == "wgsl") run_wgsl(cases, gendir, work);
  else if (lang == "latex") run_latex(cases, gendir, work);
  else if (lang == "dot") run_dot(cases, gendir, work);
  else if (lang == "cpp" || lang == "cuda") run_native(cases, gendir, work, lang);
  else if (lang == "glsl") run_glsl(cases, gendir, work);
  else if (lang == "simd") run_simd(cases, gendir, work, false);
  else if (lang == "simd-aarch64") run_simd(cases, gendir, work, true);
  else {
    std::fprintf(stderr, "targets_check: no driver for %s\n", lang.c_str());
    return 2;
  }
  auto t2 = std::chrono::steady_clock::now();
  std::printf("%s: %s in %.2f s\n", lang.c_str(), failures ? "FAILED" : numeric ? "all outputs within tolerance" : "all files built",
              std::chrono::duration<double>(t2 - t1).count());
  return failures ? 1 : 0;
}
