// The cgagen command line: exit codes and messages, determinism across processes, --stats/--diff/--eval.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>
#include <sys/wait.h>

namespace {

struct Result {
  int code;
  std::string out;  // stdout and stderr together
};

Result run(const std::string& args) {
  std::string cmd = std::string(CGAGEN_EXE) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("popen failed");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

std::string script(const std::string& name) { return std::string(CGA_SOURCE_DIR) + "/runtime/scripts/" + name; }

std::string write_temp(const std::string& name, const std::string& text) {
  std::string path = std::string(CGA_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

}  // namespace

TEST_CASE("usage errors exit 2 with a message", "[cli]") {
  auto r = run("");
  CHECK(r.code == 2);
  CHECK(r.out.find("no script given") != std::string::npos);
  r = run("--frobnicate " + script("motor_mul.clu"));
  CHECK(r.code == 2);
  CHECK(r.out.find("unknown option '--frobnicate'") != std::string::npos);
  r = run("--target fortran " + script("motor_mul.clu"));
  CHECK(r.code == 2);
  CHECK(r.out.find("unknown target 'fortran'") != std::string::npos);
  r = run("-O7 " + script("motor_mul.clu"));
  CHECK(r.code == 2);
  r = run("--eval A=1,2 " + script("motor_reverse.clu"));
  CHECK(r.code == 2);
  CHECK(r.out.find("needs 12 value(s), got 2") != std::string::npos);
}

TEST_CASE("help exits 0 and lists the options", "[cli]") {
  auto r = run("--help");
  CHECK(r.code == 0);
  for (const char* opt : {"--target", "-O2", "--pack", "--return", "--stats", "--diff", "--eval", "--dump-ast"})
    CHECK(r.out.find(opt) != std::string::npos);
}

TEST_CASE("script errors exit 1 with file:line:col and a caret", "[cli]") {
  std::string path = write_temp("cli_bad.clu", "a = 1;\n?b = (a + ;\n");
  auto r = run(path);
  CHECK(r.code == 1);
  CHECK(r.out.find("cli_bad.clu:2:") != std::string::npos);
  CHECK(r.out.find("error:") != std::string::npos);
  CHECK(r.out.find("^") != std::string::npos);
  r = run(std::string(CGA_BINARY_DIR) + "/no_such_script.clu");
  CHECK(r.code == 1);
  CHECK(r.out.find("cgagen: error: cannot read") != std::string::npos);
}

TEST_CASE("bad --pack and --return are reported, not crashed on", "[cli]") {
  auto r = run("--target glsl --pack M=mat3x4 --pack P=vec3 " + script("transform_point.clu"));
  CHECK(r.code == 1);
  CHECK(r.out.find("cannot pack 'P' (4 blades) as vec3") != std::string::npos);
  r = run("--target glsl --return Q " + script("transform_point.clu"));
  CHECK(r.code == 1);
  CHECK(r.out.find("not an output") != std::string::npos);
}

TEST_CASE("two processes emit byte-identical code", "[cli]") {
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    for (const char* target : {"cpp", "glsl", "cuda"}) {
      std::string args = std::string("--target ") + target + " " + level + " " + script("motor_to_matrix.clu");
      auto a = run(args), b = run(args);
      REQUIRE(a.code == 0);
      CHECK(a.out == b.out);
    }
  }
}

TEST_CASE("stats, diff and eval print their reports", "[cli]") {
  auto r = run("--stats " + script("transform_point.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.rfind("kernel transform_point at -O2\noutput P: ", 0) == 0);
  CHECK(r.out.find("\ntotal: ") != std::string::npos);
  r = run("--diff -O1 -O2 " + script("transform_point.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.find("--- transform_point -O1") != std::string::npos);
  CHECK(r.out.find("op counts -O1 -> -O2:") != std::string::npos);
  // M = 1 (identity motor): the point comes back unchanged with weight 1.
  r = run("--eval M=1,0,0,0,0,0,0,0,0,0,0,0 x=0.5 y=-2 z=3 " + script("transform_point.clu"));
  CHECK(r.code == 0);
  CHECK(r.out == "P e1 0.5\nP e2 -2\nP e3 3\nP e0 1\n");
  // The spelling: the script first, the values after it.
  auto r2 = run("--eval " + script("transform_point.clu") + " M=1,0,0,0,0,0,0,0,0,0,0,0 x=0.5 y=-2 z=3");
  CHECK(r2.code == 0);
  CHECK(r2.out == r.out);
}

TEST_CASE("dump-ast prints the statements", "[cli]") {
  auto r = run("--dump-ast " + script("motor_mul.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.find("assign ?C = (* A B)") != std::string::npos);
}

// Issue 11: the fuzzer's find (the paper's A.1 with `einf` misspelt `eiof` and `translationCGA2` misspelt
// `translationCGA4`) compiles at every level, warns about both names where they are used, lists them as
// inputs in --stats, and fails under --Werror.
TEST_CASE("misspelt names that became inputs are warned about; --Werror makes them errors", "[cli]") {
  const std::string path = std::string(CGA_SOURCE_DIR) + "/fuzz/regressions/paper_a1_mutant_timeout.clu";
  const std::string eiof = path + ":17:29: warning: 'eiof' is used before it is assigned and becomes an input; "
                                  "did you mean 'einf'?\nDilation = 1+ (1-d1)/(1+d1)*eiof^e0;\n" +
                           std::string(28, ' ') + "^\n";
  const std::string cga4 = path + ":31:8: warning: 'translationCGA4' is used before it is assigned and becomes an "
                                  "input; did you mean 'translationCGA2'?\nmotor2=translationCGA4*R2;\n       ^\n";
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    auto r = run(std::string(level) + " -o /dev/null " + path);
    INFO(level << "\n" << r.out);
    CHECK(r.code == 0);
    CHECK(r.out == eiof + cga4);
  }
  auto r = run("--Werror -o /dev/null " + path);
  CHECK(r.code == 1);
  CHECK(r.out.find(path + ":17:29: error: 'eiof' is used before it is assigned and becomes an input; did you mean "
                          "'einf'? [-Werror]\n") != std::string::npos);
  CHECK(r.out.find(path + ":31:8: error: 'translationCGA4'") != std::string::npos);
  r = run("--stats " + path);
  CHECK(r.code == 0);
  CHECK(r.out.find("\ninputs: transX, transY, transZ, axis1X, axis1Y, axis1Z, angle1, d1, eiof, trans2X, trans2Y, "
                   "trans2Z, axis2X, axis2Y, axis2Z, angle2, d2, translationCGA4, alpha, X, Y, Z\n") !=
        std::string::npos);
  // The bundled scripts have no such names: cgagen_generate() builds them all with --Werror.
  r = run("--Werror --stats " + script("transform_point.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.find("warning") == std::string::npos);
  CHECK(r.out.find("\ninputs: M (1, e1^e2, e1^e3, e1^einf, e2^e3, e2^einf, e3^einf, einf^e0, e1^e2^e3^einf, "
                   "e1^e2^einf^e0, e1^e3^einf^e0, e2^e3^einf^e0), x, y, z\n") != std::string::npos);
}

TEST_CASE("work budget: an over-budget statement fails fast with a located error; large forms fall back", "[cli]") {
  const std::string bad = std::string(CGA_SOURCE_DIR) + "/tests/gen/scripts/bad/over_budget.clu";
  for (const char* level : {"-O0", "-O2"}) {
    auto r = run(std::string(level) + " " + bad);
    INFO(r.out);
    CHECK(r.code == 1);
    CHECK(r.out.rfind(bad + ":5:2: error: statement 'v' is over cgagen's work budget: a product would expand one "
                            "coefficient to about 100000 terms (limit 20000); split it into smaller statements or "
                            "give fewer blades\n",
                      0) == 0);
  }
  // circle3's fully expanded -O1 form has ~460000 expression nodes: -O1 and -O2 keep the statement form and
  // say so; a small kernel gets no note.
  const std::string circle3 = std::string(CGA_SOURCE_DIR) + "/tests/gen/scripts/circle3.clu";
  for (const char* level : {"-O1", "-O2"}) {
    auto r = run(std::string("--stats ") + level + " " + circle3);
    CHECK(r.code == 0);
    CHECK(r.out.find(std::string("\nnote: ") + level + " kept the script's statement form: the expanded form has ") !=
          std::string::npos);
  }
  auto r = run("--stats " + script("transform_point.clu"));
  CHECK(r.out.find("note:") == std::string::npos);
}

TEST_CASE("cli: --target list prints the table of targets, --target-extension the extension of one", "[cli]") {
  auto r = run("--target list");
  CHECK(r.code == 0);
  CHECK(r.out == "cpp\nglsl\ncuda\nhlsl\nglsl-es\nopencl\npython\njavascript\nrust\nlatex\ndot\n");
  r = run("--target-extension python");
  CHECK(r.code == 0);
  CHECK(r.out == ".py\n");
  r = run("--target-extension fortran");
  CHECK(r.code == 2);
}
