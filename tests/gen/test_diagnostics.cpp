// Every error the front end can report, checked as the full rendered diagnostic (`file:line:col: error:
// message`, the source line, the caret), plus SourceFile and format_diagnostic on their own.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>
#include <string>

#include "front/diagnostics.hpp"
#include "front/parser.hpp"

using namespace cgagen::front;

namespace {

// The rendered diagnostic for a script that must fail to parse.
std::string diag(const std::string& text) {
  SourceFile file("t.clu", text);
  try {
    parse(file);
  } catch (const CompileError& e) {
    return format_diagnostic(file, e.loc(), e.what());
  }
  FAIL("no error for: " << text);
  return "";
}

// What a diagnostic must look like: the header, the line, and a caret after `pad`.
std::string want(int line, int col, const std::string& message, const std::string& source_line,
                 const std::string& pad) {
  return "t.clu:" + std::to_string(line) + ":" + std::to_string(col) + ": error: " + message + "\n" + source_line +
         "\n" + pad + "^\n";
}

std::string spaces(int n) { return std::string(static_cast<size_t>(n), ' '); }

// want() for a long ASCII line: format_diagnostic quotes the 120 columns from 60 before the column ("..."
// where it cuts), the caret under the column.
std::string want_cut(int line, int col, const std::string& message, const std::string& source_line) {
  const size_t at = static_cast<size_t>(col - 1), n = source_line.size();
  const size_t first = n > 120 && at > 60 ? at - 60 : 0;
  const size_t last = n > 120 ? std::min(n, first + 120) : n;
  const std::string quote =
      (first ? "..." : "") + source_line.substr(first, last - first) + (last < n ? "..." : "");
  return want(line, col, message, quote, spaces(static_cast<int>((first ? 3 : 0) + at - first)));
}

}  // namespace

TEST_CASE("SourceFile: lines, CRLF, out of range, load", "[diagnostics]") {
  SourceFile f("a.clu", "one\r\ntwo\n\nlast");
  CHECK(f.path() == "a.clu");
  CHECK(f.line(1) == "one");
  CHECK(f.line(2) == "two");
  CHECK(f.line(3) == "");
  CHECK(f.line(4) == "last");
  CHECK(f.line(5) == "");
  CHECK(f.line(0) == "");
  CHECK(f.line(-3) == "");

  const std::string path = "test_diagnostics_load.clu";
  {
    std::ofstream out(path, std::ios::binary);
    out << "x = 1;\n?x;\n";
  }
  SourceFile loaded = SourceFile::load(path);
  CHECK(loaded.text() == "x = 1;\n?x;\n");
  CHECK(loaded.line(2) == "?x;");
  std::remove(path.c_str());

  try {
    SourceFile::load("/nonexistent/dir/missing.clu");
    FAIL("load of a missing file did not throw");
  } catch (const std::runtime_error& e) {
    CHECK(std::string(e.what()) == "cannot read /nonexistent/dir/missing.clu: No such file or directory");
  }
}

TEST_CASE("format_diagnostic: tabs, UTF-8, columns past the end, no location", "[diagnostics]") {
  SourceFile f("t.clu", "\tx =\t1 $;\nab\n");
  // Tabs before the column are copied so the caret lines up under any tab width.
  CHECK(format_diagnostic(f, {1, 8}, "m") == "t.clu:1:8: error: m\n\tx =\t1 $;\n\t   \t  ^\n");
  CHECK(format_diagnostic(f, {2, 1}, "m") == "t.clu:2:1: error: m\nab\n^\n");
  CHECK(format_diagnostic(f, {2, 5}, "m") == "t.clu:2:5: error: m\nab\n    ^\n");
  CHECK(format_diagnostic(f, {0, 0}, "m") == "t.clu: error: m\n");
  // Columns are bytes; the caret moves one place per UTF-8 character.
  SourceFile u("t.clu", "/* \xC3\xA9 */ x = $;");
  CHECK(format_diagnostic(u, {1, 14}, "m") == "t.clu:1:14: error: m\n/* \xC3\xA9 */ x = $;\n" + spaces(12) + "^\n");
}

TEST_CASE("lexer errors", "[diagnostics]") {
  CHECK(diag("x = 1 $;") == want(1, 7, "unexpected character '$'", "x = 1 $;", spaces(6)));
  CHECK(diag("y = 2;\nx = a % b;") == want(2, 7, "unexpected character '%'", "x = a % b;", spaces(6)));
  CHECK(diag(std::string("x = \x01;")) == want(1, 5, "unexpected character '\\x01'", "x = \\x01;", spaces(4)));
  CHECK(diag("x = \xC3\xA9;") == want(1, 5, "unexpected character '\xC3\xA9'", "x = \xC3\xA9;", spaces(4)));
  CHECK(diag("x = \xFF;") == want(1, 5, "unexpected character '\\xFF'", "x = \\xFF;", spaces(4)));
  CHECK(diag("x = 1 $;\r\n") == want(1, 7, "unexpected character '$'", "x = 1 $;", spaces(6)));
  CHECK(diag("x = 1;\n  /* never closed\ny = 2;") ==
        want(2, 3, "unterminated block comment", "  /* never closed", spaces(2)));
  CHECK(diag("x = 2.einf;") == want(1, 5, "invalid number '2.einf'", "x = 2.einf;", spaces(4)));
  CHECK(diag("x = 12abc;") == want(1, 5, "invalid number '12abc'", "x = 12abc;", spaces(4)));
  CHECK(diag("x = 2e;") == want(1, 5, "invalid number '2e'", "x = 2e;", spaces(4)));
  CHECK(diag("x = 1.5e+;") == want(1, 5, "invalid number '1.5e'", "x = 1.5e+;", spaces(4)));
}

