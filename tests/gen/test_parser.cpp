// The CluScript front end on valid input: operator precedence and associativity (every pair of binary
// operators, prefix operators), statement forms, macros, pragmas, comments, numbers, source locations,
// and scripts that are deeply nested or large. Error messages are in test_diagnostics.cpp.
#include <catch2/catch.hpp>

#include <string>
#include <utility>
#include <vector>

#include "front/parser.hpp"
#include "front/print.hpp"

using namespace cgagen::front;

namespace {

Script parse_text(const std::string& text) { return parse(SourceFile("t.clu", text)); }

// The S-expression of the right-hand side of "x = SRC;".
std::string expr(const std::string& src) {
  Script s = parse_text("x = " + src + ";");
  REQUIRE(s.statements.size() == 1);
  REQUIRE(s.statements[0]->kind == Stmt::Kind::Assign);
  return to_sexpr(*s.statements[0]->value);
}

std::string script(const std::string& text) { return to_sexpr(parse_text(text)); }

using Row = std::pair<const char*, const char*>;

void check_rows(const std::vector<Row>& rows) {
  for (const auto& [src, want] : rows) {
    INFO("source: " << src);
    CHECK(expr(src) == want);
  }
}

}  // namespace

TEST_CASE("every pair of binary operators: precedence ^ . / * (+ -), all left associative", "[parser]") {
  check_rows({
      {"a + b + c", "(+ (+ a b) c)"},
      {"a + b - c", "(- (+ a b) c)"},
      {"a + b * c", "(+ a (* b c))"},
      {"a + b / c", "(+ a (/ b c))"},
      {"a + b . c", "(+ a (. b c))"},
      {"a + b ^ c", "(+ a (^ b c))"},
      {"a - b + c", "(+ (- a b) c)"},
      {"a - b - c", "(- (- a b) c)"},
      {"a - b * c", "(- a (* b c))"},
      {"a - b / c", "(- a (/ b c))"},
      {"a - b . c", "(- a (. b c))"},
      {"a - b ^ c", "(- a (^ b c))"},
      {"a * b + c", "(+ (* a b) c)"},
      {"a * b - c", "(- (* a b) c)"},
      {"a * b * c", "(* (* a b) c)"},
      {"a * b / c", "(* a (/ b c))"},
      {"a * b . c", "(* a (. b c))"},
      {"a * b ^ c", "(* a (^ b c))"},
      {"a / b + c", "(+ (/ a b) c)"},
      {"a / b - c", "(- (/ a b) c)"},
      {"a / b * c", "(* (/ a b) c)"},
      {"a / b / c", "(/ (/ a b) c)"},
      {"a / b . c", "(/ a (. b c))"},
      {"a / b ^ c", "(/ a (^ b c))"},
      {"a . b + c", "(+ (. a b) c)"},
      {"a . b - c", "(- (. a b) c)"},
      {"a . b * c", "(* (. a b) c)"},
      {"a . b / c", "(/ (. a b) c)"},
      {"a . b . c", "(. (. a b) c)"},
      {"a . b ^ c", "(. a (^ b c))"},
      {"a ^ b + c", "(+ (^ a b) c)"},
      {"a ^ b - c", "(- (^ a b) c)"},
      {"a ^ b * c", "(* (^ a b) c)"},
      {"a ^ b / c", "(/ (^ a b) c)"},
      {"a ^ b . c", "(. (^ a b) c)"},
      {"a ^ b ^ c", "(^ (^ a b) c)"},
  });
}

TEST_CASE("the examples the language spec spells out", "[parser]") {
  check_rows({
      {"e1^einf.e1", "(. (^ e1 einf) e1)"},
      {"a*b/c", "(* a (/ b c))"},
      {"-a*b", "(neg (* a b))"},
      {"~a^b", "(^ (rev a) b)"},
      {"*a^b", "(^ (dual a) b)"},
      {"1-0.5^t^einf", "(- 1 (^ (^ 0.5 t) einf))"},
      {"(1-d1)/(1+d1)*einf^e0", "(* (/ (- 1 d1) (+ 1 d1)) (^ einf e0))"},
      {"-angle1/2*plane", "(neg (* (/ angle1 2) plane))"},
  });
}

