// js_check LIBRARY MJS NODE RUNNER WORK_DIR [COUNT]: a generated library's JavaScript (cgagen --library --target
// javascript) run by node against the same library's C++ (which tests/library checks against the oracle). COUNT
// functions (default 150; 0: every function) are drawn with a fixed seed (check_sample.hpp), each on kRows
// seeded operand rows; RUNNER (js_check.mjs) evaluates each function on each row as ops.OP, as the method and
// as the exported kernel. Every value must agree with the C++ within 1e-4 (1 + |value|). Exit status 0 when all
// agree.
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

template <class TypeInfo, class FunctionInfo, class Matrices, size_t NT, size_t NF>
int check(const std::string& lib, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF], const Matrices& matrices,
          const std::string& mjs,
          const std::string& node, const std::string& runner, const std::string& work, size_t count) {
  std::vector<library_check::Case> cases = library_check::sample("js_check", types, fns, count, kRows);
  if (cases.empty()) return 1;
  const size_t sampled = cases.size();
  for (auto& c : library_check::matrix_cases(types, matrices, kRows)) cases.push_back(std::move(c));
  const std::string base = work + "/" + lib;
  {
    std::ofstream in(base + ".in");
    char buf[64];
    for (const auto& c : cases) {
      in << "case " << c.name << " " << c.a << " " << (c.arity == 2 ? c.b : "-") << " " << c.result << " " << kRows
         << "\n";
      for (size_t row = 0; row < kRows; ++row) {
        const size_t n = c.na + c.nb;
        for (size_t k = 0; k < n; ++k) {
          std::snprintf(buf, sizeof buf, "%s%.9g", k ? " " : "", static_cast<double>(c.x[row * n + k]));
          in << buf;
        }
        in << "\n";
      }
    }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string run = node + " " + runner + " " + mjs + " " + base + ".in " + base + ".out";
  if (std::system(run.c_str()) != 0) {
    std::fprintf(stderr, "js_check: %s failed\n", run.c_str());
    return 1;
  }
  std::printf("js_check: %s: node in %.1f s\n", lib.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  std::vector<std::vector<double>> got(cases.size());
  std::vector<std::vector<std::string>> forms(cases.size());
  std::ifstream out(base + ".out");
  std::string line;
  for (size_t i = 0; i < cases.size() && std::getline(out, line); ++i) {
    std::istringstream header(line);
    std::string word;
    header >> word;  // "forms"
    while (header >> word) forms[i].push_back(word);
    for (size_t row = 0; row < kRows && std::getline(out, line); ++row) {
      std::istringstream words(line);
      for (std::string w; words >> w;) got[i].push_back(std::strtod(w.c_str(), nullptr));  // "inf" and "nan" too
    }
  }
  const int bad = library_check::compare("js_check", lib, cases, got, forms, kRows);
  double worst = 0;
  for (size_t i = 0; i < cases.size(); ++i)
    for (size_t k = 0; k < got[i].size() && got[i].size() == kRows * forms[i].size() * cases[i].nr; ++k) {
      const double w = cases[i].want[(k / (forms[i].size() * cases[i].nr)) * cases[i].nr + k % cases[i].nr];
      worst = std::max(worst, std::abs(got[i][k] - w) / (1 + std::abs(w)));
    }
  std::printf("js_check: %s: %zu of %zu functions and %zu matrices run in JavaScript (%zu rows each), %d values "
              "off, largest difference %.3g (1 + |value|)\n",
              lib.c_str(), sampled, NF, cases.size() - sampled, kRows, bad, worst);
  return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 6) {
    std::fprintf(stderr, "usage: js_check LIBRARY MJS NODE RUNNER WORK_DIR [COUNT]\n");
    return 2;
  }
  const std::string lib = argv[1];
  const size_t count = argc > 6 ? std::strtoul(argv[6], nullptr, 10) : 150;
  if (lib == "pga3") return check(lib, pga3::types, pga3::functions, pga3::matrices, argv[2], argv[3], argv[4], argv[5], count);
  if (lib == "cga3") return check(lib, cga3::types, cga3::functions, cga3::matrices, argv[2], argv[3], argv[4], argv[5], count);
  if (lib == "e3") return check(lib, e3::types, e3::functions, e3::matrices, argv[2], argv[3], argv[4], argv[5], count);
  if (lib == "cga_rigid")
    return check(lib, cga_rigid::types, cga_rigid::functions, cga_rigid::matrices, argv[2], argv[3], argv[4], argv[5], count);
  std::fprintf(stderr, "js_check: unknown library %s\n", lib.c_str());
  return 2;
}
