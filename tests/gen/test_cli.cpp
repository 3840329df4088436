// The cgagen command line: exit codes and messages, determinism across processes, --stats/--diff/--eval.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <cstdio>
#include <sstream>
#include <vector>
#include <fstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

#include "cli_run.hpp"
#include "opt/passes.hpp"

using cga_test::run;
using cga_test::script;
using cga_test::write_temp;

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

TEST_CASE("the pass table: cgagen --passes lists the -O2 passes in run order and exits 0", "[cli]") {
  auto r = run("--passes");
  CHECK(r.code == 0);
  // Every row of the table, in order, one per line.
  size_t at = 0;
  for (const auto& p : cgagen::opt::pass_table()) {
    const size_t found = r.out.find(p.name, at);
    INFO(p.name);
    REQUIRE(found != std::string::npos);
    CHECK(r.out.find(p.description, found) != std::string::npos);
    at = found + p.name.size();
  }
  for (const char* name : {"pair-products", "shared-subtrees", "fold-negations", "inline-single-use", "factor-sums",
                           "drop-aliases", "merge-equal"})
    CHECK(r.out.find(name) != std::string::npos);
  CHECK(run("--help").out.find("--passes") != std::string::npos);
  // --stats names them at -O2, in the same order, and not below.
  std::string names = "\npasses:";
  for (const auto& p : cgagen::opt::pass_table()) names += " " + p.name;
  CHECK(run("--stats -O2 " + script("motor_mul.clu")).out.find(names + "\n") != std::string::npos);
  CHECK(run("--stats -O1 " + script("motor_mul.clu")).out.find("passes:") == std::string::npos);
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
      std::string args = std::string("--target ") + target + " " + level + " " + CGA_SOURCE_DIR +
                         "/tests/kernels/scripts/motor_to_matrix.clu";
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
  // The spelling users write: the script first, the values after it.
  auto r2 = run("--eval " + script("transform_point.clu") + " M=1,0,0,0,0,0,0,0,0,0,0,0 x=0.5 y=-2 z=3");
  CHECK(r2.code == 0);
  CHECK(r2.out == r.out);
}

