// cgagen --gpc on faulty sources: each fault is one located diagnostic in the original file (the line, a
// caret) and exit status 1, never a crash; and the options --gpc refuses. CGAGEN_EXE and CGA_BINARY_DIR
// come from CMakeLists.txt.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <utility>
#include <vector>

#include "cli_run.hpp"

namespace {

using Shell = cga_test::Result;

// The scratch folder, one per process: ctest runs the test cases as parallel processes, which must not
// share files.
std::string scratch() {
  const std::string dir = std::string(CGA_BINARY_DIR) + "/gpc_errors/" + std::to_string(getpid());
  std::filesystem::create_directories(dir);
  return dir;
}

// cgagen --gpc NAME run in the scratch folder, so that diagnostics name the file as NAME.
Shell gpc_run(const std::string& name, const std::string& text, const std::string& options = "") {
  const std::string dir = scratch();
  std::ofstream(dir + "/" + name, std::ios::binary) << text;
  const std::string cmd = "cd " + dir + " && " + CGAGEN_EXE + " --gpc " + options + " " + name + " -o out.hpp 2>&1";
  return cga_test::shell(cmd);
}

const char* kGood = "void f(const float* x, float* y) {\n"
                    "#pragma gpc begin\n"
                    "    a = mv_from_array(x, e1, e2);\n"
                    "#pragma clucalc begin\n"
                    "    ?r = a * a;\n"
                    "#pragma clucalc end\n"
                    "#pragma gpc end\n"
                    "    y[0] = mv_get_bladecoeff(r, 1);\n"
                    "}\n";

std::string with(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("no " + from);
  return text.replace(at, from.size(), to);
}

void expect(const std::string& name, const std::string& text, const std::string& diagnostic) {
  const Shell r = gpc_run(name, text);
  INFO(r.out);
  CHECK(r.code == 1);
  CHECK(r.out == diagnostic);
}

}  // namespace

TEST_CASE("gpc diagnostics: the source compiles as written", "[gpc]") {
  const Shell r = gpc_run("good.hpg", kGood);
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(r.out.empty());
}

TEST_CASE("gpc diagnostics: block structure", "[gpc]") {
  expect("open.hpg", with(kGood, "#pragma gpc end\n", ""),
         "open.hpg:2:1: error: '#pragma gpc begin' without '#pragma gpc end'\n#pragma gpc begin\n^\n");
  expect("script_open.hpg", with(kGood, "#pragma clucalc end\n", ""),
         "script_open.hpg:4:1: error: '#pragma clucalc begin' without '#pragma clucalc end' before '#pragma gpc end' "
         "(line 6)\n#pragma clucalc begin\n^\n");
  expect("stray_end.hpg", std::string(kGood) + "  #pragma gpc end\n",
         "stray_end.hpg:10:3: error: '#pragma gpc end' without '#pragma gpc begin'\n  #pragma gpc end\n  ^\n");
  expect("nested.hpg", with(kGood, "#pragma clucalc begin\n", "#pragma gpc begin\n"),
         "nested.hpg:4:1: error: '#pragma gpc begin' inside the gpc block that begins at line 2 (blocks do not nest; "
         "close it with '#pragma gpc end')\n#pragma gpc begin\n^\n");
  expect("no_script.hpg", "#pragma gpc begin\n#pragma gpc end\n",
         "no_script.hpg:1:1: error: the gpc block has no script: write it between '#pragma clucalc begin' and "
         "'#pragma clucalc end'\n#pragma gpc begin\n^\n");
  expect("bad_word.hpg", with(kGood, "#pragma gpc end", "#pragma gpc finish"),
         "bad_word.hpg:7:13: error: unknown '#pragma gpc' line (expected '#pragma gpc begin' or '#pragma gpc end')\n"
         "#pragma gpc finish\n            ^\n");
}

