// Recursive-descent parser for CluScript (grammar in docs/language.md). One function per precedence level,
// loosest first: additive (+ -), unary minus, geometric (*), division (/), inner (.), outer (^), prefix
// (* ~, and - + right after a tighter operator, as Gaalop allows in a*-b), primary.
// Recursion is bounded (kMaxNesting) and so is the depth of the tree a long operator chain builds
// (kMaxTreeDepth), so no input can overflow the stack here or in the stages that walk the tree.
#include <algorithm>
#include <deque>
#include <optional>
#include <string>

#include "front/lexer.hpp"
#include "front/parser.hpp"

namespace cgagen::front {
namespace {

constexpr int kMaxNesting = 256;     // parentheses, prefix operators, call arguments, macro bodies
constexpr int kMaxTreeDepth = 2000;  // operators on one path from the root of an expression to a leaf

std::string at_text(SourceLoc loc) { return std::to_string(loc.line) + ":" + std::to_string(loc.col); }

// An expression and the depth of its tree (a leaf is 1).
struct Parsed {
  ExprPtr expr;
  int depth = 1;
};

// Words that CLUCalc uses after ':' for display settings (":IPNS;", ":Red;"); they mean nothing here.
bool is_display_directive(std::string_view name) {
  for (std::string_view w : {"IPNS", "OPNS", "Black", "Blue", "Cyan", "Green", "Magenta", "Orange", "Red", "White",
                             "Yellow"})
    if (name == w) return true;
  return false;
}

class Parser {
 public:
  explicit Parser(const SourceFile& file) : lexer_(file.text()) {}

  Script script() {
    Script s;
    while (peek().kind != TokKind::End) {
      if (peek().kind == TokKind::RBrace) throw CompileError(peek().loc, "unexpected '}'");
      if (is_unroll()) {
        unrolled_loop(s.statements);
        continue;
      }
      if (StmtPtr st = statement()) s.statements.push_back(std::move(st));
    }
    s.warnings = std::move(warnings_);
    return s;
  }

 private:
  // ---- tokens --------------------------------------------------------------------------------------
  const Token& peek(size_t k = 0) {
    while (ahead_.size() <= k) ahead_.push_back(lexer_.next());
    return ahead_[k];
  }
  Token take() {
    peek();
    Token t = std::move(ahead_.front());
    ahead_.pop_front();
    if (t.kind != TokKind::End) prev_end_ = t.end();
    return t;
  }
  bool accept(TokKind kind) {
    if (peek().kind != kind) return false;
    take();
    return true;
  }
  // "expected ..." errors point just past the previous token: where the missing text belongs.
  [[noreturn]] void fail_after(const std::string& message) { throw CompileError(prev_end_, message); }
  void expect(TokKind kind, const std::string& message) {
    if (!accept(kind)) fail_after(message);
  }

  // Counts one level of recursion for the lifetime of the guard.
  struct Nest {
    Nest(Parser& p, SourceLoc loc) : p_(p) {
      if (++p_.nesting_ > kMaxNesting)
        throw CompileError(loc, "expression nested too deeply (more than " + std::to_string(kMaxNesting) + " levels)");
    }
    ~Nest() { --p_.nesting_; }
    Nest(const Nest&) = delete;
    Nest& operator=(const Nest&) = delete;
    Parser& p_;
  };

  // ---- loops -------------------------------------------------------------------------------------
  // Gaalop 2.0: "#pragma unroll N" then "loop STATEMENT" or "loop { STATEMENTS }". The trip count is a
  // constant, so the loop is unrolled here: the body's statements N times (nodes are shared, immutable).
  static constexpr long kMaxUnroll = 1000;

  bool is_unroll() {
    return peek().kind == TokKind::Pragma && !peek().words.empty() && peek().words[0] == "unroll";
  }