TEST_CASE("dump-ast prints the statements", "[cli]") {
  auto r = run("--dump-ast " + script("motor_mul.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.find("assign ?C = (* A B)") != std::string::npos);
}

// A fuzzer find (the paper's A.1 with `einf` misspelt `eiof` and `translationCGA2` misspelt
// `translationCGA4`) compiles at every level, warns about both names where they are used, lists them as
// inputs in --stats, and fails under --Werror.
TEST_CASE("misspelt names that became inputs are warned about, --Werror makes them errors", "[cli]") {
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

TEST_CASE("work budget: an over-budget statement fails fast with a located error, large forms fall back", "[cli]") {
  const std::string bad = std::string(CGA_SOURCE_DIR) + "/tests/gen/scripts/bad/over_budget.clu";
  for (const char* level : {"-O0", "-O2"}) {
    auto r = run(std::string(level) + " " + bad);
    INFO(r.out);
    CHECK(r.code == 1);
    CHECK(r.out.rfind(bad + ":10:2: error: statement 'v' is over cgagen's work budget: the statement's products "
                            "expand to more than 100000 terms in all; split it into smaller statements or give fewer "
                            "blades\n",
                      0) == 0);
  }
  // circle3's fully expanded -O1 form has 208494 symbol occurrences: -O1 and -O2 keep the statement form and
  // say so (substitution stops once the form is certain to pass the budget); a small kernel gets no note.
  const std::string circle3 = std::string(CGA_SOURCE_DIR) + "/tests/gen/scripts/circle3.clu";
  for (const char* level : {"-O1", "-O2"}) {
    auto r = run(std::string("--stats ") + level + " " + circle3);
    CHECK(r.code == 0);
    CHECK(r.out.find(std::string("\nnote: ") + level + " kept the script's statement form: the expanded form has "
                                                       "more than 4000 symbol occurrences (budget 4000)\n") != std::string::npos);
  }
  auto r = run("--stats " + script("transform_point.clu"));
  CHECK(r.out.find("note:") == std::string::npos);
}

// Generator regressions, each a valid script that was refused or broke: --eval at every level gives the
// value, and the emitted C++ uses only std:: functions (no conjugate, no zero-size array).
TEST_CASE("regressions: abs of real inputs, gcd with functions, zero outputs, exp of one blade", "[cli]") {
  struct Case {
    const char* script;
    const char* inputs;
    const char* expected;
  };
  const Case cases[] = {
      {"?v = abs(a)*abs(a);", "a=-0.5", "v 1 0.25\n"},
      {"?v = VecN3(x, y, abs(z));", "x=1 y=2 z=-3", "v e1 1\nv e2 2\nv e3 3\nv einf 7\nv e0 1\n"},
      {"?v = abs(exp(a));", "a=0", "v 1 1\n"},
      {"?v = (a+1)/sin(b);", "a=1 b=1.5707963267948966", "v 1 2\n"},
      {"?a = 0; ?b = x*e1;", "x=2", "a 1 0\nb e1 2\n"},
  };
  for (const Case& c : cases) {
    const std::string path = write_temp("regression.clu", c.script);
    for (const char* level : {"-O0", "-O1", "-O2"}) {
      auto r = run(std::string(level) + " --eval " + path + " " + c.inputs);
      INFO(c.script << " " << level << "\n" << r.out);
      CHECK(r.code == 0);
      CHECK(r.out == c.expected);
      r = run(std::string(level) + " " + path);
      CHECK(r.code == 0);
      CHECK(r.out.find("conjugate") == std::string::npos);
      CHECK(r.out.find("[0]") == r.out.find("[0] ="));  // every [0] is an element, never a zero-size array
    }
  }
  // exp of a scalar times one blade: the sign of the square comes from the blade (e1^e2 squares to -1: a
  // rotation, cos + sin; einf^e0 squares to +1: a boost, cosh + sinh), whatever the sign of the scalar.
  auto values = [](const std::string& text) {
    std::vector<double> v;
    std::istringstream in(text);
    std::string output, blade;
    double x;
    while (in >> output >> blade >> x) v.push_back(x);
    return v;
  };
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    auto r = run(std::string(level) + " --eval " + write_temp("regression.clu", "?v = exp(-(a+b)/2*e1^e2);") + " a=1 b=0");
    REQUIRE(r.code == 0);
    auto v = values(r.out);
    REQUIRE(v.size() == 2);
    CHECK(v[0] == Approx(std::cos(0.5)).epsilon(1e-14));
    CHECK(v[1] == Approx(-std::sin(0.5)).epsilon(1e-14));
    r = run(std::string(level) + " --eval " + write_temp("regression.clu", "?v = exp((a-b)*einf^e0);") + " a=0 b=1");
    REQUIRE(r.code == 0);
    v = values(r.out);
    REQUIRE(v.size() == 2);
    CHECK(v[0] == Approx(std::cosh(1.0)).epsilon(1e-14));
    CHECK(v[1] == Approx(-std::sinh(1.0)).epsilon(1e-14));
  }
  // Dividing by a versor whose coefficients hold sin/cos of an input works like the sandwich with ~R.
  const std::string path = write_temp("regression.clu", "R = RotorN3(0,0,1,phi); ?v = R*VecN3(x,y,z)/R; ?w = R*VecN3(x,y,z)*~R;");
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    auto r = run(std::string(level) + " --eval " + path + " x=1 y=0.5 z=2 phi=0.7");
    REQUIRE(r.code == 0);
    const auto v = values(r.out);
    REQUIRE(v.size() == 10);  // v and w: e1 e2 e3 einf e0 each
    for (int i = 0; i < 5; ++i) CHECK(v[i] == Approx(v[i + 5]).margin(1e-14));
  }
}

// --eval follows the printed code's order of operations (sums in canonical term order, products left to
// right), not GiNaC's process-dependent term order: the same bits in every process.
TEST_CASE("eval gives the same bits in every process", "[cli]") {
  const std::string args = " --eval " + std::string(CGA_SOURCE_DIR) + "/tests/gen/scripts/paper_a1.clu "
                           "transX=1 transY=2 transZ=3 axis1X=0.1 axis1Y=0.2 axis1Z=0.9 angle1=0.7 d1=1.3 "
                           "trans2X=-1 trans2Y=0.5 trans2Z=2 axis2X=0.3 axis2Y=-0.2 axis2Z=0.4 angle2=1.1 d2=0.8 "
                           "alpha=0.3 X=0.5 Y=0.6 Z=-0.7";
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    const auto first = run(level + args);
    REQUIRE(first.code == 0);
    for (int k = 0; k < 6; ++k) CHECK(run(level + args).out == first.out);
  }
}