TEST_CASE("pragma errors", "[diagnostics]") {
  CHECK(diag("#pragma\nx = 1;") == want(1, 1, "empty pragma", "#pragma", ""));
  CHECK(diag("  //#pragma   \n") == want(1, 5, "empty pragma", "  //#pragma   ", spaces(4)));
  CHECK(diag("#pragma // only a comment") == want(1, 1, "empty pragma", "#pragma // only a comment", ""));
  CHECK(diag("x = 1; #pragma output x") ==
        want(1, 8, "'#pragma' must be the first thing on its line", "x = 1; #pragma output x", spaces(7)));
  const std::string hash = "unexpected character '#' (a pragma is written '#pragma WORDS...')";
  CHECK(diag("#define X 1") == want(1, 1, hash, "#define X 1", ""));
  CHECK(diag("#pragmatic x") == want(1, 1, hash, "#pragmatic x", ""));
  CHECK(diag("x = a +\n#pragma output x\n b;") ==
        want(2, 1, "a pragma cannot appear inside a statement", "#pragma output x", ""));
}

TEST_CASE("statement errors", "[diagnostics]") {
  const std::string semi = "expected ';' after statement";
  CHECK(diag("x = a b;") == want(1, 6, semi, "x = a b;", spaces(5)));
  // A missing ';' at the end of a line is reported there, not on the next line.
  CHECK(diag("x = 1\ny = 2;") == want(1, 6, semi, "x = 1", spaces(5)));
  CHECK(diag("x = 1\n") == want(1, 6, semi, "x = 1", spaces(5)));
  CHECK(diag("x = a = b;") == want(1, 7, semi, "x = a = b;", spaces(6)));
  CHECK(diag("f(a) g;") == want(1, 5, semi, "f(a) g;", spaces(4)));
  CHECK(diag("x = a/**/b;") == want(1, 6, semi, "x = a/**/b;", spaces(5)));
  CHECK(diag("x = a.5;") == want(1, 6, semi, "x = a.5;", spaces(5)));

  const std::string lhs = "the left side of '=' must be a name";
  CHECK(diag("3 = x;") == want(1, 3, lhs, "3 = x;", spaces(2)));
  CHECK(diag("a + b = c;") == want(1, 7, lhs, "a + b = c;", spaces(6)));
  CHECK(diag("M = { a * b = 1 }") == want(1, 13, lhs, "M = { a * b = 1 }", spaces(12)));

  CHECK(diag("? = 1;") == want(1, 2, "expected a name after '?'", "? = 1;", spaces(1)));
  CHECK(diag(": 3;") == want(1, 2, "expected a name after ':'", ": 3;", spaces(1)));
  CHECK(diag("!;") == want(1, 2, "expected a name after '!'", "!;", spaces(1)));
  CHECK(diag("!x;") == want(1, 3, "expected '=' after '!x'", "!x;", spaces(2)));
  CHECK(diag("?x + 1;") == want(1, 3, "expected '=' or ';' after '?x'", "?x + 1;", spaces(2)));
  CHECK(diag(":x y") == want(1, 3, "expected '=' or ';' after ':x'", ":x y", spaces(2)));
  CHECK(diag("?x") == want(1, 3, "expected '=' or ';' after '?x'", "?x", spaces(2)));
  CHECK(diag("?M = { 1 }") == want(1, 6, "a macro definition cannot be marked with '?'", "?M = { 1 }", spaces(5)));

  const std::string brace = "unexpected '{' (braces only enclose a macro body: Name = { ... })";
  CHECK(diag("{ x = 1; }") == want(1, 1, brace, "{ x = 1; }", ""));
  CHECK(diag("M = { { 1 } }") == want(1, 7, brace, "M = { { 1 } }", spaces(6)));
  CHECK(diag("x = 1; }") == want(1, 8, "unexpected '}'", "x = 1; }", spaces(7)));
  CHECK(diag("M = { 1 } }") == want(1, 11, "unexpected '}'", "M = { 1 } }", spaces(10)));
}