  void unrolled_loop(std::vector<StmtPtr>& out) {
    Token p = take();
    const SourceLoc count_loc = p.word_locs.size() > 1 ? p.word_locs[1] : p.loc;
    const bool digits = p.words.size() == 2 && !p.words[1].empty() && p.words[1].size() <= 4 &&
                        p.words[1].find_first_not_of("0123456789") == std::string::npos;
    if (!digits) throw CompileError(count_loc, "'#pragma unroll' expects a trip count, a whole number");
    const long n = std::stol(p.words[1]);
    if (n > kMaxUnroll) throw CompileError(count_loc, "'#pragma unroll' trip count above " + std::to_string(kMaxUnroll));
    if (peek().kind != TokKind::Ident || peek().text != "loop")
      throw CompileError(peek().loc, "expected 'loop' after '#pragma unroll'");
    Token loop = take();
    Nest nest(*this, loop.loc);
    std::vector<StmtPtr> body;
    if (accept(TokKind::LBrace)) {
      for (;;) {
        if (peek().kind == TokKind::RBrace) break;
        if (peek().kind == TokKind::End) fail_after("expected '}' to close the loop opened at " + at_text(loop.loc));
        if (is_unroll()) {
          unrolled_loop(body);
          continue;
        }
        if (StmtPtr st = statement()) body.push_back(std::move(st));
      }
      take();  // '}'
    } else if (is_unroll()) {
      unrolled_loop(body);
    } else if (StmtPtr st = statement()) {
      body.push_back(std::move(st));
    }
    for (const auto& st : body)
      if (st->kind == Stmt::Kind::MacroDef) throw CompileError(st->loc, "a macro cannot be defined inside a loop");
    if (static_cast<double>(body.size()) * static_cast<double>(n) + static_cast<double>(out.size()) > 10000)
      throw CompileError(loop.loc, "the unrolled loop would have more than 10000 statements");
    for (long k = 0; k < n; ++k) out.insert(out.end(), body.begin(), body.end());
  }

  // ---- statements ----------------------------------------------------------------------------------
  // One statement, or null for one that has no effect (";" and CLUCalc display settings).
  StmtPtr statement() {
    const Token& t = peek();
    switch (t.kind) {
      case TokKind::Pragma: return pragma();
      case TokKind::Semi: take(); return nullptr;
      case TokKind::Question: return marked(Marker::Output);
      case TokKind::Colon: return marked(Marker::Visual);
      case TokKind::Bang: return marked(Marker::EvalOnly);
      case TokKind::LBrace:
        throw CompileError(t.loc, "unexpected '{' (braces only enclose a macro body: Name = { ... })");
      case TokKind::Ident:
        // Gaalop 2.0's precompiler had if/else, loop and break; cgagen has no control flow yet. Say so
        // instead of "expected ',' or ')' in call to 'if'".
        if (t.text == "loop" && peek(1).kind != TokKind::Assign)
          throw CompileError(t.loc, "'loop' needs '#pragma unroll N' on the line before it: only loops with a "
                                    "constant trip count are supported (they are unrolled)");
        if (t.text == "if" && peek(1).kind == TokKind::LParen) return if_statement();
        if (t.text == "else" && peek(1).kind != TokKind::Assign)
          throw CompileError(t.loc, "'else' without an 'if' before it");
        if ((t.text == "while" && peek(1).kind == TokKind::LParen) ||
            (t.text == "break" && peek(1).kind != TokKind::Assign))
          throw CompileError(t.loc, "'" + std::string(t.text) + "': only if/else and loops with a constant trip count "
                                    "('#pragma unroll N' before 'loop') are supported; a '" + std::string(t.text) +
                                    "' would need a trip count known at generation time");
        if (peek(1).kind == TokKind::Assign) {
          if (peek(2).kind == TokKind::LBrace) return macro();
          return assignment(Marker::None, take());
        }
        break;
      default: break;
    }
    auto st = std::make_shared<Stmt>();
    st->kind = Stmt::Kind::ExprStmt;
    st->loc = t.loc;
    st->value = expression().expr;
    no_assignment_to_expression();
    expect(TokKind::Semi, "expected ';' after statement");
    return st;
  }

