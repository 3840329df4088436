// targets_check LANG GENDIR WORKDIR SCRIPT...: runs the kernels cgagen emitted for LANG (GENDIR/NAME<ext>,
// made by cgagen_generate() at build time) on random inputs with the language's own compiler or
// interpreter, and compares every output blade with the reference.
//
// Reference: the script's -O0 program (its statements as written, no optimizer) evaluated in double by
// opt::evaluate, the evaluator behind `cgagen --eval`. The compiled C++ kernels are held to the dense R(4,1)
// oracle by tests/kernels, and `--eval` to the compiled kernels; the targets here print the -O2 program,
// so an optimizer or printer fault in any language shows up as a difference.
//
// Inputs: uniform in [-1, 1], rounded to float (the same values go to float and double code). Samples at
// which the script is ill-conditioned are redrawn: each input is perturbed by a relative 2^-20 and the sample
// is kept only if no output moves by more than 1e-5 of its scale (an amplification <= ~10), and if every
// reference value is finite. Error of one blade: |got - ref| / max(1, max |ref| over that output's blades),
// i.e. relative to the output's size, absolute below 1. Tolerances: 1e-5 in float, 1e-12 in double.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "emit/emit.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"

using namespace cgagen;
namespace fs = std::filesystem;

namespace {

constexpr int kSamples = 1000;
constexpr double kTolFloat = 1e-5, kTolDouble = 1e-12;
std::string g_refdir;  // WORKDIR/../reference

struct Case {
  std::string name, path;
  opt::Program prog;  // -O2: the interface the targets print
  opt::Program ref;   // -O0: the reference
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

Case load(const std::string& path, bool numeric) {
  Case c;
  c.path = path;
  c.name = fs::path(path).stem().string();
  front::SourceFile file = front::SourceFile::load(path);
  Kernel k = expand(front::parse(file), c.name);
  c.prog = opt::optimize(k, opt::Level::O2);
  c.ref = opt::optimize(k, opt::Level::O0);
  for (const auto& in : c.prog.inputs) {
    c.in_sizes.push_back(in.is_multivector ? in.symbols.size() : 0);
    c.nin += in.is_multivector ? in.symbols.size() : 1;
  }
  for (const auto& o : c.prog.outputs) {
    c.out_sizes.push_back(o.slots.size());
    c.nout += o.slots.size();
  }
  // The reference is computed once per build (ctest fixture targets/reference) and read by every language.
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
  while (numeric && static_cast<int>(c.inputs.size()) < kSamples) {
    if (++attempts > 50 * kSamples) throw std::runtime_error(c.name + ": too few well-conditioned samples");
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

std::string meta_json(const Case& c) {
  std::string s = "{\"name\": \"" + c.name + "\", \"inputs\": [";
  for (size_t i = 0; i < c.in_sizes.size(); ++i) s += (i ? ", " : "") + std::to_string(c.in_sizes[i]);
  s += "], \"outputs\": [";
  for (size_t i = 0; i < c.out_sizes.size(); ++i) s += (i ? ", " : "") + std::to_string(c.out_sizes[i]);
  return s + "]}\n";
}

// ---- C-family glue: a call of NAME with inputs taken from a flat row `src` and outputs into `dst`.
// decl(type, name, n) declares an array; element(src, k) reads input value k.
struct CCall {
  std::string decls, call, copy_out;
};
CCall c_call(const Case& c, const std::string& T, const std::string& fn, const std::string& src,
             const std::string& dst, bool arrays_by_ref = false) {
  CCall r;
  size_t off = 0;
  std::string args;
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
    args += (args.empty() ? "" : ", ") + a;
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
  r.call = "  " + fn + "(" + args + ");\n";
  return r;
}

// The C++ double kernel on n random inputs: nanoseconds per kernel call.
double cpp_bench(const Case& c, const std::string& gendir, const std::string& work, long n) {
  CCall k = c_call(c, "double", "cga::kernels::" + c.name, "a", "o");
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
    std::ofstream(base + ".json") << meta_json(c);
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
    std::ofstream(base + ".json") << meta_json(c);
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
      CCall k = c_call(c, T, c.name + suffix, "a", "o");
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
    CCall k = c_call(c, "float", c.name, "In", "Out");
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

// GLSL ES: each file checked by glslang as a `#version 300 es` vertex shader (the WebGL 2 level), then run in a
// `#version 310 es` compute wrapper (SSBOs 0/1, one group per row) on the headless GL 4.5 context, whose
// ES 3.1 compatibility compiles ES shaders with the ES rules (llvmpipe in CI). Float only.
void run_glsl_es(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  auto replace_all = [](std::string s, const std::string& a, const std::string& b) {
    for (size_t p = 0; (p = s.find(a, p)) != std::string::npos; p += b.size()) s.replace(p, a.size(), b);
    return s;
  };
  for (const auto& c : cases) {
    std::string base = work + "/" + c.name;
    std::string code = slurp(gendir + "/" + c.name + ".essl");
    std::ofstream(base + ".vert") << "#version 300 es\n" << code << "\nvoid main() { gl_Position = vec4(0.0); }\n";
    CCall k = c_call(c, "float", c.name, "In", "Out");
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
      std::printf("GLSL ES 3.00 (glslang, vertex) + ES 3.10 compute on %s", slurp(base + ".device").c_str());
    check(c, "glsl-es compute float", base + ".es32", kTolFloat);
  }
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
    size_t expected = c.nin + c.prog.temps.size() + c.nout;
    ok &= nodes == expected && slurp(base + ".svg").find("<svg") != std::string::npos && slurp(base + ".err").empty();
    std::printf("%s %-20s dot: %zu nodes (expected %zu: inputs + temporaries + output blades), %zu edges\n",
                ok ? "ok  " : "FAIL", c.name.c_str(), nodes, expected, edges);
    failures += !ok;
  }
}

// Rust: one crate over every script's module (#[path]), one rustc run; `drive NAME f32|f64` reads rows on stdin.
void run_rust(const std::vector<Case>& cases, const std::string& gendir, const std::string& work) {
  std::string src = "use std::io::{self, BufRead, Write};\n\n";
  for (const auto& c : cases) src += "#[path = \"" + gendir + "/" + c.name + ".rs\"]\nmod k_" + c.name + ";\n";
  for (const auto& c : cases) {
    src += "\nfn run_" + c.name + "(single: bool, a: &[f64]) -> Vec<f64> {\n  let mut r = Vec::new();\n";
    for (std::string T : {"f32", "f64"}) {
      src += std::string(T == "f32" ? "  if single {\n" : "  } else {\n");
      std::string args;
      size_t off = 0;
      for (size_t i = 0; i < c.in_sizes.size(); ++i) {
        size_t n = c.in_sizes[i];
        if (n == 0) {
          args += (args.empty() ? "" : ", ") + std::string("a[") + std::to_string(off++) + "] as " + T;
          continue;
        }
        std::string v = "i" + std::to_string(i);
        src += "    let mut " + v + " = [0.0 as " + T + "; " + std::to_string(n) + "];\n    for k in 0.." +
               std::to_string(n) + " { " + v + "[k] = a[" + std::to_string(off) + " + k] as " + T + "; }\n";
        off += n;
        args += (args.empty() ? "" : ", ") + std::string("&") + v;
      }
      std::string outs;
      for (size_t i = 0; i < c.out_sizes.size(); ++i) {
        std::string v = "o" + std::to_string(i);
        src += "    let mut " + v + " = [0.0 as " + T + "; " + std::to_string(c.out_sizes[i]) + "];\n";
        args += ", &mut " + v;
        outs += "    r.extend(" + v + ".iter().map(|&v| v as f64));\n";
      }
      src += "    k_" + c.name + "::" + c.name + "_" + T + "(" + args + ");\n" + outs;
    }
    src += "  }\n  r\n}\n";
  }
  src += "\nfn main() {\n  let args: Vec<String> = std::env::args().collect();\n  let single = args[2] == \"f32\";\n"
         "  let f: fn(bool, &[f64]) -> Vec<f64> = match args[1].as_str() {\n";
  for (const auto& c : cases) src += "    \"" + c.name + "\" => run_" + c.name + ",\n";
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
  } else if (lang == "python") run_python(cases, gendir, work);
  else if (lang == "javascript") run_javascript(cases, gendir, work);
  else if (lang == "rust") run_rust(cases, gendir, work);
  else if (lang == "opencl") run_opencl(cases, gendir, work);
  else if (lang == "hlsl") run_hlsl(cases, gendir, work);
  else if (lang == "glsl-es") run_glsl_es(cases, gendir, work);
  else if (lang == "latex") run_latex(cases, gendir, work);
  else if (lang == "dot") run_dot(cases, gendir, work);
  else {
    std::fprintf(stderr, "targets_check: no driver for %s\n", lang.c_str());
    return 2;
  }
  auto t2 = std::chrono::steady_clock::now();
  std::printf("%s: %s in %.2f s\n", lang.c_str(), failures ? "FAILED" : numeric ? "all outputs within tolerance" : "all files built",
              std::chrono::duration<double>(t2 - t1).count());
  return failures ? 1 : 0;
}
