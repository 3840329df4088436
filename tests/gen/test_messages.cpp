// The command line's messages for what a new user meets: files that are no script (a directory, a binary
// file, an over-long line), the quoted line cut and escaped, typo hints for short names, variables and
// functions, other libraries' names, `R^2`, NaN in --eval. Each checks the exact text.
#include <catch2/catch.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "expand/hints.hpp"

using cga_test::run;
using cga_test::write_temp;

namespace {
const std::string kBad = std::string(CGA_SOURCE_DIR) + "/tests/gen/scripts/bad/";
}

TEST_CASE("a directory, a binary file and an over-long line get one located line", "[messages]") {
  const std::string dir = std::string(CGA_BINARY_DIR) + "/messages";
  std::filesystem::create_directories(dir);
  auto r = run(dir);
  CHECK(r.code == 1);
  CHECK(r.out == dir + ":1:1: error: is a directory, not a script\n");
  r = run(kBad + "binary.clu");
  CHECK(r.code == 1);
  CHECK(r.out == kBad + "binary.clu:2:1: error: not a text file: byte \\x00; a script is UTF-8 text\n");
  // Latin-1 in a comment is accepted (the lexer skips it), in code it is not.
  CHECK(run("-o /dev/null " + write_temp("messages/latin1_comment.clu", "// caf\xe9\n?x = a;\n")).code == 0);
  const std::string latin1 = write_temp("messages/latin1.clu", "?x = a;\n?y = caf\xe9;\n");
  r = run(latin1);
  CHECK(r.code == 1);
  CHECK(r.out == latin1 + ":2:9: error: not a text file: byte \\xE9, which is not UTF-8; a script is UTF-8 text\n");
  const std::string long_line = write_temp("messages/long.clu", "?x = " + std::string(70000, ' ') + "a;\n");
  r = run(long_line);
  CHECK(r.code == 1);
  CHECK(r.out == long_line + ":1:65537: error: line 1 is longer than 65536 bytes; a script's lines are shorter\n");
}

TEST_CASE("the quoted line is cut to 120 columns around the column, control bytes escaped", "[messages]") {
  std::string text = "?x = ";
  for (int i = 0; i < 50; ++i) text += "a + ";
  text += "foo(1)";
  for (int i = 0; i < 50; ++i) text += " + b";
  const std::string wide = write_temp("messages/wide.clu", text + ";\n");
  auto r = run(wide);
  CHECK(r.code == 1);
  std::string quote = "...";
  for (int i = 0; i < 15; ++i) quote += "a + ";
  quote += "foo(1)";
  for (int i = 0; i < 13; ++i) quote += " + b";
  quote += " +...";
  CHECK(r.out == wide + ":1:206: error: unknown function 'foo'\n" + quote + "\n" + std::string(63, ' ') + "^\n");
  const std::string ctl = write_temp("messages/ctl.clu", "?x = a\x01 + b;\n");
  r = run(ctl);
  CHECK(r.out == ctl + ":1:7: error: unexpected character '\\x01'\n?x = a\\x01 + b;\n      ^\n");
}

TEST_CASE("typo hints reach short names and pick variables for reads, functions for calls", "[messages]") {
  auto r = run("-o /dev/null " + kBad + "short_typo.clu");
  CHECK(r.code == 0);
  CHECK(r.out == kBad + "short_typo.clu:4:11: warning: 'Tt' is used before it is assigned and becomes an input; "
                        "did you mean 'T'?\n?q = T*p*~Tt;\n          ^\n");
  CHECK(run("--Werror -o /dev/null " + kBad + "short_typo.clu").code == 1);
  r = run("-o /dev/null " + write_temp("messages/sn.clu", "sn = x*2;\n?q = sn.snn;\n"));
  CHECK(r.out.find("sn.clu:2:9: warning: 'snn' is used before it is assigned and becomes an input; did you mean "
                   "'sn'?\n") != std::string::npos);
  // Coordinates and indices next to a short name are no typos.
  r = run("-o /dev/null " + write_temp("messages/coords.clu", "n = e1;\np = e2;\n?q = n*nx + p*p1 + ny;\n"));
  CHECK(r.code == 0);
  CHECK(r.out.empty());
  r = run(write_temp("messages/snn.clu", "?q = snn(x);\n"));
  CHECK(r.code == 1);
  CHECK(r.out.find("snn.clu:1:6: error: unknown function 'snn'; did you mean 'sin'?\n") != std::string::npos);
}