  void no_assignment_to_expression() {
    if (peek().kind == TokKind::Assign)
      throw CompileError(peek().loc, "the left side of '=' must be a name");
    no_condition_operator();
  }

  // A comparison or && || outside an if condition: say where they may appear.
  void no_condition_operator() {
    const TokKind k = peek().kind;
    if (k == TokKind::Compare || k == TokKind::AndAnd || k == TokKind::OrOr)
      throw CompileError(peek().loc, "'" + std::string(peek().text) +
                                         "' may only appear in the condition of an 'if' (a value cannot be a truth value)");
  }

  // ---- if / else ---------------------------------------------------------------------------------
  // Gaalop 2.0: if (CONDITION) STATEMENT-OR-BLOCK [else STATEMENT-OR-BLOCK]; 'else if' chains. Both
  // branches are expanded and every name they assign becomes a select per blade (docs/language.md).
  StmtPtr if_statement() {
    Token kw = take();    // 'if'
    Token open = take();  // '('
    Nest nest(*this, kw.loc);
    auto st = std::make_shared<Stmt>();
    st->kind = Stmt::Kind::If;
    st->loc = kw.loc;
    st->value = condition().expr;
    if (peek().kind == TokKind::Assign)
      throw CompileError(peek().loc, "'=' in a condition: compare with '=='");
    expect(TokKind::RParen, "expected ')' to close the condition of 'if' opened at " + at_text(open.loc));
    branch(st->body, "if", kw.loc);
    if (peek().kind == TokKind::Ident && peek().text == "else" && peek(1).kind != TokKind::Assign) {
      Token e = take();
      st->else_loc = e.loc;
      if (peek().kind == TokKind::Ident && peek().text == "if" && peek(1).kind == TokKind::LParen)
        st->else_body.push_back(if_statement());
      else
        branch(st->else_body, "else", e.loc);
    }
    return st;
  }

  // '{' statements '}' or one statement.
  void branch(std::vector<StmtPtr>& out, const std::string& what, SourceLoc at) {
    if (accept(TokKind::LBrace)) {
      for (;;) {
        if (peek().kind == TokKind::RBrace) break;
        if (peek().kind == TokKind::End) fail_after("expected '}' to close the '" + what + "' at " + at_text(at));
        if (is_unroll()) {
          unrolled_loop(out);
          continue;
        }
        if (peek().kind == TokKind::Ident && peek(1).kind == TokKind::Assign && peek(2).kind == TokKind::LBrace)
          throw CompileError(peek().loc, "a macro cannot be defined inside '" + what + "'");
        if (StmtPtr st = statement()) out.push_back(std::move(st));
      }
      take();  // '}'
    } else if (is_unroll()) {
      unrolled_loop(out);
    } else if (peek().kind == TokKind::End) {
      fail_after("expected a statement or '{' after '" + what + "'");
    } else if (peek().kind == TokKind::Ident && peek(1).kind == TokKind::Assign && peek(2).kind == TokKind::LBrace) {
      throw CompileError(peek().loc, "a macro cannot be defined inside '" + what + "'");
    } else if (StmtPtr st = statement()) {
      out.push_back(std::move(st));
    }
  }

  Parsed make_logic(const Token& op, Parsed a, std::optional<Parsed> b) {
    auto e = std::make_shared<Expr>();
    e->kind = Expr::Kind::Logic;
    e->text = std::string(op.text);
    e->loc = op.loc;
    int depth = a.depth;
    e->args.push_back(std::move(a.expr));
    if (b) {
      depth = std::max(depth, b->depth);
      e->args.push_back(std::move(b->expr));
    }
    return {std::move(e), check_depth(depth + 1, op.loc)};
  }