TEST_CASE("gpc diagnostics: inputs, the script and outputs, located in the original file", "[gpc]") {
  expect("blade.hpg", with(kGood, "x, e1, e2", "x, e1, e7"),
         "blade.hpg:3:30: error: unknown blade 'e7' in mv_from_array (the scalar is 1; the cga basis vectors are e1 "
         "e2 e3 einf e0)\n    a = mv_from_array(x, e1, e7);\n                             ^\n");
  expect("twice.hpg", with(kGood, "x, e1, e2", "x, e1, e1"),
         "twice.hpg:3:30: error: blade 'e1' is listed twice in mv_from_array\n    a = mv_from_array(x, e1, e1);\n"
         "                             ^\n");
  expect("script.hpg", with(kGood, "?r = a * a;", "?r = a * ;"),
         "script.hpg:5:14: error: expected expression, found ';'\n    ?r = a * ;\n             ^\n");
  expect("output.hpg", with(kGood, "mv_get_bladecoeff(r, 1)", "mv_get_bladecoeff(s, 1)"),
         "output.hpg:8:30: error: 's' in mv_get_bladecoeff is not an output of a gpc block before this line (block 1 "
         "outputs r)\n    y[0] = mv_get_bladecoeff(s, 1);\n                             ^\n");
  expect("to_array.hpg", with(kGood, "y[0] = mv_get_bladecoeff(r, 1);", "auto z = to_array(q);"),
         "to_array.hpg:8:23: error: 'q' in to_array is not an output of a gpc block before this line (block 1 "
         "outputs r)\n    auto z = to_array(q);\n                      ^\n");
  expect("coeff_blade.hpg", with(kGood, "mv_get_bladecoeff(r, 1)", "mv_get_bladecoeff(r, e1^e9)"),
         "coeff_blade.hpg:8:33: error: unknown blade 'e1^e9' in mv_get_bladecoeff (the scalar is 1; the cga basis "
         "vectors are e1 e2 e3 einf e0)\n    y[0] = mv_get_bladecoeff(r, e1^e9);\n                                ^\n");
  expect("from_outside.hpg", std::string(kGood) + "void g(const float* x) { b = mv_from_array(x, e1); }\n",
         "from_outside.hpg:10:30: error: mv_from_array declares an input of a gpc block: it belongs between "
         "'#pragma gpc begin' and '#pragma clucalc begin'\nvoid g(const float* x) { b = mv_from_array(x, e1); }\n"
         "                             ^\n");
  expect("strided.hpg", with(kGood, "mv_from_array(x, e1, e2)", "mv_from_stridedarray(x, 0, 4, e1, e2)"),
         "strided.hpg:3:9: error: Gaalop's mv_from_stridedarray is not supported by cgagen --gpc (use mv_from_array, "
         "to_array, mv_to_array or mv_get_bladecoeff)\n    a = mv_from_stridedarray(x, 0, 4, e1, e2);\n        ^\n");
  expect("basis.hpg", with(kGood, "a = mv_from_array", "e1 = mv_from_array"),
         "basis.hpg:3:5: error: cannot declare basis vector 'e1' as an input\n    e1 = mv_from_array(x, e1, e2);\n"
         "    ^\n");
}

TEST_CASE("gpc: --Werror makes a script warning an error, and the options --gpc refuses", "[gpc]") {
  const std::string misspelt = with(kGood, "?r = a * a;", "?r = a * einff;");
  Shell r = gpc_run("warn.hpg", misspelt);
  CHECK(r.code == 0);
  CHECK(r.out.find("warn.hpg:5:14: warning: 'einff' is used before it is assigned and becomes an input; did you mean "
                   "'einf'?") == 0);
  r = gpc_run("warn.hpg", misspelt, "--Werror");
  CHECK(r.code == 1);
  CHECK(r.out.find("warn.hpg:5:14: error: ") == 0);
  r = gpc_run("good.hpg", kGood, "--target glsl");
  CHECK(r.code == 2);
  CHECK(r.out.find("--gpc prints C, C++, CUDA or OpenCL statements") != std::string::npos);
  r = gpc_run("good.hpg", kGood, "--stats");
  CHECK(r.code == 2);
}

namespace {
// The lines of the compiler's errors about NAME in FILE ("FILE:LINE:COL: error: ... 'NAME' ..."), in order.
std::vector<int> error_lines(const std::string& out, const std::string& file, const std::string& name) {
  std::vector<int> lines;
  size_t at = 0;
  while ((at = out.find(file + ":", at)) != std::string::npos) {
    const size_t end = out.find('\n', at);
    const std::string line = out.substr(at, end - at);
    at = end;
    if (line.find(": error: ") != std::string::npos && line.find("'" + name + "'") != std::string::npos)
      lines.push_back(std::stoi(line.substr(file.size() + 1)));
  }
  return lines;
}
}  // namespace