// Gaalop compatibility: forms Gaalop's CGA scripts use, each with its value.
TEST_CASE("Gaalop forms: 1.0 as the scalar blade, abs of a multivector, coefficient, SphereN3, overloads", "[cli]") {
  struct Case {
    const char* script;
    const char* inputs;
    const char* expected;
  };
  const Case cases[] = {
      {"#pragma output r 1.0\n?r = 2*x;", "x=3", "r 1 6\n"},
      // abs(L) = sqrt(|<L ~L>_0|): |3 e1 + 4 e2| = 5
      {"L = e1*a + e2*b;\n?m = abs(L);", "a=3 b=4", "m 1 5\n"},
      // the scalar c with which the multivector holds c * blade; e2^e1 = -e1^e2
      {"?c = coefficient(x*e1^e2 + y*e3, e2^e1); ?d = coefficient(x*e1^e2 + y*e3, e3);", "x=3 y=4",
       "c 1 -3\nd 1 4\n"},
      // Gaalop's SphereN3 around (1,2,3) of radius 2 is *(VecN3(1,2,3) - 2 einf), in both of its forms; its
      // dual, as Gaalop's scripts take it (*SphereN3), is -(VecN3(1,2,3) - 2 einf) (** = -1 in CGA)
      {"?s = *SphereN3(1,2,3,r); ?t = *SphereN3(VecN3(1,2,3), r);", "r=2",
       "s e1 -1\ns e2 -2\ns e3 -3\ns einf -5\ns e0 -1\nt e1 -1\nt e2 -2\nt e3 -3\nt einf -5\nt e0 -1\n"},
      {"?s = SphereN3(1,2,3,r);", "r=2",
       // -(V.I) by hand, V = e1 + 2 e2 + 3 e3 + 5 einf + e0, I = e1^e2^e3^einf^e0, einf.e0 = -1
       "s e1^e2^e3^einf 5\ns e1^e2^e3^e0 -1\ns e1^e2^einf^e0 -3\ns e1^e3^einf^e0 2\ns e2^e3^einf^e0 -1\n"},
      // a macro overloaded by argument count, one form calling the other (not a recursion)
      {"S = {VecN3(_P(1),_P(2),_P(3)) - _P(4)*_P(4)/2*einf}\nS = {S(_P(1),0,0,_P(2))}\n?a = S(x, r);", "x=1 r=2",
       "a e1 1\na einf -1.5\na e0 1\n"},
  };
  for (const Case& c : cases) {
    const std::string path = write_temp("gaalop.clu", c.script);
    for (const char* level : {"-O0", "-O2"}) {
      auto r = run(std::string(level) + " --eval " + path + " " + c.inputs);
      INFO(c.script << " " << level << "\n" << r.out);
      CHECK(r.code == 0);
      CHECK(r.out == c.expected);
    }
  }
  auto r = run("--eval " + write_temp("gaalop.clu", "?c = coefficient(x*e1, e1 + e2);") + " x=1");
  CHECK(r.code == 1);
  CHECK(r.out.find("'coefficient' takes a basis blade as its second argument") != std::string::npos);
}