  // condition: and_condition { '||' and_condition }
  Parsed condition() {
    Parsed lhs = and_condition();
    while (peek().kind == TokKind::OrOr) {
      Token op = take();
      lhs = make_logic(op, std::move(lhs), and_condition());
    }
    return lhs;
  }

  // and_condition: not_condition { '&&' not_condition }
  Parsed and_condition() {
    Parsed lhs = not_condition();
    while (peek().kind == TokKind::AndAnd) {
      Token op = take();
      lhs = make_logic(op, std::move(lhs), not_condition());
    }
    return lhs;
  }

  // not_condition: '!' not_condition | '(' condition ')' | expression [comparison expression]
  // A parenthesis opens a condition when a comparison, '&&', '||' or '!' stands directly inside it.
  Parsed not_condition() {
    if (peek().kind == TokKind::Bang) {
      Token op = take();
      Nest nest(*this, op.loc);
      return make_logic(op, not_condition(), std::nullopt);
    }
    if (peek().kind == TokKind::LParen && parenthesized_condition()) {
      Token open = take();
      Nest nest(*this, open.loc);
      Parsed inside = condition();
      expect(TokKind::RParen, "expected ')' to close '(' at " + at_text(open.loc));
      return inside;
    }
    Parsed lhs = expression();
    if (peek().kind != TokKind::Compare) return lhs;
    Token op = take();
    Parsed rhs = expression();
    if (peek().kind == TokKind::Compare)
      throw CompileError(peek().loc, "comparisons do not chain: write a < b && b < c");
    auto e = std::make_shared<Expr>();
    e->kind = Expr::Kind::Compare;
    e->text = std::string(op.text);
    e->loc = op.loc;
    const int depth = std::max(lhs.depth, rhs.depth) + 1;
    e->args.push_back(std::move(lhs.expr));
    e->args.push_back(std::move(rhs.expr));
    return {std::move(e), check_depth(depth, op.loc)};
  }

  // Does the '(' at peek(at) hold a condition: a comparison, '&&', '||' or '!' at its own level, or nothing
  // but a parenthesized condition ("((a < b))")?
  bool parenthesized_condition(size_t at = 0) {
    // Deeper than the nesting limit it cannot parse anyway: as an expression it reaches the limit's error.
    if (at > static_cast<size_t>(kMaxNesting)) return false;
    int depth = 0;
    for (size_t k = at;; ++k) {
      const Token& t = peek(k);
      switch (t.kind) {
        case TokKind::LParen: ++depth; break;
        case TokKind::RParen:
          if (--depth == 0) return false;
          // The group at at+1 closes here, right before ours: "((...))" is a condition when its inside is.
          if (depth == 1 && peek(at + 1).kind == TokKind::LParen && peek(k + 1).kind == TokKind::RParen &&
              matching_paren(at + 1) == k)
            return parenthesized_condition(at + 1);
          break;
        case TokKind::Compare:
        case TokKind::AndAnd:
        case TokKind::OrOr:
        case TokKind::Bang:
          if (depth == 1) return true;
          break;
        case TokKind::End:
        case TokKind::Semi:
        case TokKind::LBrace:
        case TokKind::RBrace: return false;
        default: break;
      }
    }
  }

  // The index (for peek) of the ')' that closes the '(' at peek(at); 0 when it is not closed.
  size_t matching_paren(size_t at) {
    int depth = 0;
    for (size_t k = at;; ++k) {
      const TokKind kind = peek(k).kind;
      if (kind == TokKind::LParen) ++depth;
      else if (kind == TokKind::RParen && --depth == 0) return k;
      else if (kind == TokKind::End || kind == TokKind::Semi || kind == TokKind::LBrace || kind == TokKind::RBrace) return 0;
    }
  }

  StmtPtr pragma() {
    Token t = take();
    auto st = std::make_shared<Stmt>();
    st->kind = Stmt::Kind::Pragma;
    st->loc = t.loc;
    st->words = std::move(t.words);
    st->word_locs = std::move(t.word_locs);
    return st;
  }