// The statements of a block take more lines than its script: each carries a #line of the script line it
// comes from, so that the compiler's errors about a name the user wrote land on the line that wrote it.
TEST_CASE("gpc: C errors in the generated statements and the calls after them are at their own lines", "[gpc]") {
  const std::string text = "#include <array>\n"                                     // 1
                           "#include <cmath>\n"                                     // 2
                           "float f(const float* x, float angle, float* y) {\n"     // 3
                           "#pragma gpc begin\n"                                    // 4
                           "    a = mv_from_array(x, e1, e2);\n"                    // 5
                           "    v = mv_from_array(vv, e1, e3);\n"                   // 6: vv is undeclared
                           "#pragma clucalc begin\n"                                // 7
                           "    R = cos(angel / 2) + sin(angle / 2) * e1^e2;\n"     // 8: angel for angle
                           "    s = scale * a;\n"                                   // 9: scale is undeclared
                           "    ?r = R * s * ~R + v;\n"                             // 10
                           "#pragma clucalc end\n"                                  // 11
                           "#pragma gpc end\n"                                      // 12
                           "    y[0] = mv_get_bladecoeff(r, e1);\n"                 // 13
                           "    yy[1] = mv_get_bladecoeff(r, e2);\n"                // 14: yy is undeclared
                           "    auto z = to_array(r);\n"                            // 15
                           "    zz = to_array(r);\n"                                // 16: zz is undeclared
                           "    return y[0] + z[0];\n"                              // 17
                           "}\n"                                                    // 18
                           "float g() { return undeclared_after; }\n";              // 19
  for (const char* level : {"-O0", "-O2"}) {
    const Shell r = gpc_run("lines.hpg", text, level);
    INFO(level << "\n" << r.out);
    REQUIRE(r.code == 0);
    const Shell c = cga_test::shell("cd " + scratch() + " && LC_ALL=C " + CXX_COMPILER + " -std=c++17 -fsyntax-only -x c++ out.hpp 2>&1");
    INFO(c.out);
    CHECK(c.code != 0);
    for (const auto& [name, line] : std::vector<std::pair<std::string, int>>{
             {"vv", 6}, {"angel", 8}, {"scale", 9}, {"yy", 14}, {"zz", 16}, {"undeclared_after", 19}}) {
      INFO(name);
      const std::vector<int> lines = error_lines(c.out, "lines.hpg", name);
      REQUIRE(!lines.empty());
      CHECK(lines.front() == line);
    }
    CHECK(c.out.find("out.hpp:") == std::string::npos);
  }
}

TEST_CASE("gpc: a source without blocks is copied unchanged after its #line", "[gpc]") {
  const std::string text = "// to_array(x) in a comment, \"#pragma gpc begin\" in a string\n"
                           "#include <array>\nauto f(const int (&v)[2]) { return std::to_array(v); }\n"
                           "/*\n#pragma gpc begin\n*/\nint main() { return 0; }";
  const Shell r = gpc_run("plain.cpp", text);
  INFO(r.out);
  CHECK(r.code == 0);
  std::ifstream in(scratch() + "/out.hpp", std::ios::binary);
  const std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  CHECK(out == "#line 1 \"plain.cpp\"\n" + text);
}

TEST_CASE("gpc: mv_to_array and mv_get_bladecoeff as written after comments and directives", "[gpc]") {
  const std::string text = "void f(float* o, const float* x) {\n"
                           "#pragma gpc begin\n"
                           "  a = mv_from_array(x, e1, e2);\n"
                           "#pragma clucalc begin\n"
                           "  ?r = a*e1;\n"
                           "#pragma clucalc end\n"
                           "#pragma gpc end\n"
                           "#if 1\n"
                           "  // all blades, then two by name (one the output lacks), then one reversed\n"
                           "  o = mv_to_array(r);\n"
                           "  o = mv_to_array(r, e1^e2, e3);\n"
                           "  o[0] = mv_get_bladecoeff(r, e2 ^ e1) + mv_get_bladecoeff(r, 1.0);\n"
                           "#endif\n"
                           "}\n";
  const Shell r = gpc_run("calls.hpg", text);
  INFO(r.out);
  REQUIRE(r.code == 0);
  std::ifstream in(scratch() + "/out.hpp", std::ios::binary);
  const std::string out((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  INFO(out);
  // r = a e1 = x0 + x1 e2 e1: blades 1 and e1^e2, r[1] the coefficient of e1^e2 (= -x[1]).
  CHECK(out.find("\n  o[0] = r[0]; o[1] = r[1];\n") != std::string::npos);
  CHECK(out.find("\n  o[0] = r[1]; o[1] = 0.0f;\n") != std::string::npos);
  CHECK(out.find("\n  o[0] = (-r[1]) + r[0];\n") != std::string::npos);
  CHECK(out.find("#endif\n#line 14 \"calls.hpg\"\n}\n") != std::string::npos);
}