TEST_CASE("parentheses override precedence", "[parser]") {
  check_rows({
      {"(a + b) * c", "(* (+ a b) c)"},
      {"a ^ (b . c)", "(^ a (. b c))"},
      {"(a * b) / c", "(/ (* a b) c)"},
      {"a - (b - c)", "(- a (- b c))"},
      {"((((a))))", "a"},
      {"-(a + b)", "(neg (+ a b))"},
      {"~(a * b)", "(rev (* a b))"},
      {"*(p1^p2^p3)", "(dual (^ (^ p1 p2) p3))"},
  });
}

TEST_CASE("prefix operators stack and bind tighter than every binary operator", "[parser]") {
  check_rows({
      {"~*a", "(rev (dual a))"},
      {"*~a", "(dual (rev a))"},
      {"-~a", "(neg (rev a))"},
      {"--a", "(neg (neg a))"},
      {"~~a", "(rev (rev a))"},
      {"**a", "(dual (dual a))"},
      {"-*~a", "(neg (dual (rev a)))"},
      {"~a . b", "(. (rev a) b)"},
      {"*a . b", "(. (dual a) b)"},
      {"~a * b", "(* (rev a) b)"},
      {"a * ~b", "(* a (rev b))"},
      {"a * *b", "(* a (dual b))"},
      {"a**b", "(* a (dual b))"},
      {"a ^ ~b ^ c", "(^ (^ a (rev b)) c)"},
      {"M*X*~M", "(* (* M X) (rev M))"},
  });
}

TEST_CASE("unary minus: loosest at the start of a term, tight after a product operator", "[parser]") {
  check_rows({
      {"-a + b", "(+ (neg a) b)"},
      {"-a - b", "(- (neg a) b)"},
      {"-a / b", "(neg (/ a b))"},
      {"-a . b", "(neg (. a b))"},
      {"-a ^ b", "(neg (^ a b))"},
      {"a + -b", "(+ a (neg b))"},
      {"a - -b", "(- a (neg b))"},
      {"a - -b * c", "(- a (neg (* b c)))"},
      // After * / . ^ a minus negates one operand, as in Gaalop (a*-b, a^-b).
      {"a * -b", "(* a (neg b))"},
      {"a ^ -b", "(^ a (neg b))"},
      {"a . -b", "(. a (neg b))"},
      {"a / -b", "(/ a (neg b))"},
      {"a * -b * c", "(* (* a (neg b)) c)"},
      {"a * -b / c", "(* a (/ (neg b) c))"},
      {"a ^ -b ^ c", "(^ (^ a (neg b)) c)"},
      {"~-a", "(rev (neg a))"},
      {"*-a ^ b", "(^ (dual (neg a)) b)"},
      // Unary plus changes nothing.
      {"+a", "a"},
      {"a * +b", "(* a b)"},
      {"+-a", "(neg a)"},
      {"-+a", "(neg a)"},
  });
}

TEST_CASE("calls and macro arguments", "[parser]") {
  check_rows({
      {"f()", "(call f)"},
      {"sqrt(x)", "(call sqrt x)"},
      {"atan2(y, x)", "(call atan2 y x)"},
      {"VecN3(x+1, y*2, -z)", "(call VecN3 (+ x 1) (* y 2) (neg z))"},
      {"f (a)", "(call f a)"},
      {"f(g(h(a)), b)", "(call f (call g (call h a)) b)"},
      {"-f(a)^b", "(neg (^ (call f a) b))"},
      {"~f(a)", "(rev (call f a))"},
      {"_P(1)", "_P1"},
      {"_P( 12 )", "_P12"},
      {"_P(007)", "_P7"},
      {"_P(1)*_P(2)", "(* _P1 _P2)"},
      {"_P", "_P"},
      {"_Px", "_Px"},
  });
}