  // ?x = e;  ?x;  :x = e;  :x;  !x = e;
  StmtPtr marked(Marker marker) {
    Token mark = take();
    const std::string m(mark.text);
    if (peek().kind != TokKind::Ident) fail_after("expected a name after '" + m + "'");
    Token name = take();
    if (peek().kind == TokKind::Semi && marker != Marker::EvalOnly) {
      take();
      if (marker == Marker::Visual && is_display_directive(name.text)) return nullptr;
      auto st = std::make_shared<Stmt>();
      st->kind = Stmt::Kind::Assign;
      st->loc = name.loc;
      st->marker = marker;
      st->name = std::string(name.text);
      return st;
    }
    if (peek().kind != TokKind::Assign) {
      if (marker == Marker::EvalOnly) fail_after("expected '=' after '!" + std::string(name.text) + "'");
      fail_after("expected '=' or ';' after '" + m + std::string(name.text) + "'");
    }
    if (peek(1).kind == TokKind::LBrace)
      throw CompileError(peek(1).loc, "a macro definition cannot be marked with '" + m + "'");
    return assignment(marker, std::move(name));
  }

  // NAME = expression ;   (NAME already taken)
  StmtPtr assignment(Marker marker, Token name) {
    take();  // '='
    auto st = std::make_shared<Stmt>();
    st->kind = Stmt::Kind::Assign;
    st->loc = name.loc;
    st->marker = marker;
    st->name = std::string(name.text);
    st->value = expression().expr;
    if (peek().kind == TokKind::Assign) throw CompileError(peek().loc, "expected ';' after statement");
    no_condition_operator();
    // Inside a macro, an assignment that ends its line without ';' is accepted, as Gaalop's parser recovers
    // from it (its own QuestionLineMacro test script is written so), with a warning.
    if (macro_depth_ > 0 && peek().kind != TokKind::Semi && peek().loc.line > prev_end_.line) {
      warnings_.push_back({prev_end_, "missing ';' after the assignment to '" + st->name + "' (accepted, as Gaalop does)"});
      return st;
    }
    expect(TokKind::Semi, "expected ';' after statement");
    return st;
  }

  // NAME = { statement... [expression] } [;]
  StmtPtr macro() {
    Token name = take();
    take();  // '='
    Token open = take();
    Nest nest(*this, open.loc);
    ++macro_depth_;
    struct Leave {
      int& depth;
      ~Leave() { --depth; }
    } leave{macro_depth_};
    auto st = std::make_shared<Stmt>();
    st->kind = Stmt::Kind::MacroDef;
    st->loc = name.loc;
    st->name = std::string(name.text);
    const std::string unclosed =
        "expected '}' to close macro '" + st->name + "' opened at " + at_text(open.loc);
    for (;;) {
      const Token& t = peek();
      if (t.kind == TokKind::RBrace) break;
      if (t.kind == TokKind::End) fail_after(unclosed);
      bool statement_form = t.kind == TokKind::Pragma || t.kind == TokKind::Semi || t.kind == TokKind::Question ||
                            t.kind == TokKind::Colon || t.kind == TokKind::Bang || t.kind == TokKind::LBrace ||
                            (t.kind == TokKind::Ident && peek(1).kind == TokKind::Assign) ||
                            (t.kind == TokKind::Ident && t.text == "if" && peek(1).kind == TokKind::LParen);
      if (statement_form) {
        if (StmtPtr s = statement()) st->body.push_back(std::move(s));
        continue;
      }
      // An expression: the macro's value when '}' follows, else an expression statement.
      SourceLoc loc = t.loc;
      ExprPtr e = expression().expr;
      no_assignment_to_expression();
      if (peek().kind == TokKind::RBrace) {
        st->result = std::move(e);
        break;
      }
      if (peek().kind == TokKind::End) fail_after(unclosed);
      if (peek().kind != TokKind::Semi) fail_after("expected ';' or '}' after expression in macro '" + st->name + "'");
      take();
      auto es = std::make_shared<Stmt>();
      es->kind = Stmt::Kind::ExprStmt;
      es->loc = loc;
      es->value = std::move(e);
      st->body.push_back(std::move(es));
    }
    take();  // '}'
    accept(TokKind::Semi);
    return st;
  }