TEST_CASE("macro errors", "[diagnostics]") {
  CHECK(diag("M = {\n  a = 1;\n") ==
        want(2, 9, "expected '}' to close macro 'M' opened at 1:5", "  a = 1;", spaces(8)));
  CHECK(diag("M = { 1 + 2") == want(1, 12, "expected '}' to close macro 'M' opened at 1:5", "M = { 1 + 2", spaces(11)));
  CHECK(diag("M = { a b }") ==
        want(1, 8, "expected ';' or '}' after expression in macro 'M'", "M = { a b }", spaces(7)));

  const std::string arg = "macro argument must be _P(<positive integer>)";
  CHECK(diag("M = { _P(0) }") == want(1, 7, arg, "M = { _P(0) }", spaces(6)));
  CHECK(diag("M = { _P(x) }") == want(1, 7, arg, "M = { _P(x) }", spaces(6)));
  CHECK(diag("M = { _P(1.5) }") == want(1, 7, arg, "M = { _P(1.5) }", spaces(6)));
  CHECK(diag("M = { _P(-1) }") == want(1, 7, arg, "M = { _P(-1) }", spaces(6)));
  CHECK(diag("M = { _P() }") == want(1, 7, arg, "M = { _P() }", spaces(6)));
  CHECK(diag("M = { _P(1 }") == want(1, 7, arg, "M = { _P(1 }", spaces(6)));
  CHECK(diag("M = { _P(12345678901) }") == want(1, 7, arg, "M = { _P(12345678901) }", spaces(6)));
  CHECK(diag("x = _P(") == want(1, 5, arg, "x = _P(", spaces(4)));
}

TEST_CASE("expression errors", "[diagnostics]") {
  CHECK(diag("x = ;") == want(1, 5, "expected expression, found ';'", "x = ;", spaces(4)));
  CHECK(diag("x = )") == want(1, 5, "expected expression, found ')'", "x = )", spaces(4)));
  CHECK(diag("x = }") == want(1, 5, "expected expression, found '}'", "x = }", spaces(4)));
  CHECK(diag("= 1;") == want(1, 1, "expected expression, found '='", "= 1;", ""));
  CHECK(diag("x = a ^ ^ b;") == want(1, 9, "expected expression, found '^'", "x = a ^ ^ b;", spaces(8)));
  CHECK(diag("x = a . / b;") == want(1, 9, "expected expression, found '/'", "x = a . / b;", spaces(8)));
  CHECK(diag("x = 1 +") == want(1, 8, "expected expression", "x = 1 +", spaces(7)));
  CHECK(diag("x = f(a,") == want(1, 9, "expected expression", "x = f(a,", spaces(8)));
  CHECK(diag("x = (a\ny = 2;") == want(1, 7, "expected ')' to close '(' at 1:5", "x = (a", spaces(6)));
  CHECK(diag("x = ((a + b) * c;") ==
        want(1, 17, "expected ')' to close '(' at 1:5", "x = ((a + b) * c;", spaces(16)));
  CHECK(diag("x = f(a b);") ==
        want(1, 8, "expected ',' or ')' in call to 'f' opened at 1:6", "x = f(a b);", spaces(7)));
  CHECK(diag("x = g(1, 2") ==
        want(1, 11, "expected ',' or ')' in call to 'g' opened at 1:6", "x = g(1, 2", spaces(10)));
}

TEST_CASE("deep nesting is an error, never a stack overflow", "[diagnostics][stress]") {
  const std::string deep = "expression nested too deeply (more than 256 levels)";
  // The 257th '(' is at column 4 + 257.
  std::string parens = "x = " + std::string(300, '(') + "a" + std::string(300, ')') + ";";
  CHECK(diag(parens) == want_cut(1, 261, deep, parens));
  std::string tildes = "x = " + std::string(300, '~') + "a;";
  CHECK(diag(tildes) == want_cut(1, 261, deep, tildes));
  std::string minuses = "x = " + std::string(300, '-') + "a;";
  CHECK(diag(minuses) == want_cut(1, 261, deep, minuses));
  std::string stars = "x = a*" + std::string(300, '*') + "a;";
  CHECK(diag(stars) == want_cut(1, 263, deep, stars));
  // The 257th call's '(' is at column 6 + 2*256.
  std::string calls = "x = ";
  for (int i = 0; i < 300; ++i) calls += "f(";
  calls += "a" + std::string(300, ')') + ";";
  CHECK(diag(calls) == want_cut(1, 518, deep, calls));
  // The 257th nested macro's '{' is at column 5 + 6*256.
  std::string macros;
  for (int i = 0; i < 300; ++i) macros += "M = { ";
  macros += std::string(300, '}');
  CHECK(diag(macros) == want_cut(1, 1541, deep, macros));
  // 100000 open parentheses.
  std::string huge = "x = " + std::string(100000, '(') + "a";
  std::string d = diag(huge);
  CHECK(d.substr(0, d.find('\n')) == "t.clu:1:261: error: " + deep);
}

TEST_CASE("an operator chain too deep for the later stages is an error", "[diagnostics][stress]") {
  // Left-associative chains build trees as deep as they are long; the 2000th '+' crosses the limit.
  std::string chain = "x = a";
  for (int i = 0; i < 2500; ++i) chain += "+a";
  chain += ";";
  CHECK(diag(chain) == want_cut(1, 4004,
                            "expression too long (more than 2000 nested operations); split it into several assignments",
                            chain));
}