TEST_CASE("numbers are kept as written", "[parser]") {
  check_rows({
      {"12", "12"},
      {"0.5", "0.5"},
      {".5", ".5"},
      {"5.", "5."},
      {"1e-3", "1e-3"},
      {"2.5E+2", "2.5E+2"},
      {"1e5", "1e5"},
      // A '.' right after digits belongs to the number, as in Gaalop's lexer: 2.e1 is twenty.
      {"2.e1", "2.e1"},
      {"2 .e1", "(. 2 e1)"},
      {"2. . e1", "(. 2. e1)"},
      // Gaalop's float type suffix is accepted and dropped.
      {"1.5f", "1.5"},
      {"2d", "2"},
  });
}

TEST_CASE("statement forms", "[parser]") {
  CHECK(script("x = a;") == "(= x a)\n");
  CHECK(script("?x = a;") == "(?= x a)\n");
  CHECK(script("?x;") == "(? x)\n");
  CHECK(script(":x = a;") == "(:= x a)\n");
  CHECK(script(":x;") == "(: x)\n");
  CHECK(script("!x = a;") == "(!= x a)\n");
  CHECK(script("a * b;") == "(expr (* a b))\n");
  CHECK(script("f(a);") == "(expr (call f a))\n");
  CHECK(script("x;") == "(expr x)\n");
  // Empty statements and CLUCalc display settings leave nothing behind.
  CHECK(script(";;x = 1;;") == "(= x 1)\n");
  CHECK(script(":IPNS; :Red; x = 1; :OPNS;") == "(= x 1)\n");
  CHECK(script("") == "");
  CHECK(script("  \n\t\n") == "");

  Script s = parse_text("?x = a;\n:y;\n!z = 1;\nw = 2;");
  REQUIRE(s.statements.size() == 4);
  CHECK(s.statements[0]->marker == Marker::Output);
  CHECK(s.statements[0]->name == "x");
  CHECK(s.statements[1]->marker == Marker::Visual);
  CHECK(s.statements[1]->value == nullptr);
  CHECK(s.statements[2]->marker == Marker::EvalOnly);
  CHECK(s.statements[3]->marker == Marker::None);
  // A statement's location is its name (Assign) or where its expression starts (ExprStmt).
  CHECK(s.statements[0]->loc.line == 1);
  CHECK(s.statements[0]->loc.col == 2);
  CHECK(s.statements[1]->loc.line == 2);
  CHECK(s.statements[1]->loc.col == 2);
  Script e = parse_text("  -a;");
  CHECK(e.statements[0]->loc.col == 3);
}

TEST_CASE("if/else: conditions, branches, else-if chains (Gaalop 2.0)", "[parser][if]") {
  // Comparisons bind looser than every operator; ! tighter than &&, && tighter than ||.
  CHECK(script("if (a + b < c*d) x = 1;") == "(if (< (+ a b) (* c d)) (then (= x 1)))\n");
  CHECK(script("if (a <= b && !(c >= d) || e != f) { x = 1; } else { x = 2; y = 3; }") ==
        "(if (|| (&& (<= a b) (! (>= c d))) (!= e f)) (then (= x 1)) (else (= x 2) (= y 3)))\n");
  CHECK(script("if (a == b) ?x = 1; else if (a > b) ?x = 2; else ?x = 3;") ==
        "(if (== a b) (then (?= x 1)) (else (if (> a b) (then (?= x 2)) (else (?= x 3)))))\n");
  // Parentheses around a condition, around an operand, and nested; a scalar alone; ! of a scalar.
  CHECK(script("if (((a < b))) x = 1;") == "(if (< a b) (then (= x 1)))\n");
  CHECK(script("if ((a + b) < c) x = 1;") == "(if (< (+ a b) c) (then (= x 1)))\n");
  CHECK(script("if (!a) x = 1;") == "(if (! a) (then (= x 1)))\n");
  CHECK(script("if (a) {} else {}") == "(if a (then) (else))\n");
  // A block holds any statements, loops included; the 'else' is located.
  Script s = parse_text("if (a < b) {\n  x = 1;\n  #pragma unroll 2\n  loop x = x*2;\n}\nelse x = 0;");
  REQUIRE(s.statements.size() == 1);
  const Stmt& st = *s.statements[0];
  CHECK(st.kind == Stmt::Kind::If);
  CHECK(st.body.size() == 3);
  CHECK(st.else_body.size() == 1);
  CHECK(st.else_loc.line == 6);
  CHECK(st.else_loc.col == 1);
  // 'if' and 'else' stay ordinary names where they are assigned.
  CHECK(script("else = 2; if = 3;") == "(= else 2)\n(= if 3)\n");
}

