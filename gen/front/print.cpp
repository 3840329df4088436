// S-expression printer for the AST (see print.hpp).
#include "front/print.hpp"

namespace cgagen::front {
namespace {

const char* binary_name(BinaryOp op) {
  switch (op) {
    case BinaryOp::Add: return "+";
    case BinaryOp::Sub: return "-";
    case BinaryOp::Geo: return "*";
    case BinaryOp::Div: return "/";
    case BinaryOp::Inner: return ".";
    case BinaryOp::Outer: return "^";
  }
  return "?";
}

const char* unary_name(UnaryOp op) {
  switch (op) {
    case UnaryOp::Negate: return "neg";
    case UnaryOp::Reverse: return "rev";
    case UnaryOp::Dual: return "dual";
  }
  return "?";
}

void print(const Expr& e, std::string& out) {
  switch (e.kind) {
    case Expr::Kind::Number:
    case Expr::Kind::Name: out += e.text; return;
    case Expr::Kind::MacroArg: out += "_P" + std::to_string(e.index); return;
    case Expr::Kind::Unary: out += "("; out += unary_name(e.unary_op); break;
    case Expr::Kind::Binary: out += "("; out += binary_name(e.binary_op); break;
    case Expr::Kind::Call: out += "(call " + e.text; break;
    case Expr::Kind::Compare:
    case Expr::Kind::Logic: out += "(" + e.text; break;
  }
  for (const ExprPtr& a : e.args) {
    out += ' ';
    print(*a, out);
  }
  out += ')';
}

void print(const Stmt& s, std::string& out) {
  switch (s.kind) {
    case Stmt::Kind::Assign: {
      const char* mark = s.marker == Marker::Output ? "?" : s.marker == Marker::Visual ? ":" :
                         s.marker == Marker::EvalOnly ? "!" : "";
      // "?x = e" prints as (?= x e), "?x;" as (? x), a plain "x = e" as (= x e).
      std::string head = std::string(mark) + (s.value ? "=" : "");
      if (head.empty()) head = "=";
      out += "(" + head + " " + s.name;
      if (s.value) {
        out += ' ';
        print(*s.value, out);
      }
      out += ')';
      return;
    }
    case Stmt::Kind::ExprStmt:
      out += "(expr ";
      if (s.value) print(*s.value, out);
      out += ')';
      return;
    case Stmt::Kind::Pragma:
      out += "(pragma";
      for (const auto& w : s.words) out += " " + w;
      out += ')';
      return;
    case Stmt::Kind::MacroDef:
      out += "(macro " + s.name;
      for (const StmtPtr& b : s.body) {
        out += ' ';
        print(*b, out);
      }
      if (s.result) {
        out += " (result ";
        print(*s.result, out);
        out += ')';
      }
      out += ')';
      return;
    case Stmt::Kind::If:
      out += "(if ";
      if (s.value) print(*s.value, out);
      out += " (then";
      for (const StmtPtr& b : s.body) {
        out += ' ';
        print(*b, out);
      }
      out += ')';
      if (s.else_loc.line > 0) {
        out += " (else";
        for (const StmtPtr& b : s.else_body) {
          out += ' ';
          print(*b, out);
        }
        out += ')';
      }
      out += ')';
      return;
  }
}

}  // namespace

std::string to_sexpr(const Expr& e) {
  std::string out;
  print(e, out);
  return out;
}

std::string to_sexpr(const Stmt& s) {
  std::string out;
  print(s, out);
  return out;
}

std::string to_sexpr(const Script& s) {
  std::string out;
  for (const StmtPtr& st : s.statements) {
    print(*st, out);
    out += '\n';
  }
  return out;
}

}  // namespace cgagen::front