// An n-joint chain reads its joint angles a1 ... a12 as inputs and assigns its products C2 ... C12: a10 is
// the next angle, not a misspelt C10, and --Werror (cgagen_generate's default) must pass.
TEST_CASE("a numbered family of inputs is not hinted toward another stem's numbered names", "[messages]") {
  std::string text = "C1 = 1;\n";
  for (int i = 2; i <= 12; ++i)
    text += "C" + std::to_string(i) + " = C" + std::to_string(i - 1) + " * (cos(a" + std::to_string(i) +
            ") + sin(a" + std::to_string(i) + ")*e1^e2);\n";
  text += "?R = C12 * a1;\n";
  auto r = run("--Werror -o /dev/null " + write_temp("messages/chain12.clu", text));
  CHECK(r.code == 0);
  CHECK(r.out.empty());
  // Real typos next to numbered names still warn: a stem's other number, a misspelt stem of its own.
  r = run("-o /dev/null " + write_temp("messages/family_typos.clu",
                                       "motor1 = 1 + e1^e2;\nmotor2 = motor1*motor1;\n?q = motr2 + Tt;\nT = 2;\n"));
  CHECK(r.out.find("'motr2' is used before it is assigned and becomes an input; did you mean 'motor2'?") !=
        std::string::npos);
  CHECK(r.out.find("'Tt' is used before it is assigned and becomes an input; did you mean 'T'?") != std::string::npos);
  CHECK(run("--Werror -o /dev/null " + kBad + "short_typo.clu").code == 1);
  // Free names read so far count as the family too (theta1 ... theta9 before theta10).
  const std::vector<std::string> assigned = {"Theta10", "Theta9"};
  CHECK(cgagen::hints::for_read("theta10", assigned, {}) == std::optional<std::string>("Theta10"));
  CHECK(!cgagen::hints::for_read("theta10", assigned, {}, {"theta9"}));
  CHECK(cgagen::hints::for_read("Theta11", assigned, {}, {"theta9"}) == std::optional<std::string>("Theta10"));
  CHECK(cgagen::hints::for_read("eiof", {"einf"}, {}, {"eio1"}) == std::optional<std::string>("einf"));
}

TEST_CASE("other libraries' names point at cgagen's spelling or say it does not exist", "[messages]") {
  auto r = run(kBad + "other_library_name.clu");
  CHECK(r.code == 1);
  CHECK(r.out == kBad + "other_library_name.clu:3:6: error: unknown function 'inverse'; did you mean 'invert'?\n"
                        "?x = inverse(A);\n     ^\n");
  auto first_line = [](const std::string& call) {
    auto out = run(write_temp("messages/other.clu", "A = e1 + e2;\nB = e3;\n?x = " + call + ";\n")).out;
    return out.substr(0, out.find('\n'));
  };
  const std::string at = std::string(CGA_BINARY_DIR) + "/messages/other.clu:3:6: error: unknown function ";
  CHECK(first_line("reverse(A)") == at + "'reverse'; cgagen writes the reverse as ~X");
  CHECK(first_line("dual(A)") == at + "'dual'; did you mean 'Dual'?");  // a near built-in comes first
  CHECK(first_line("norm(A)") == at + "'norm'; did you mean 'abs'? (abs(X) of a multivector is its magnitude)");
  CHECK(first_line("unit(A)") == at + "'unit'; did you mean 'normalize'?");
  CHECK(first_line("inner(A, B)") == at + "'inner'; cgagen writes Gaalop's (Hestenes') inner product as A . B or "
                                          "hip(A, B); see also dot, lcont, rcont");
  CHECK(first_line("wedge(A, B)") == at + "'wedge'; cgagen writes the outer product as A ^ B");
  CHECK(first_line("meet(A, B)") == at + "'meet'; cgagen has no 'meet'; rp(A, B) is the regressive product");
  CHECK(first_line("vee(A, B)") == at + "'vee'; did you mean 'rp'? (the regressive product)");
  CHECK(first_line("left_contraction(A, B)") == at + "'left_contraction'; did you mean 'lcont'? (the left contraction)");
  CHECK(first_line("conjugation(A)") == at + "'conjugation'; did you mean 'conjugate'? (the Clifford conjugate)");
  CHECK(first_line("grade_select(A, 2)") == at + "'grade_select'; did you mean 'grade'? (grade(X, k))");
  // normalize (X / sqrt|<X ~X>_0|) is a built-in of every algebra.
  CHECK(run("--algebra 3d -o /dev/null " + write_temp("messages/other3d.clu", "?x = normalize(e1);\n")).code == 0);
}

TEST_CASE("R^2 is warned about as the outer product with 2, 0.5^t is not", "[messages]") {
  auto r = run("-o /dev/null " + write_temp("messages/pow.clu", "R = 1 + e1^e2;\n?x = R^2;\n?y = 1 - 0.5^e1^einf;\n"));
  CHECK(r.code == 0);
  CHECK(r.out == std::string(CGA_BINARY_DIR) + "/messages/pow.clu:2:7: warning: 'R^2' is the outer product with the "
                                               "number 2, i.e. 2*R; for a power write R*R\n?x = R^2;\n      ^\n");
}

TEST_CASE("NaN from --eval prints as nan, without a sign", "[messages]") {
  auto r = run("--eval " + write_temp("messages/nan.clu", "?x = sqrt(a);\n?y = a/b;\n") + " a=-1 b=0");
  CHECK(r.code == 0);
  CHECK(r.out == "x 1 nan\ny 1 -inf\n");
}
