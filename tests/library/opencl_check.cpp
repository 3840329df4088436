// opencl_check LIBRARY CL HOST WORK_DIR [COUNT]: a generated library's OpenCL C (cgagen --library --target
// opencl) built and run on the first OpenCL device (PoCL on the CPU) against the same library's C++ (which
// tests/library checks against the oracle). COUNT functions (default 150; 0: every function) are drawn with a
// fixed seed (check_sample.hpp), each on kRows seeded operand rows. The check appends to the library one kernel
// per function, run_cI_f32 and run_cI_f64, that loads a row into the operand structs, calls the library
// function LIBRARY_OP_A_B (and its _f64) and stores the result; HOST (tests/targets' opencl_host) builds it
// with -cl-std=CL1.2 -Werror and runs both precisions. Every value must agree with the C++ within
// 1e-4 (1 + |value|). Exit status 0 when all agree.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cga3.hpp"
#include "cga_rigid.hpp"
#include "check_sample.hpp"
#include "e3.hpp"
#include "pga3.hpp"

namespace {

constexpr size_t kRows = 16;

// One wrapper kernel: run_NAME_SUFFIX over rows of a's then b's coefficients.
std::string wrapper(const std::string& lib, const library_check::Case& c, const std::string& name,
                    const std::string& real, const std::string& suffix) {
  const std::string fn = lib + "_" + c.name + "_" + c.a + (c.arity == 2 ? "_" + c.b : "") + suffix;
  const std::string call = c.name == "matrix" ? lib + "_apply_" + c.a + "_" + c.b + suffix + "(" + fn + "(a), b);\n"
                                              : fn + (c.arity == 2 ? "(a, b);\n" : "(a);\n");
  const size_t n = c.na + c.nb;
  std::ostringstream s;
  s << "__kernel void run_" << name << (suffix.empty() ? "_f32" : suffix) << "(__global const " << real
    << "* in, __global " << real << "* out) {\n  const size_t i = get_global_id(0);\n";
  s << "  " << lib << "_" << c.a << suffix << " a;\n";
  s << "  for (int k = 0; k < " << c.na << "; ++k) a.v[k] = in[i * " << n << " + k];\n";
  if (c.arity == 2) {
    s << "  " << lib << "_" << c.b << suffix << " b;\n";
    s << "  for (int k = 0; k < " << c.nb << "; ++k) b.v[k] = in[i * " << n << " + " << c.na << " + k];\n";
  }
  s << "  const " << lib << "_" << c.result << suffix << " r = " << call;
  s << "  for (int k = 0; k < " << c.nr << "; ++k) out[i * " << c.nr << " + k] = r.v[k];\n}\n";
  return s.str();
}

std::vector<double> read_values(const std::string& path) {
  std::vector<double> v;
  std::ifstream in(path);
  for (std::string w; in >> w;) v.push_back(std::strtod(w.c_str(), nullptr));  // "inf" and "nan" too
  return v;
}

template <class TypeInfo, class FunctionInfo, class Matrices, size_t NT, size_t NF>
int check(const std::string& lib, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF], const Matrices& matrices,
          const std::string& cl,
          const std::string& host, const std::string& work, size_t count) {
  std::vector<library_check::Case> cases = library_check::sample("opencl_check", types, fns, count, kRows);
  if (cases.empty()) return 1;
  const size_t sampled = cases.size();
  for (auto& c : library_check::matrix_cases(types, matrices, kRows)) cases.push_back(std::move(c));
  const std::string base = work + "/" + lib;
  std::ostringstream program;
  program << std::ifstream(cl).rdbuf() << "\n// opencl_check's kernels\n";
  std::string args;
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    const std::string name = "c" + std::to_string(i), in = base + "." + name;
    program << wrapper(lib, c, name, "float", "") << "#ifdef cl_khr_fp64\n"
            << wrapper(lib, c, name, "double", "_f64") << "#endif\n";
    std::ofstream rows(in + ".in");
    char buf[64];
    const size_t n = c.na + c.nb;
    for (size_t row = 0; row < kRows; ++row) {
      for (size_t k = 0; k < n; ++k) {
        std::snprintf(buf, sizeof buf, "%s%.9g", k ? " " : "", static_cast<double>(c.x[row * n + k]));
        rows << buf;
      }
      rows << "\n";
    }
    args += " " + name + " " + std::to_string(n) + " " + std::to_string(c.nr) + " " + in + ".in " + in + ".f32 " +
            in + ".f64";
  }
  std::ofstream(base + "_check.cl") << program.str();
  const auto t0 = std::chrono::steady_clock::now();
  const std::string run = host + " " + base + "_check.cl" + args;
  if (std::system(run.c_str()) != 0) {
    std::fprintf(stderr, "opencl_check: %s_check.cl failed\n", base.c_str());
    return 1;
  }
  std::printf("opencl_check: %s: built and run in %.1f s\n", lib.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  std::vector<std::vector<double>> got(cases.size());
  std::vector<std::vector<std::string>> forms(cases.size(), {"float", "double"});
  double worst = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    const std::string in = base + ".c" + std::to_string(i);
    const std::vector<double> f32 = read_values(in + ".f32"), f64 = read_values(in + ".f64");
    if (f32.size() != kRows * c.nr || f64.size() != kRows * c.nr) continue;  // compare reports the count
    for (size_t row = 0; row < kRows; ++row)
      for (const auto* v : {&f32, &f64})
        for (size_t k = 0; k < c.nr; ++k) {
          const double g = (*v)[row * c.nr + k], w = c.want[row * c.nr + k];
          got[i].push_back(g);
          worst = std::max(worst, std::abs(g - w) / (1 + std::abs(w)));
        }
  }
  const int bad = library_check::compare("opencl_check", lib, cases, got, forms, kRows);
  std::printf("opencl_check: %s: %zu of %zu functions and %zu matrices run in OpenCL C (%zu rows each, float and "
              "double), %d values off, largest difference %.3g (1 + |value|)\n",
              lib.c_str(), sampled, NF, cases.size() - sampled, kRows, bad, worst);
  return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: opencl_check LIBRARY CL HOST WORK_DIR [COUNT]\n");
    return 2;
  }
  const std::string lib = argv[1];
  const size_t count = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 150;
  if (lib == "pga3") return check(lib, pga3::types, pga3::functions, pga3::matrices, argv[2], argv[3], argv[4], count);
  if (lib == "cga3") return check(lib, cga3::types, cga3::functions, cga3::matrices, argv[2], argv[3], argv[4], count);
  if (lib == "e3") return check(lib, e3::types, e3::functions, e3::matrices, argv[2], argv[3], argv[4], count);
  if (lib == "cga_rigid") return check(lib, cga_rigid::types, cga_rigid::functions, cga_rigid::matrices, argv[2], argv[3], argv[4], count);
  std::fprintf(stderr, "opencl_check: unknown library %s\n", lib.c_str());
  return 2;
}