TEST_CASE("fuzzer find: a quotient by exp(g) optimizes at every level", "[cli]") {
  const std::string path = std::string(CGA_SOURCE_DIR) + "/fuzz/regressions/gcd_with_function.clu";
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    auto r = run(std::string(level) + " --eval " + path + " g=0.5 d=0.25");
    INFO(r.out);
    REQUIRE(r.code == 0);
    // *D = -(1-d)/exp(g) on the pseudoscalar (the dual of a scalar s is -s e1^e2^e3^einf^e0)
    CHECK(r.out.rfind("M e1^e2^e3^einf^e0 ", 0) == 0);
    CHECK(std::stod(r.out.substr(19)) == Approx(-0.75 * std::exp(-0.5)).epsilon(1e-14));
  }
}

TEST_CASE("cli: --target list prints the table of targets, --target-extension the extension of one", "[cli]") {
  auto r = run("--target list");
  CHECK(r.code == 0);
  CHECK(r.out == "cpp\nsimd\nglsl\ncuda\nhlsl\nglsl-es\nwgsl\nopencl\npython\njavascript\nrust\nlatex\ndot\n");
  r = run("--target-extension python");
  CHECK(r.code == 0);
  CHECK(r.out == ".py\n");
  r = run("--target-extension fortran");
  CHECK(r.code == 2);
}

TEST_CASE("the C++ of every bundled kernel compiles without a warning at every level", "[cli]") {
  // -O0 and -O1 print the script's statements: a value's blade that no output reads (one an `#pragma output`
  // leaves out) must not become an unused variable, or a user's -Wall -Werror build fails. All kernels of a
  // level go into one translation unit (their names differ), compiled once.
  namespace fs = std::filesystem;
  std::vector<fs::path> scripts;
  for (const auto& e : fs::directory_iterator(fs::path(CGA_SOURCE_DIR) / "runtime" / "scripts"))
    if (e.path().extension() == ".clu") scripts.push_back(e.path());
  std::sort(scripts.begin(), scripts.end());
  scripts.push_back(fs::path(CGA_SOURCE_DIR) / "bench" / "ik_arm" / "arm5.clu");
  scripts.push_back(fs::path(CGA_SOURCE_DIR) / "tests" / "diff" / "regressions" / "products_words.clu");
  const fs::path dir = fs::path(CGA_BINARY_DIR) / ("warnings_" + std::to_string(static_cast<long>(getpid())));
  fs::create_directories(dir);
  for (const char* level : {"-O0", "-O1", "-O2"}) {
    std::string tu;
    for (const auto& s : scripts) {
      const fs::path out = dir / (s.stem().string() + level + ".hpp");
      auto r = run(std::string(level) + " --target cpp -o " + out.string() + " " + s.string());
      INFO(s << " " << level << ": " << r.out);
      REQUIRE(r.code == 0);
      tu += "#include \"" + out.string() + "\"\n";
    }
    tu += "int main() { return 0; }\n";
    const fs::path src = dir / (std::string("all") + level + ".cpp");
    std::ofstream(src) << tu;
    auto c = cga_test::shell("c++ -std=c++17 -Wall -Wextra -Wshadow -Wunused -Werror -fsyntax-only " + src.string() + " 2>&1");
    INFO(level << ": " << c.out.substr(0, 2000));
    CHECK(c.code == 0);
  }
  fs::remove_all(dir);
}