TEST_CASE("if/else: malformed conditions and branches are located errors", "[parser][if]") {
  auto error_at = [](const std::string& text) -> std::string {
    try {
      parse_text(text);
    } catch (const CompileError& e) {
      return std::to_string(e.loc().line) + ":" + std::to_string(e.loc().col) + " " + e.what();
    }
    return "no error";
  };
  CHECK(error_at("if (a < b x = 1;").find("1:10 expected ')' to close the condition of 'if'") == 0);
  CHECK(error_at("if (a = b) x = 1;").find("1:7 '=' in a condition") == 0);
  CHECK(error_at("if (a < b < c) x = 1;").find("1:11 comparisons do not chain") == 0);
  CHECK(error_at("x = a < b;").find("1:7 '<' may only appear in the condition of an 'if'") == 0);
  CHECK(error_at("x = a && b;").find("1:7 '&&' may only appear") == 0);
  CHECK(error_at("if (a < b) {\n x = 1;").find("2:8 expected '}' to close the 'if' at 1:1") == 0);
  CHECK(error_at("if (a < b)").find("1:11 expected a statement or '{' after 'if'") == 0);
  CHECK(error_at("if (a < b) x = 1; else { M = { 1 } }").find("1:26 a macro cannot be defined inside 'else'") == 0);
  CHECK(error_at("else x = 1;").find("1:1 'else' without an 'if'") == 0);
  CHECK(error_at("if (a < ) x = 1;").find("1:9 expected expression") == 0);
  // Parentheses around a condition nest up to the limit, like any others; deeper is the nesting error.
  CHECK(script("if (" + std::string(200, '(') + "a < b" + std::string(200, ')') + ") x = 1;") ==
        "(if (< a b) (then (= x 1)))\n");
  const std::string deep = "if (" + std::string(100000, '(') + "a < b" + std::string(100000, ')') + ") x = 1;";
  CHECK(error_at(deep).find("expression nested too deeply") != std::string::npos);
}

TEST_CASE("macro definitions", "[parser]") {
  CHECK(script("M = { _P(1) * 2 }") == "(macro M (result (* _P1 2)))\n");
  CHECK(script("M = { _P(1) * 2 };") == "(macro M (result (* _P1 2)))\n");
  CHECK(script("M = { a = _P(1); b = a*a; a + b }") ==
        "(macro M (= a _P1) (= b (* a a)) (result (+ a b)))\n");
  // Without a final expression the body ends with a statement.
  CHECK(script("M = { a = _P(1); ?a; }") == "(macro M (= a _P1) (? a))\n");
  CHECK(script("M = { _P(1); }") == "(macro M (expr _P1))\n");
  CHECK(script("M = { }") == "(macro M)\n");
  CHECK(script("M = { f(_P(1)); g(_P(2)) }") == "(macro M (expr (call f _P1)) (result (call g _P2)))\n");
  // A macro body may hold another definition; the expander gives it meaning.
  CHECK(script("M = { N = { _P(1) } N(_P(1)) }") == "(macro M (macro N (result _P1)) (result (call N _P1)))\n");
  CHECK(script("M = { 1 }\nx = M();") == "(macro M (result 1))\n(= x (call M))\n");

  Script s = parse_text("\n  Exp_approx = {\n  1 + _P(1)\n};");
  REQUIRE(s.statements.size() == 1);
  const Stmt& m = *s.statements[0];
  CHECK(m.kind == Stmt::Kind::MacroDef);
  CHECK(m.name == "Exp_approx");
  CHECK(m.loc.line == 2);
  CHECK(m.loc.col == 3);
  REQUIRE(m.result);
  CHECK(m.body.empty());
  CHECK(m.result->args.at(1)->kind == Expr::Kind::MacroArg);
  CHECK(m.result->args.at(1)->index == 1);
  CHECK(m.result->args.at(1)->loc.line == 3);
  CHECK(m.result->args.at(1)->loc.col == 7);
}

