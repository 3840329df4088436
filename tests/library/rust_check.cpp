// rust_check LIBRARY RS RUSTC WORK_DIR [COUNT]: a generated library's Rust (cgagen --library --target rust)
// compiled by rustc and run against the same library's C++ (which tests/library checks against the oracle).
// COUNT functions (default 150; 0: every function) are drawn with a fixed seed (check_sample.hpp), each on
// kRows seeded operand rows. The driver written here includes the library as a module and calls each function
// every way the Rust library offers it: the free function OP_A_B(&a, &b), the method a.OP() of a unary
// operation, and the std::ops operator where the operation has one; each must agree with the C++ within
// 1e-4 (1 + |value|). rustc must not warn about the library. Exit status 0 when all agree.
#include <chrono>
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

constexpr size_t kRows = 4;

std::string read(const std::string& path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// The Rust operator of an operation, where the library gives it one ("" otherwise; ~ reverse has none).
std::string rust_operator(const std::string& op) {
  if (op == "gp") return "*";
  if (op == "outer") return "^";
  if (op == "inner") return "|";
  if (op == "rp") return "&";
  if (op == "add") return "+";
  if (op == "sub" || op == "neg") return "-";
  if (op == "dual") return "!";
  return "";
}

// The forms a case is called in, in the order the driver writes them.
std::vector<std::string> forms(const library_check::Case& c) {
  if (c.name == "matrix") return {"apply", "operator *"};
  std::vector<std::string> f = {"function"};
  if (c.arity == 1) f.push_back("method");
  if (!rust_operator(c.name).empty()) f.push_back("operator " + rust_operator(c.name));
  return f;
}

std::string driver(const std::string& lib, const std::string& rs, const std::vector<library_check::Case>& cases) {
  using library_check::camel;
  std::string src = "use std::io::{self, BufRead, Write};\n\n#[path = \"" + rs + "\"]\nmod " + lib + ";\n";
  for (size_t i = 0; i < cases.size(); ++i) {
    const auto& c = cases[i];
    const std::string fn = lib + "::" + c.name + "_" + c.a + (c.arity == 2 ? "_" + c.b : "");
    src += "\nfn c" + std::to_string(i) + "(x: &[f32], y: &mut Vec<f32>) {\n";
    src += "    let a = " + lib + "::" + camel(c.a) + " { v: x[0.." + std::to_string(c.na) + "].try_into().unwrap() };\n";
    if (c.name == "matrix") {  // the matrix of a's sandwich on b's type, applied to b
      src += "    let b = " + lib + "::" + camel(c.b) + " { v: x[" + std::to_string(c.na) + ".." +
             std::to_string(c.na + c.nb) + "].try_into().unwrap() };\n";
      src += "    y.extend_from_slice(&" + fn + "(&a).apply(&b).v);\n";
      src += "    y.extend_from_slice(&(" + fn + "(&a) * b).v);\n}\n";
      continue;
    }
    if (c.arity == 2) {
      src += "    let b = " + lib + "::" + camel(c.b) + " { v: x[" + std::to_string(c.na) + ".." +
             std::to_string(c.na + c.nb) + "].try_into().unwrap() };\n";
      src += "    y.extend_from_slice(&" + fn + "(&a, &b).v);\n";
    } else {
      src += "    y.extend_from_slice(&" + fn + "(&a).v);\n";
      src += "    y.extend_from_slice(&a." + c.name + "().v);\n";
    }
    const std::string op = rust_operator(c.name);
    if (!op.empty()) src += "    y.extend_from_slice(&(" + (c.arity == 2 ? "a " + op + " b" : op + "a") + ").v);\n";
    src += "}\n";
  }
  src += "\nconst CASES: [fn(&[f32], &mut Vec<f32>); " + std::to_string(cases.size()) + "] = [";
  for (size_t i = 0; i < cases.size(); ++i) src += (i ? ", c" : "c") + std::to_string(i);
  src += "];\n\n"
         "// Each line: a case's index, then its operands' coefficients; written back: its values in every form.\n"
         "fn main() {\n"
         "    let stdin = io::stdin();\n"
         "    let mut out = io::BufWriter::new(io::stdout());\n"
         "    for line in stdin.lock().lines() {\n"
         "        let line = line.unwrap();\n"
         "        let mut words = line.split_whitespace();\n"
         "        let case: usize = words.next().unwrap().parse().unwrap();\n"
         "        let x: Vec<f32> = words.map(|w| w.parse().unwrap()).collect();\n"
         "        let mut y = Vec::new();\n"
         "        CASES[case](&x, &mut y);\n"
         "        let words: Vec<String> = y.iter().map(|v| format!(\"{:?}\", v)).collect();\n"
         "        writeln!(out, \"{}\", words.join(\" \")).unwrap();\n"
         "    }\n"
         "}\n";
  return src;
}

template <class TypeInfo, class FunctionInfo, class Matrices, size_t NT, size_t NF>
int check(const std::string& lib, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF], const Matrices& matrices,
          const std::string& rs,
          const std::string& rustc, const std::string& work, size_t count) {
  std::vector<library_check::Case> cases = library_check::sample("rust_check", types, fns, count, kRows);
  if (cases.empty()) return 1;
  const size_t sampled = cases.size();
  for (auto& c : library_check::matrix_cases(types, matrices, kRows)) cases.push_back(std::move(c));
  const std::string base = work + "/" + lib;
  std::ofstream(base + "_check.rs") << driver(lib, rs, cases);
  {
    std::ofstream in(base + ".in");
    char buf[64];
    for (size_t i = 0; i < cases.size(); ++i)
      for (size_t row = 0; row < kRows; ++row) {
        in << i;
        const size_t n = cases[i].na + cases[i].nb;
        for (size_t k = 0; k < n; ++k) {
          std::snprintf(buf, sizeof buf, " %.9g", static_cast<double>(cases[i].x[row * n + k]));
          in << buf;
        }
        in << "\n";
      }
  }
  const auto t0 = std::chrono::steady_clock::now();
  const std::string compile = rustc + " --edition 2021 -O -o " + base + "_check " + base + "_check.rs 2> " +
                              base + "_rustc.log";
  const int rc = std::system(compile.c_str());
  const std::string log = read(base + "_rustc.log");
  std::printf("rust_check: %s: rustc in %.1f s\n", lib.c_str(),
              std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  if (rc != 0 || !log.empty()) {  // the generated code compiles without a warning
    std::fprintf(stderr, "rust_check: %s (%s)\n%s", rc ? "rustc failed" : "rustc warned", compile.c_str(), log.c_str());
    return 1;
  }
  const std::string run = base + "_check < " + base + ".in > " + base + ".out";
  if (std::system(run.c_str()) != 0) {
    std::fprintf(stderr, "rust_check: %s failed\n", run.c_str());
    return 1;
  }
  std::vector<std::vector<double>> got(cases.size());
  std::vector<std::vector<std::string>> form(cases.size());
  std::ifstream out(base + ".out");
  std::string line;
  for (size_t i = 0; i < cases.size(); ++i) {
    form[i] = forms(cases[i]);
    for (size_t row = 0; row < kRows && std::getline(out, line); ++row) {
      std::istringstream words(line);
      for (std::string w; words >> w;) got[i].push_back(std::strtod(w.c_str(), nullptr));  // "inf" and "NaN" too
    }
  }
  const int bad = library_check::compare("rust_check", lib, cases, got, form, kRows);
  std::printf("rust_check: %s: %zu of %zu functions and %zu matrices run in Rust (%zu rows each), %d values off\n",
              lib.c_str(), sampled, NF, cases.size() - sampled, kRows, bad);
  return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 5) {
    std::fprintf(stderr, "usage: rust_check LIBRARY RS RUSTC WORK_DIR [COUNT]\n");
    return 2;
  }
  const std::string lib = argv[1];
  const size_t count = argc > 5 ? std::strtoul(argv[5], nullptr, 10) : 150;
  if (lib == "pga3") return check(lib, pga3::types, pga3::functions, pga3::matrices, argv[2], argv[3], argv[4], count);
  if (lib == "cga3") return check(lib, cga3::types, cga3::functions, cga3::matrices, argv[2], argv[3], argv[4], count);
  if (lib == "e3") return check(lib, e3::types, e3::functions, e3::matrices, argv[2], argv[3], argv[4], count);
  if (lib == "cga_rigid") return check(lib, cga_rigid::types, cga_rigid::functions, cga_rigid::matrices, argv[2], argv[3], argv[4], count);
  std::fprintf(stderr, "rust_check: unknown library %s\n", lib.c_str());
  return 2;
}