TEST_CASE("#pragma algebra: a script names its algebra, and a conflicting --algebra is a located error", "[cli]") {
  const std::string pga = write_temp("pragma_algebra_pga.clu", "#pragma algebra 3dpga\n?p = e0^e1;\n");
  auto r = run("--eval " + pga);
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(r.out == "p e0^e1 1\n");  // in CGA, e0^e1 would be -e1^e0
  CHECK(run("--algebra 3dpga --eval " + pga).code == 0);  // the same algebra named twice
  r = run("--algebra cga " + pga);
  CHECK(r.code == 1);
  CHECK(r.out.rfind(pga + ":1:17: error: '#pragma algebra 3dpga' conflicts with --algebra cga\n", 0) == 0);
  // A definition file next to the script, by a relative name.
  write_temp("pragma_algebra_plane.csv", "1,e1,e2\n\n1,e1,e2\ne1=1,e2=1\n\n");
  const std::string file = write_temp("pragma_algebra_file.clu", "#pragma algebra pragma_algebra_plane.csv\n?q = e1*e2*e1;\n");
  r = run("--eval " + file);
  INFO(r.out);
  CHECK(r.out == "q e2 -1\n");
  r = run(write_temp("pragma_algebra_bad.clu", "#pragma algebra nowhere\n?p = e1;\n"));
  CHECK(r.code == 1);
  CHECK(r.out.find("pragma_algebra_bad.clu:1:17: error: '#pragma algebra': unknown algebra") != std::string::npos);
  r = run(write_temp("pragma_algebra_two.clu", "#pragma algebra 3dpga\n#pragma algebra cga\n?p = e1;\n"));
  CHECK(r.out.find("pragma_algebra_two.clu:2:17: error: '#pragma algebra cga' after '#pragma algebra 3dpga' at line 1") !=
        std::string::npos);
}

TEST_CASE("cli: --outputs keeps the named outputs and drops the work only the others need", "[cli]") {
  const std::string src = write_temp("outputs.clu", "?a = x*y + z;\n?b = x*x*x*y;\n?c = a + 1;\n");
  auto all = run("--stats " + src);
  auto some = run("--stats --outputs c,a " + src);
  REQUIRE(all.code == 0);
  REQUIRE(some.code == 0);
  CHECK(all.out.find("output b: ") != std::string::npos);
  CHECK(some.out.find("output b: ") == std::string::npos);
  // The script's order, not the option's.
  CHECK(some.out.find("output a: ") < some.out.find("output c: "));
  // What only b needs is gone: a's one multiplication is left of the three (b shares x*y with a).
  auto total_mul = [](const std::string& out) {
    const auto at = out.find("\ntotal: ");
    return std::stoi(out.substr(out.find("add, ", at) + 5));
  };
  CHECK(total_mul(all.out) == 3);
  CHECK(total_mul(some.out) == 1);
  auto r = run("--eval x=2 y=3 z=1 --outputs b " + src);
  CHECK(r.code == 0);
  CHECK(r.out == "b 1 24\n");
  r = run("--outputs q " + src);
  CHECK(r.code == 2);
  CHECK(r.out.find("--outputs names 'q', which is not an output of the script (its outputs: a, b, c)") !=
        std::string::npos);
}

TEST_CASE("cli: --library --also writes each target from one build, the same bytes as a run per target", "[cli]") {
  const std::string spec = std::string(CGA_SOURCE_DIR) + "/libraries/e3.gal";
  const std::string dir = std::string(CGA_BINARY_DIR) + "/";
  auto r = run("--library --target cpp -o " + dir + "also_e3.hpp --also glsl=" + dir + "also_e3.glsl --also rust=" + dir +
               "also_e3.rs " + spec);
  REQUIRE(r.code == 0);
  for (const char* t : {"glsl", "rust"}) {
    const std::string ext = t == std::string("glsl") ? ".glsl" : ".rs";
    r = run(std::string("--library --target ") + t + " -o " + dir + "alone_e3" + ext + " " + spec);
    REQUIRE(r.code == 0);
    const std::string together = cga_test::read_text(dir + "also_e3" + ext), alone = cga_test::read_text(dir + "alone_e3" + ext);
    CHECK(!together.empty());
    CHECK(together == alone);
  }
  r = run("--also glsl=x.glsl " + script("motor_mul.clu"));
  CHECK(r.code == 2);
  CHECK(r.out.find("--also applies to --library") != std::string::npos);
  r = run("--library --also glsl " + spec);
  CHECK(r.code == 2);
  CHECK(r.out.find("--also expects TARGET=FILE, got 'glsl'") != std::string::npos);
  r = run("--library --also fortran=x.f " + spec);
  CHECK(r.code == 2);
  CHECK(r.out.find("unknown target 'fortran'") != std::string::npos);
  r = run("--library --stats --also glsl=x.glsl " + spec);
  CHECK(r.code == 2);
}
