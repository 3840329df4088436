// The cgagen command line as an installed tool: --version, --target list, a script from standard
// input, the exit codes --help documents, and GCC's `file:line:col: error:` form of script errors.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <sys/wait.h>

#include "cli_run.hpp"

using cga_test::run;
using cga_test::script;
using cga_test::write_temp;

TEST_CASE("version: --version prints the project version", "[cli]") {
  auto r = run("--version");
  CHECK(r.code == 0);
  CHECK(r.out == std::string("cgagen ") + CGAGEN_VERSION + "\n");
}

TEST_CASE("target list: --target list prints every target, one per line, each of them accepted", "[cli]") {
  auto r = run("--target list");
  CHECK(r.code == 0);
  CHECK(r.out.rfind("cpp\nsimd\nglsl\ncuda\n", 0) == 0);  // C++, its SIMD form, then the shading languages (tests/targets checks the rest)
  std::istringstream lines(r.out);
  std::string target;
  while (std::getline(lines, target)) {
    auto t = run("--target " + target + " " + script("motor_reverse.clu"));
    CHECK(t.code == 0);
  }
}

TEST_CASE("stdin: - reads the script from standard input, diagnostics name <stdin>", "[cli]") {
  std::string good = write_temp("cli_stdin_good.clu", "?c = (a*e1) ^ (b*e2);\n");
  auto from_file = run("--name kernel " + good);
  auto r = run("- < " + good);
  CHECK(r.code == 0);
  CHECK(r.out.find("inline void kernel(float a, float b, float c[1])") != std::string::npos);
  CHECK(r.out.find("from <stdin>") != std::string::npos);
  CHECK(r.out.substr(r.out.find('\n')) == from_file.out.substr(from_file.out.find('\n')));  // same code
  r = run("--name wedge --stats - < " + good);
  CHECK(r.code == 0);
  CHECK(r.out.find("kernel wedge") != std::string::npos);

  std::string bad = write_temp("cli_stdin_bad.clu", "a = 1;\n?b = (a + ;\n");
  r = run("- < " + bad);
  CHECK(r.code == 1);
  CHECK(r.out.rfind("<stdin>:2:11: error: ", 0) == 0);
}

TEST_CASE("script errors keep GCC's file:line:col: error: form", "[cli]") {
  std::string path = write_temp("cli_gcc_form.clu", "a = 1;\n?b = (a + ;\n");
  auto r = run(path);
  CHECK(r.code == 1);
  // First line exactly FILE:LINE:COL: error: MESSAGE, then the source line, then the caret under column 11.
  const std::regex form("^" + path + R"(:2:11: error: [^\n]+\n\?b = \(a \+ ;\n {10}\^\n)");
  CHECK(std::regex_search(r.out, form));
}

TEST_CASE("help: --help documents the exit codes and the new options", "[cli]") {
  auto r = run("--help");
  CHECK(r.code == 0);
  for (const char* s : {"--version", "--target list", "standard input", "exit status", "0 success", "2 bad usage"})
    CHECK(r.out.find(s) != std::string::npos);
  CHECK(run("--version --frobnicate").code == 0);  // --version answers at once, like --help
  CHECK(run("--target").code == 2);
}
