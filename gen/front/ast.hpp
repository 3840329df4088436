// The abstract syntax tree of a CluScript (CLUCalc/Gaalop) file, with source locations.
// Produced by the parser (front/parser.hpp), consumed by the expander (expand/). Immutable once built:
// nodes are shared (macros reuse their bodies at every call), so they are held by shared_ptr<const>.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace cgagen::front {

// 1-based line and column of the first character of a token.
struct SourceLoc {
  int line = 0;
  int col = 0;
};

enum class UnaryOp {
  Negate,   // -a
  Reverse,  // ~a
  Dual,     // *a   (Gaalop: a * (-e1^e2^e3^einf^e0))
};

enum class BinaryOp {
  Add,    // a + b
  Sub,    // a - b
  Geo,    // a * b   geometric product
  Div,    // a / b
  Inner,  // a . b   Gaalop inner product
  Outer,  // a ^ b   outer product
};

struct Expr;
using ExprPtr = std::shared_ptr<const Expr>;

struct Expr {
  enum class Kind {
    Number,    // text: the literal as written ("0.5", "2", "1e-3"); the expander makes it an exact rational
    Name,      // text: identifier (e1, einf, alpha, ...)
    MacroArg,  // index: _P(index), 1-based
    Unary,     // unary_op, args[0]
    Binary,    // binary_op, args[0], args[1]
    Call,      // text: callee name (built-in function or macro), args: the arguments
    Compare,   // text: "<", "<=", ">", ">=", "==" or "!=", args[0], args[1] (scalars; if conditions only)
    Logic,     // text: "&&" or "||" (args[0], args[1]) or "!" (args[0]) over conditions
  };
  Kind kind = Kind::Number;
  SourceLoc loc;  // the operator token for Unary/Binary, the name for Call, the token otherwise
  std::string text;
  int index = 0;
  UnaryOp unary_op = UnaryOp::Negate;
  BinaryOp binary_op = BinaryOp::Add;
  std::vector<ExprPtr> args;
};

// How a statement marks its target, by its prefix character.
enum class Marker {
  None,      // x = e;
  Output,    // ?x = e;  or  ?x;
  Visual,    // :x = e;  (CLUCalc visual output; treated as an output)
  EvalOnly,  // !x = e;  (evaluated, never an output)
};

struct Stmt;
using StmtPtr = std::shared_ptr<const Stmt>;

struct Stmt {
  enum class Kind {
    Assign,    // marker name = value;   (value may be null for "?x;": mark an existing name as output)
    MacroDef,  // name = { body...; result }   result may be null for a macro with no final expression
    Pragma,    // words: the pragma's whitespace-separated words after "#pragma" (e.g. {"output","M","1","e1^e2"})
    ExprStmt,  // value;  a bare expression (evaluated and discarded)
    If,        // if (value) { body } else { else_body }: value is the condition (Compare, Logic or a
               // scalar, true when nonzero); else_body is empty without 'else'. See docs/language.md.
  };
  Kind kind = Kind::Assign;
  SourceLoc loc;  // the name (Assign/MacroDef), the '#' (Pragma), the expression start (ExprStmt)
  Marker marker = Marker::None;
  std::string name;
  ExprPtr value;                 // Assign, ExprStmt
  std::vector<StmtPtr> body;     // MacroDef: the statements before the final expression; If: the then-branch
  std::vector<StmtPtr> else_body;  // If: the else-branch (an 'else if' is an If inside it)
  SourceLoc else_loc;              // If: the 'else' keyword (line 0 without one)
  ExprPtr result;                // MacroDef: the final expression (the macro's value)
  std::vector<std::string> words;     // Pragma
  std::vector<SourceLoc> word_locs;   // Pragma: where each word starts
};

struct Script {
  std::vector<StmtPtr> statements;
  // Forms the parser accepts as Gaalop's does but that are probably slips (a ';' missing at the end of a
  // line inside a macro): where, and what; the expander reports them as warnings.
  std::vector<std::pair<SourceLoc, std::string>> warnings;
};

}  // namespace cgagen::front