  // ---- expressions ---------------------------------------------------------------------------------
  Parsed make_unary(UnaryOp op, SourceLoc loc, Parsed a) {
    auto e = std::make_shared<Expr>();
    e->kind = Expr::Kind::Unary;
    e->unary_op = op;
    e->loc = loc;
    e->args.push_back(std::move(a.expr));
    return {std::move(e), check_depth(a.depth + 1, loc)};
  }

  Parsed make_binary(BinaryOp op, SourceLoc loc, Parsed a, Parsed b) {
    auto e = std::make_shared<Expr>();
    e->kind = Expr::Kind::Binary;
    e->binary_op = op;
    e->loc = loc;
    e->args.push_back(std::move(a.expr));
    e->args.push_back(std::move(b.expr));
    return {std::move(e), check_depth(std::max(a.depth, b.depth) + 1, loc)};
  }

  static int check_depth(int depth, SourceLoc loc) {
    if (depth > kMaxTreeDepth)
      throw CompileError(loc, "expression too long (more than " + std::to_string(kMaxTreeDepth) +
                                  " nested operations); split it into several assignments");
    return depth;
  }

  Parsed expression() { return additive(); }

  // unary_minus { ('+' | '-') unary_minus }
  Parsed additive() {
    Parsed lhs = unary_minus();
    for (;;) {
      TokKind k = peek().kind;
      if (k != TokKind::Plus && k != TokKind::Minus) return lhs;
      Token op = take();
      lhs = make_binary(k == TokKind::Plus ? BinaryOp::Add : BinaryOp::Sub, op.loc, std::move(lhs), unary_minus());
    }
  }

  // ('-' | '+') unary_minus | geometric      -a*b is -(a*b)
  Parsed unary_minus() {
    TokKind k = peek().kind;
    if (k != TokKind::Minus && k != TokKind::Plus) return geometric();
    Token op = take();
    Nest nest(*this, op.loc);
    Parsed a = unary_minus();
    if (k == TokKind::Plus) return a;
    return make_unary(UnaryOp::Negate, op.loc, std::move(a));
  }

  // division { '*' division }
  Parsed geometric() {
    Parsed lhs = division();
    while (peek().kind == TokKind::Star) {
      Token op = take();
      lhs = make_binary(BinaryOp::Geo, op.loc, std::move(lhs), division());
    }
    return lhs;
  }

  // inner { '/' inner }      a*b/c is a*(b/c)
  Parsed division() {
    Parsed lhs = inner();
    while (peek().kind == TokKind::Slash) {
      Token op = take();
      lhs = make_binary(BinaryOp::Div, op.loc, std::move(lhs), inner());
    }
    return lhs;
  }

  // outer { '.' outer }      e1^einf.e1 is (e1^einf).e1
  Parsed inner() {
    Parsed lhs = outer();
    while (peek().kind == TokKind::Dot) {
      Token op = take();
      lhs = make_binary(BinaryOp::Inner, op.loc, std::move(lhs), outer());
    }
    return lhs;
  }

  // prefix { '^' prefix }
  Parsed outer() {
    Parsed lhs = prefix();
    while (peek().kind == TokKind::Caret) {
      Token op = take();
      lhs = make_binary(BinaryOp::Outer, op.loc, std::move(lhs), prefix());
    }
    return lhs;
  }

