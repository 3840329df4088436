// glsl_check LIBRARY GLSL GL_RUNNER WORK_DIR [COUNT]: a generated library's GLSL (cgagen --library --target
// glsl) run on the headless GL context (gl_compute_runner: Mesa llvmpipe in CI) against the same library's
// C++ (which tests/library checks against the oracle). COUNT functions (default 150; 0: every function) are
// drawn with a fixed seed; each becomes one row of a compute shader that builds its operands from the input
// row, calls LIBRARY_OP(a, b) and writes the result's coefficients. Operands are seeded random coefficients
// in [-1, 1] (the same formula runs on both sides, so any operand does; inverse and normalize get operands
// away from a zero norm). Exit status 0 when every coefficient agrees within 1e-4 (1 + |value|).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cga3.hpp"
#include "cga_rigid.hpp"
#include "e3.hpp"
#include "pga3.hpp"

namespace {

std::string read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Blade k of type `name` ("" past its end).
template <class TypeInfo, size_t NT>
std::string types_blade(const TypeInfo (&types)[NT], const std::string& name, size_t k) {
  for (const auto& t : types)
    if (t.name == name && k < t.size) return std::string(t.blades[k]);
  return "";
}

template <class TypeInfo, class FunctionInfo, size_t NT, size_t NF>
int check(const std::string& lib, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF], const std::string& glsl,
          const std::string& runner, const std::string& work, size_t count) {
  std::map<std::string, size_t> size;
  for (const auto& t : types) size[std::string(t.name)] = t.size;
  std::vector<size_t> picked(NF);
  for (size_t i = 0; i < NF; ++i) picked[i] = i;
  std::mt19937 rng(20261128u);
  std::shuffle(picked.begin(), picked.end(), rng);
  if (count && count < NF) picked.resize(count);
  std::sort(picked.begin(), picked.end());
  size_t nin = 1, nout = 1;
  for (size_t i : picked) {
    const auto& f = fns[i];
    nin = std::max(nin, size[std::string(f.a)] + (f.arity == 2 ? size[std::string(f.b)] : 0));
    nout = std::max(nout, size[std::string(f.result)]);
  }
  std::uniform_int_distribution<int> d(-256, 256);
  std::vector<float> in(picked.size() * nin, 0.0f), want(picked.size() * nout, 0.0f);
  std::vector<std::string> cases;
  for (size_t row = 0; row < picked.size(); ++row) {
    const auto& f = fns[picked[row]];
    const std::string name(f.name), a(f.a), b(f.b), r(f.result);
    const size_t na = size[a], nb = f.arity == 2 ? size[b] : 0, nr = size[r];
    float* x = &in[row * nin];
    float* y = &want[row * nout];
    // Operands on which the C++ value is finite: inverse and normalize away from a zero norm, log near the
    // identity (a scalar blade near 1, small other blades: its domain is rotors and motors).
    bool finite = false;
    for (int tries = 0; tries < 100 && !finite; ++tries) {
      for (size_t k = 0; k < na + nb; ++k) x[k] = static_cast<float>(d(rng) / (name == "log" ? 1024.0 : 256.0));
      if (name == "log")
        for (size_t k = 0; k < na; ++k)
          if (types_blade(types, a, k) == "1") x[k] += 1.0f;
      if (name == "inverse" || name == "normalize") {
        std::vector<float> n(1, 0.0f);
        for (size_t j = 0; j < NF; ++j)  // the operand's norm_sqr, through the library itself
          if (std::string(fns[j].name) == "norm_sqr" && std::string(fns[j].a) == a) fns[j].unary(x, n.data());
        if (std::abs(n[0]) <= 0.25f) continue;
      }
      if (f.arity == 2) f.binary(x, x + na, y);
      else f.unary(x, y);
      finite = std::all_of(y, y + nr, [](float v) { return std::isfinite(v); });
    }
    if (!finite) {
      std::fprintf(stderr, "glsl_check: %s %s: no operand with a finite C++ value in 100 draws\n", lib.c_str(), name.c_str());
      return 1;
    }
    std::string c = "      " + lib + "_" + a + " a;\n";
    for (size_t k = 0; k < na; ++k) c += "      a.v[" + std::to_string(k) + "] = X(" + std::to_string(k) + ");\n";
    if (f.arity == 2) {
      c += "      " + lib + "_" + b + " b;\n";
      for (size_t k = 0; k < nb; ++k) c += "      b.v[" + std::to_string(k) + "] = X(" + std::to_string(na + k) + ");\n";
    }
    c += "      " + lib + "_" + r + " r = " + lib + "_" + name + (f.arity == 2 ? "(a, b);\n" : "(a);\n");
    c += "      for (int k = 0; k < " + std::to_string(nr) + "; ++k) Y(k) = r.v[k];\n";
    cases.push_back(c);
  }
  // Shaders of at most kChunk rows each: one with more than about 75 cases over this library miscompiled on
  // Mesa 22.3.6's llvmpipe (log of a translator gave -inf; the same case in a smaller shader is right).
  constexpr size_t kChunk = 32;
  const std::string library = read(glsl);
  std::vector<double> got;
  for (size_t first = 0; first < picked.size(); first += kChunk) {
    const size_t rows = std::min(kChunk, picked.size() - first);
    std::string body;
    for (size_t i = 0; i < rows; ++i) body += "    case " + std::to_string(i) + "u: {\n" + cases[first + i] + "    } break;\n";
    const std::string shader = "#version 450\n" + library +
                               "layout(local_size_x = 1) in;\n"
                               "layout(std430, binding = 0) readonly buffer In { float xin[]; };\n"
                               "layout(std430, binding = 1) writeonly buffer Out { float xout[]; };\n"
                               "#define X(k) xin[row * " + std::to_string(nin) + "u + uint(k)]\n"
                               "#define Y(k) xout[row * " + std::to_string(nout) + "u + uint(k)]\n"
                               "void main() {\n  uint row = gl_WorkGroupID.x;\n  switch (row) {\n" + body + "  }\n}\n";
    const std::string base = work + "/" + lib + "_" + std::to_string(first / kChunk);
    std::ofstream(base + ".comp") << shader;
    {
      std::ofstream fin(base + ".in");
      char buf[64];
      for (size_t i = first * nin; i < (first + rows) * nin; ++i) {
        std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(in[i]));
        fin << buf << ((i + 1) % nin ? " " : "\n");
      }
    }
    const std::string cmd = runner + " " + base + ".comp " + std::to_string(nin) + " " + std::to_string(nout) + " " +
                            base + ".in " + base + ".out > /dev/null";
    if (std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "glsl_check: %s failed (shader: %s.comp)\n", cmd.c_str(), base.c_str());
      return 1;
    }
    std::ifstream fout(base + ".out");
    for (std::string t; fout >> t;) got.push_back(std::strtod(t.c_str(), nullptr));  // "inf" and "nan" too
  }
  if (got.size() != want.size()) {
    std::fprintf(stderr, "glsl_check: %zu values back, %zu expected\n", got.size(), want.size());
    return 1;
  }
  int bad = 0;
  for (size_t row = 0; row < picked.size(); ++row) {
    const auto& f = fns[picked[row]];
    for (size_t k = 0; k < size[std::string(f.result)]; ++k) {
      const double w = want[row * nout + k], g = got[row * nout + k];
      if (!(std::abs(g - w) <= 1e-4 * (1 + std::abs(w)))) {
        if (bad++ < 20)
          std::fprintf(stderr, "glsl_check: %s %s(%.*s%s%.*s) coefficient %zu: GLSL %.9g, C++ %.9g\n", lib.c_str(),
                       std::string(f.name).c_str(), int(f.a.size()), f.a.data(), f.arity == 2 ? ", " : "",
                       int(f.b.size()), f.b.data(), k, g, w);
      }
    }
  }
  std::printf("glsl_check: %s: %zu of %zu functions run in GLSL, %d coefficients off\n", lib.c_str(), picked.size(), NF,
              bad);
  return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: glsl_check LIBRARY GLSL GL_RUNNER WORK_DIR [COUNT]\n");
    return 2;
  }
  const std::string lib = argv[1];
  const size_t count = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 150;
  if (lib == "pga3") return check(lib, pga3::types, pga3::functions, argv[2], argv[3], argv[4], count);
  if (lib == "cga3") return check(lib, cga3::types, cga3::functions, argv[2], argv[3], argv[4], count);
  if (lib == "e3") return check(lib, e3::types, e3::functions, argv[2], argv[3], argv[4], count);
  if (lib == "cga_rigid") return check(lib, cga_rigid::types, cga_rigid::functions, argv[2], argv[3], argv[4], count);
  std::fprintf(stderr, "glsl_check: unknown library %s\n", lib.c_str());
  return 2;
}
