// glsl_check LIBRARY GLSL GL_RUNNER WORK_DIR [COUNT [es | hlsl GLSLANG SPIRV_CROSS]]: a generated library's
// GLSL (cgagen --library --target glsl; with `es`, the GLSL ES of --target glsl-es, in GLSL ES 3.10 compute
// shaders; with `hlsl`, the HLSL of --target hlsl, in HLSL compute shaders that glslangValidator -D turns
// into SPIR-V and spirv-cross into GLSL 4.50) run on the headless GL context (gl_compute_runner: Mesa llvmpipe in CI) against the same library's
// C++ (which tests/library checks against the oracle). COUNT functions (default 150; 0: every function) are
// drawn with a fixed seed; each becomes one row of a compute shader that builds its operands from the input
// row, calls LIBRARY_OP(a, b) and writes the result's coefficients. The sample, the operands and the
// comparison are check_sample.hpp's, as for the Rust and Python checks. Every matrix of the library too
// (LIBRARY_apply(LIBRARY_matrix_B(a), b) against the C++ scalar matrix kernel's M(b)). Exit status 0 when
// every coefficient agrees within 1e-4 (1 + |value|).
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
#include "check_sample.hpp"

namespace {

std::string read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

template <class TypeInfo, class FunctionInfo, class Matrices, size_t NT, size_t NF>
int check(const std::string& lib, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF], const Matrices& matrices,
          const std::string& glsl, const std::string& runner, const std::string& work, size_t count,
          const std::vector<std::string>& mode) {
  const std::string& kind = mode[0];
  const std::string library = read(glsl);
  // A type's name as the file spells it: HLSL's reserved words (line) get a trailing _.
  auto type = [&](const std::string& t) {
    return library.find("struct " + lib + "_" + t + " {") != std::string::npos ? lib + "_" + t : lib + "_" + t + "_";
  };
  std::vector<library_check::Case> picked = library_check::sample("glsl_check", types, fns, count, 1);
  if (picked.empty()) return 1;
  const size_t sampled = picked.size();
  for (auto& c : library_check::matrix_cases(types, matrices, 1)) picked.push_back(std::move(c));
  size_t nin = 1, nout = 1;
  for (const auto& c : picked) nin = std::max(nin, c.na + c.nb), nout = std::max(nout, c.nr);
  // One row per function: its operands in the input row, its result in the output row.
  std::vector<float> in(picked.size() * nin, 0.0f);
  std::vector<std::string> cases;
  for (size_t row = 0; row < picked.size(); ++row) {
    const library_check::Case& f = picked[row];
    std::copy(f.x.begin(), f.x.end(), in.begin() + static_cast<long>(row * nin));
    std::string c = "      " + type(f.a) + " a;\n";
    for (size_t k = 0; k < f.na; ++k) c += "      a.v[" + std::to_string(k) + "] = X(" + std::to_string(k) + ");\n";
    if (f.arity == 2) {
      c += "      " + type(f.b) + " b;\n";
      for (size_t k = 0; k < f.nb; ++k) c += "      b.v[" + std::to_string(k) + "] = X(" + std::to_string(f.na + k) + ");\n";
    }
    if (f.name == "matrix")
      c += "      " + type(f.result) + " r = " + lib + "_apply(" + lib + "_matrix_" + type(f.b).substr(lib.size() + 1) + "(a), b);\n";
    else
      c += "      " + type(f.result) + " r = " + lib + "_" + f.name + (f.arity == 2 ? "(a, b);\n" : "(a);\n");
    c += "      for (int k = 0; k < " + std::to_string(f.nr) + "; ++k) Y(k) = r.v[k];\n";
    cases.push_back(c);
  }
  // Shaders of at most kChunk rows each: one with more than about 75 cases over this library miscompiled on
  // Mesa 22.3.6's llvmpipe (log of a translator gave -inf; the same case in a smaller shader is right).
  constexpr size_t kChunk = 32;
  std::vector<double> got;
  for (size_t first = 0; first < picked.size(); first += kChunk) {
    const size_t rows = std::min(kChunk, picked.size() - first);
    std::string body;
    for (size_t i = 0; i < rows; ++i) body += "    case " + std::to_string(i) + "u: {\n" + cases[first + i] + "    } break;\n";
    const std::string sizes = "#define X(k) xin[row * " + std::to_string(nin) + "u + uint(k)]\n" +
                              "#define Y(k) xout[row * " + std::to_string(nout) + "u + uint(k)]\n";
    const std::string cases_switch = "  switch (row) {\n" + body + "  }\n}\n";
    const std::string shader =
        kind == "hlsl" ? library + "RWStructuredBuffer<float> xin : register(u0);\n"
                                   "RWStructuredBuffer<float> xout : register(u1);\n" + sizes +
                             "[numthreads(1, 1, 1)]\nvoid main(uint3 id : SV_DispatchThreadID) {\n  uint row = id.x;\n" +
                             cases_switch
                       : (kind == "es" ? "#version 310 es\n" : "#version 450\n") + library +
                             "layout(local_size_x = 1) in;\n"
                             "layout(std430, binding = 0) readonly buffer In { float xin[]; };\n"
                             "layout(std430, binding = 1) writeonly buffer Out { float xout[]; };\n" + sizes +
                             "void main() {\n  uint row = gl_WorkGroupID.x;\n" + cases_switch;
    const std::string base =
        work + "/" + lib + (kind == "glsl" ? "_" : "_" + kind + "_") + std::to_string(first / kChunk);
    std::string cmd;
    if (kind == "hlsl") {
      std::ofstream(base + ".hlsl") << shader;
      cmd = mode[1] + " -D -V -S comp -e main -o " + base + ".spv " + base + ".hlsl > " + base + ".log && " + mode[2] +
            " --version 450 --no-es --output " + base + ".comp " + base + ".spv && ";
    } else {
      std::ofstream(base + ".comp") << shader;
    }
    {
      std::ofstream fin(base + ".in");
      char buf[64];
      for (size_t i = first * nin; i < (first + rows) * nin; ++i) {
        std::snprintf(buf, sizeof buf, "%.9g", static_cast<double>(in[i]));
        fin << buf << ((i + 1) % nin ? " " : "\n");
      }
    }
    cmd += runner + " " + base + ".comp " + std::to_string(nin) + " " + std::to_string(nout) + " " + base + ".in " +
           base + ".out > /dev/null";
    if (std::system(cmd.c_str()) != 0) {
      std::fprintf(stderr, "glsl_check: %s failed (shader: %s.comp)\n", cmd.c_str(), base.c_str());
      return 1;
    }
    std::ifstream fout(base + ".out");
    for (std::string t; fout >> t;) got.push_back(std::strtod(t.c_str(), nullptr));  // "inf" and "nan" too
  }
  // The rows back as one result per case (outputs are padded to the widest result).
  if (got.size() != picked.size() * nout) {
    std::fprintf(stderr, "glsl_check: %zu values back, %zu expected\n", got.size(), picked.size() * nout);
    return 1;
  }
  std::vector<std::vector<double>> per_case;
  std::vector<std::vector<std::string>> forms;
  for (size_t row = 0; row < picked.size(); ++row) {
    per_case.emplace_back(got.begin() + static_cast<long>(row * nout), got.begin() + static_cast<long>(row * nout + picked[row].nr));
    forms.push_back({"GLSL"});
  }
  const int bad = library_check::compare("glsl_check", lib, picked, per_case, forms, 1);
  std::printf("glsl_check: %s: %zu of %zu functions and %zu matrices run in %s, %d coefficients off\n", lib.c_str(),
              sampled, NF, picked.size() - sampled, kind == "glsl" ? "GLSL" : kind == "es" ? "GLSL ES" : "HLSL", bad);
  return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: glsl_check LIBRARY GLSL GL_RUNNER WORK_DIR [COUNT [es | hlsl GLSLANG SPIRV_CROSS]]\n");
    return 2;
  }
  const std::string lib = argv[1];
  const size_t count = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 150;
  std::vector<std::string> mode{argc > 6 ? argv[6] : "glsl"};
  for (int i = 7; i < argc; ++i) mode.emplace_back(argv[i]);
  if ((mode[0] != "glsl" && mode[0] != "es" && mode[0] != "hlsl") || (mode[0] == "hlsl" && mode.size() != 3)) {
    std::fprintf(stderr, "usage: glsl_check LIBRARY GLSL GL_RUNNER WORK_DIR [COUNT [es | hlsl GLSLANG SPIRV_CROSS]]\n");
    return 2;
  }
  if (lib == "pga3") return check(lib, pga3::types, pga3::functions, pga3::matrices, argv[2], argv[3], argv[4], count, mode);
  if (lib == "cga3") return check(lib, cga3::types, cga3::functions, cga3::matrices, argv[2], argv[3], argv[4], count, mode);
  if (lib == "e3") return check(lib, e3::types, e3::functions, e3::matrices, argv[2], argv[3], argv[4], count, mode);
  if (lib == "cga_rigid")
    return check(lib, cga_rigid::types, cga_rigid::functions, cga_rigid::matrices, argv[2], argv[3], argv[4], count, mode);
  std::fprintf(stderr, "glsl_check: unknown library %s\n", lib.c_str());
  return 2;
}