  // ('*' | '~' | '-' | '+') prefix | primary
  // A '-' reaching this level follows a tighter operator (a*-b, a^-b, ~-a) and negates one operand,
  // as in Gaalop's grammar; at the start of an operand of + or - unary_minus takes it first.
  Parsed prefix() {
    TokKind k = peek().kind;
    if (k != TokKind::Star && k != TokKind::Tilde && k != TokKind::Minus && k != TokKind::Plus) return primary();
    Token op = take();
    Nest nest(*this, op.loc);
    Parsed a = prefix();
    switch (k) {
      case TokKind::Star: return make_unary(UnaryOp::Dual, op.loc, std::move(a));
      case TokKind::Tilde: return make_unary(UnaryOp::Reverse, op.loc, std::move(a));
      case TokKind::Minus: return make_unary(UnaryOp::Negate, op.loc, std::move(a));
      default: return a;
    }
  }

  Parsed primary() {
    const Token& t = peek();
    switch (t.kind) {
      case TokKind::Number: {
        Token n = take();
        auto e = std::make_shared<Expr>();
        e->kind = Expr::Kind::Number;
        e->loc = n.loc;
        e->text = std::string(n.text);
        return {std::move(e), 1};
      }
      case TokKind::Ident: {
        Token n = take();
        if (n.text == "_P" && peek().kind == TokKind::LParen) return macro_arg(n);
        if (peek().kind == TokKind::LParen) return call(n);
        auto e = std::make_shared<Expr>();
        e->kind = Expr::Kind::Name;
        e->loc = n.loc;
        e->text = std::string(n.text);
        return {std::move(e), 1};
      }
      case TokKind::LParen: {
        Token open = take();
        Nest nest(*this, open.loc);
        Parsed inside = expression();
        expect(TokKind::RParen, "expected ')' to close '(' at " + at_text(open.loc));
        return inside;
      }
      case TokKind::Pragma:
        throw CompileError(t.loc, "a pragma cannot appear inside a statement");
      case TokKind::End: fail_after("expected expression");
      default: throw CompileError(t.loc, "expected expression, found " + describe(t));
    }
  }

  // _P(n), n a positive integer literal; '_P' taken, '(' next.
  Parsed macro_arg(const Token& p) {
    const std::string message = "macro argument must be _P(<positive integer>)";
    take();  // '('
    const Token& n = peek();
    bool digits = n.kind == TokKind::Number && n.text.find_first_not_of("0123456789") == std::string_view::npos;
    size_t first = n.text.find_first_not_of('0');
    // Up to 9 significant digits always fits an int.
    if (!digits || first == std::string_view::npos || n.text.size() - first > 9) throw CompileError(p.loc, message);
    int index = std::stoi(std::string(n.text.substr(first)));
    take();
    if (peek().kind != TokKind::RParen) throw CompileError(p.loc, message);
    take();
    auto e = std::make_shared<Expr>();
    e->kind = Expr::Kind::MacroArg;
    e->loc = p.loc;
    e->index = index;
    return {std::move(e), 1};
  }

  // NAME '(' [expression {',' expression}] ')'; NAME taken, '(' next.
  Parsed call(const Token& name) {
    Token open = take();
    Nest nest(*this, open.loc);
    auto e = std::make_shared<Expr>();
    e->kind = Expr::Kind::Call;
    e->loc = name.loc;
    e->text = std::string(name.text);
    int depth = 1;
    if (!accept(TokKind::RParen)) {
      for (;;) {
        Parsed a = expression();
        depth = std::max(depth, a.depth + 1);
        e->args.push_back(std::move(a.expr));
        if (accept(TokKind::RParen)) break;
        if (!accept(TokKind::Comma))
          fail_after("expected ',' or ')' in call to '" + e->text + "' opened at " + at_text(open.loc));
      }
    }
    return {std::move(e), check_depth(depth, name.loc)};
  }

  Lexer lexer_;
  std::deque<Token> ahead_;
  SourceLoc prev_end_{1, 1};
  int nesting_ = 0;
  int macro_depth_ = 0;  // macro bodies being parsed
  std::vector<std::pair<SourceLoc, std::string>> warnings_;
};

}  // namespace

Script parse(const SourceFile& file) { return Parser(file).script(); }

}  // namespace cgagen::front
