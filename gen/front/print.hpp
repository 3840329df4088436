// S-expression rendering of the AST, for tests and `cgagen --dump-ast`:
// (+ a (* b (/ c d))), (neg a), (rev a), (dual a), (. a b), (^ a b), (call f a b), _P1, numbers and names
// as written. Statements: (= x e), (?= x e), (? x), (:= x e), (: x), (!= x e), (expr e),
// (macro Name (= t e) ... (result e)), (pragma word ...).
#pragma once

#include <string>

#include "front/ast.hpp"

namespace cgagen::front {

std::string to_sexpr(const Expr& e);
std::string to_sexpr(const Stmt& s);
std::string to_sexpr(const Script& s);  // one statement per line, each line ending in '\n'

}  // namespace cgagen::front
