// Names in generated code (gen/emit/names.hpp): the stem -> identifier rule, each target's spelling of
// reserved words, collision-free spellings, --name checks, and that tests/targets/names covers every
// reserved word of every target as an input and as an output name.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <regex>
#include <set>
#include <sstream>

#include "cli_run.hpp"
#include "emit/names.hpp"

using namespace cgagen::emit;

TEST_CASE("a file stem becomes an identifier as CMake's MAKE_C_IDENTIFIER makes it", "[names]") {
  CHECK(c_identifier("my-kernel") == "my_kernel");
  CHECK(c_identifier("2pga") == "_2pga");
  CHECK(c_identifier("a.b c") == "a_b_c");
  CHECK(c_identifier("class") == "class");
  CHECK(c_identifier("\xc3\xa9t\xc3\xa9") == "__t__");
  CHECK(is_identifier("kernel_2"));
  CHECK(is_identifier("_x"));
  CHECK_FALSE(is_identifier("2x"));
  CHECK_FALSE(is_identifier("my-kernel"));
  CHECK_FALSE(is_identifier(""));
}

TEST_CASE("each target spells its reserved words, prefixes and __ differently", "[names]") {
  CHECK(spell(syntax("cpp"), "new") == "new_");
  CHECK(spell(syntax("cpp"), "M_PI") == "M_PI_");
  CHECK(spell(syntax("cpp"), "__x") == "_x");
  CHECK(spell(syntax("cpp"), "_Foo") == "k_Foo");
  CHECK(spell(syntax("glsl"), "gl_x") == "kgl_x");
  CHECK(spell(syntax("glsl"), "new") == "new");  // not a GLSL word
  CHECK(spell(syntax("wgsl"), "_") == "_k");
  CHECK(spell(syntax("python"), "_np") == "_np_");
  CHECK(spell(syntax("python"), "lambda") == "lambda_");
  CHECK(spell(syntax("javascript"), "Math") == "Math_");
  CHECK(spell(syntax("rust"), "None") == "None_");
  CHECK(spell(syntax("rust"), "class") == "class");
  for (const auto& sx : targets()) {
    if (sx.ident) continue;  // LaTeX: math-mode names, no reserved words
    INFO(sx.name);
    for (const auto& w : sx.reserved) {
      const std::string s = spell(sx, w);
      CHECK(s != w);
      CHECK(is_identifier(s));
      CHECK(sx.reserved.count(s) == 0);
      if (sx.single_underscores) CHECK(s.find("__") == std::string::npos);
    }
  }
}

TEST_CASE("a changed name never meets another name of the file", "[names]") {
  const auto m = spellings(syntax("cpp"), {"new", "new_", "a__b", "a_b", "x"});
  CHECK(m.at("new_") == "new_");
  CHECK(m.at("new") == "new_2");
  CHECK(m.at("a_b") == "a_b");
  CHECK(m.at("a__b") == "a_b_2");
  CHECK(m.at("x") == "x");
  std::set<std::string> distinct;
  for (const auto& [k, v] : m) distinct.insert(v);
  CHECK(distinct.size() == m.size());
}

TEST_CASE("the --name value must be an identifier, the stem is made one", "[names][cli]") {
  const std::string dir = std::string(CGA_BINARY_DIR) + "/names";
  std::filesystem::create_directories(dir);
  const std::string text = "?new = float + int * double;\n?default = this;\n";
  auto r = cga_test::run("--name my-k " + cga_test::write_temp("names/kw.clu", text));
  CHECK(r.code == 2);
  CHECK(r.out.find("--name 'my-k' is not a name: use letters, digits and _, not starting with a digit") !=
        std::string::npos);
  r = cga_test::run(cga_test::write_temp("names/my-kernel.clu", text));
  CHECK(r.code == 0);
  CHECK(r.out.find("inline void my_kernel(float float_, float int_, float double_, float this_, float new_[1], "
                   "float default_[1])") != std::string::npos);
  r = cga_test::run(cga_test::write_temp("names/2pga.clu", text));
  CHECK(r.out.find("inline void _2pga(") != std::string::npos);
  r = cga_test::run("--target glsl " + cga_test::write_temp("names/class.clu", text));
  CHECK(r.out.find("void class_(float float_, float int_, float double_, float this_, out float new[1], out float "
                   "default_[1])") != std::string::npos);
  r = cga_test::run("--target list -v");
  CHECK(r.code == 0);
  size_t lines = 0;
  for (char c : r.out) lines += c == '\n';
  CHECK(lines == targets().size());
  CHECK(r.out.find("wgsl       .wgsl WGSL functions") != std::string::npos);
  CHECK(r.out.find("checked with rustc") != std::string::npos);
}

TEST_CASE("tests/targets/names uses every reserved word as an input and as an output", "[names]") {
  std::set<std::string> inputs, outputs;
  const std::regex line(R"(^\?(\w+) = (\w+) \+ 0\.5 \* (\w+);$)");
  for (const auto& e : std::filesystem::directory_iterator(std::string(CGA_SOURCE_DIR) + "/tests/targets/names")) {
    if (e.path().filename().string().rfind("keywords_", 0) != 0) continue;
    std::ifstream in(e.path());
    for (std::string l; std::getline(in, l);) {
      std::smatch m;
      if (!std::regex_match(l, m, line)) continue;
      outputs.insert(m[1]);
      inputs.insert(m[2]);
      inputs.insert(m[3]);
    }
  }
  size_t words = 0;
  for (const auto& sx : targets())
    for (const auto& w : sx.reserved) {
      INFO(sx.name << ": " << w << " (regenerate: gen_test_names \"[.print-words]\" | python3 make.py)");
      CHECK(inputs.count(w) == 1);
      CHECK(outputs.count(w) == 1);
      ++words;
    }
  CHECK(words > 1000);
}

TEST_CASE("print every reserved word of every target (input of tests/targets/names/make.py)", "[.print-words]") {
  std::set<std::string> all;
  for (const auto& sx : targets()) all.insert(sx.reserved.begin(), sx.reserved.end());
  for (const auto& w : all) std::cout << w << "\n";
}