TEST_CASE("pragmas: both spellings, words and their locations", "[parser]") {
  Script s = parse_text("//#pragma range 0 <= alpha <= 1\n  #pragma output M 1\te1^e2\nx = 1;\n");
  REQUIRE(s.statements.size() == 3);
  const Stmt& r = *s.statements[0];
  CHECK(r.kind == Stmt::Kind::Pragma);
  CHECK(r.words == std::vector<std::string>{"range", "0", "<=", "alpha", "<=", "1"});
  // The pragma's location is its '#'.
  CHECK(r.loc.line == 1);
  CHECK(r.loc.col == 3);
  REQUIRE(r.word_locs.size() == 6);
  const int cols[] = {11, 17, 19, 22, 28, 31};
  for (size_t i = 0; i < 6; ++i) {
    CHECK(r.word_locs[i].line == 1);
    CHECK(r.word_locs[i].col == cols[i]);
  }
  const Stmt& o = *s.statements[1];
  CHECK(o.words == std::vector<std::string>{"output", "M", "1", "e1^e2"});
  CHECK(o.loc.line == 2);
  CHECK(o.loc.col == 3);
  CHECK(o.word_locs.at(2).col == 20);
  CHECK(o.word_locs.at(3).col == 22);  // after a tab
  CHECK(to_sexpr(*s.statements[2]) == "(= x 1)");

  // A trailing line comment is not part of the words; a pragma needs no ';'.
  CHECK(script("#pragma output M e1 // keep e1 only\n?M = a;") == "(pragma output M e1)\n(?= M a)\n");
  // CRLF line ends do not leak into the last word.
  CHECK(script("#pragma input M 1\r\nx = 1;\r\n") == "(pragma input M 1)\n(= x 1)\n");
  // A pragma may end the file without a newline.
  CHECK(script("x = 1;\n#pragma range 0<=t<=1") == "(= x 1)\n(pragma range 0<=t<=1)\n");
  // Inside a macro body it is a statement like any other (the expander rejects it there).
  CHECK(script("M = {\n#pragma output a\n1 }") == "(macro M (pragma output a) (result 1))\n");
}

TEST_CASE("comments", "[parser]") {
  CHECK(script("// a comment\nx = 1; // another\n") == "(= x 1)\n");
  CHECK(script("x = /* inline */ 1;") == "(= x 1)\n");
  CHECK(script("/* a\n * block\n */ x = 1;") == "(= x 1)\n");
  CHECK(script("x = 1; /* unclosed? no: */ y = 2;") == "(= x 1)\n(= y 2)\n");
  CHECK(script("/* /* not nested */ x = 1;") == "(= x 1)\n");
  CHECK(script("x = 1; //") == "(= x 1)\n");
  // Only "//#pragma" and "#pragma" make a pragma; these are comments.
  CHECK(script("// #pragma output x\n//#pragmatic\nx = 1;") == "(= x 1)\n");
  CHECK(script("x = 1; //#pragma output x\n") == "(= x 1)\n");
  CHECK(script("/* c */ //#pragma output x\n") == "");
  // A comment between tokens is blank space.
  CHECK(script("x = a/**/+/**/b;") == "(= x (+ a b))\n");
}

TEST_CASE("source locations: operator token for unary and binary, name for calls", "[parser]") {
  Script s = parse_text("/* two\nlines */ x = a +\n  f(b) * -c;");
  REQUIRE(s.statements.size() == 1);
  const Stmt& st = *s.statements[0];
  CHECK(st.loc.line == 2);
  CHECK(st.loc.col == 10);
  const Expr& add = *st.value;
  REQUIRE(add.kind == Expr::Kind::Binary);
  CHECK(add.binary_op == BinaryOp::Add);
  CHECK(add.loc.line == 2);
  CHECK(add.loc.col == 16);
  const Expr& a = *add.args[0];
  CHECK(a.kind == Expr::Kind::Name);
  CHECK(a.loc.col == 14);
  const Expr& mul = *add.args[1];
  CHECK(mul.binary_op == BinaryOp::Geo);
  CHECK(mul.loc.line == 3);
  CHECK(mul.loc.col == 8);
  const Expr& call = *mul.args[0];
  CHECK(call.kind == Expr::Kind::Call);
  CHECK(call.text == "f");
  CHECK(call.loc.col == 3);
  CHECK(call.args.at(0)->loc.col == 5);
  const Expr& neg = *mul.args[1];
  CHECK(neg.kind == Expr::Kind::Unary);
  CHECK(neg.unary_op == UnaryOp::Negate);
  CHECK(neg.loc.col == 10);
  CHECK(neg.args.at(0)->loc.col == 11);
  // Tabs count as one column.
  Script t = parse_text("\tx =\t2.5;");
  CHECK(t.statements[0]->loc.col == 2);
  CHECK(t.statements[0]->value->loc.col == 6);
}

TEST_CASE("the bundled scripts parse", "[parser]") {
  for (const char* name : {"circle3.clu", "paper_a1.clu", "paper_motor.clu", "plane_distance.clu", "rotor_n3.clu",
                           "translator_inverse.clu"}) {
    INFO(name);
    SourceFile file = SourceFile::load(std::string(CGA_TEST_SCRIPTS) + "/" + name);
    Script s = parse(file);
    CHECK(!s.statements.empty());
  }
  Script a1 = parse(SourceFile::load(std::string(CGA_TEST_SCRIPTS) + "/paper_a1.clu"));
  std::string text = to_sexpr(a1);
  CHECK(text.find("(= translationCGA (- 1 (^ (^ 0.5 translationGA) einf)))") != std::string::npos);
  CHECK(text.find("(?= vertexPos (* (* finalInterpolation (call VecN3 X Y Z)) (rev finalInterpolation)))") !=
        std::string::npos);
}

TEST_CASE("nesting up to the limit and long scripts parse", "[parser][stress]") {
  // 200 levels of parentheses, prefix operators and calls are fine (the limit is 256).
  std::string parens = std::string(200, '(') + "a" + std::string(200, ')');
  CHECK(expr(parens) == "a");
  std::string tildes = std::string(200, '~') + "a";
  CHECK(expr(tildes).substr(0, 10) == "(rev (rev ");
  std::string calls;
  for (int i = 0; i < 200; ++i) calls += "f(";
  calls += "a" + std::string(200, ')');
  CHECK(expr(calls).substr(0, 14) == "(call f (call ");
  // A chain of 1500 additions stays under the tree-depth limit.
  std::string chain = "a";
  for (int i = 0; i < 1500; ++i) chain += "+a";
  Script c = parse_text("x = " + chain + ";");
  CHECK(c.statements.size() == 1);

  // About 4 MB of statements.
  std::string big;
  int n = 0;
  while (big.size() < 4'000'000) {
    std::string i = std::to_string(n++);
    big += "v" + i + " = (a*e1 + 0.5^b" + i + "^einf).e2 - ~M*X*~M / sqrt(abs(c" + i + ")); // note " + i + "\n";
    if (n % 1000 == 0) big += "M" + i + " = { _P(1) * ~_P(1) }\n/* block\n comment */\n#pragma range 0 <= t <= 1\n";
  }
  Script s = parse_text(big);
  CHECK(s.statements.size() == static_cast<size_t>(n + 2 * (n / 1000)));
  const Stmt& last = *s.statements.back();
  CHECK(last.kind == Stmt::Kind::Assign);
  CHECK(last.name == "v" + std::to_string(n - 1));
}
