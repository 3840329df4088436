// Branch-free selects, the form if/else takes in a kernel (docs/language.md, "if / else"):
//   select_lt(a, b, x, y) = a <  b ? x : y
//   select_le(a, b, x, y) = a <= b ? x : y
//   select_eq(a, b, x, y) = a == b ? x : y
// as GiNaC functions over real scalars. Every condition (> >= != && || !) is written with these three by
// swapping operands or branches and nesting (make_select), so a truth value never becomes a kernel value:
// every argument is a real scalar the optimizer may share as a temporary like any other. A select of equal
// branches is that branch; one whose operands are numbers is folded.
#pragma once

#include <ginac/ginac.h>

#include <memory>
#include <string>

namespace cgagen::symbolic {

DECLARE_FUNCTION_4P(select_lt)
DECLARE_FUNCTION_4P(select_le)
DECLARE_FUNCTION_4P(select_eq)

// A condition over real scalar expressions.
struct Condition {
  enum class Op { Lt, Le, Gt, Ge, Eq, Ne, And, Or, Not };
  Op op = Op::Ne;
  GiNaC::ex a, b;                          // comparisons
  std::shared_ptr<const Condition> l, r;   // And, Or (l, r), Not (l)
};

// cond ? x : y, as nested select_* calls.
GiNaC::ex make_select(const Condition& cond, const GiNaC::ex& x, const GiNaC::ex& y);

// Is e a call of select_lt, select_le or select_eq? Its comparison: "<", "<=" or "==".
bool is_select(const GiNaC::ex& e);
std::string select_operator(const GiNaC::ex& e);

// The value of a select whose operands are the numbers a and b: x when the comparison holds, else y.
bool select_holds(const std::string& op, double a, double b);

}  // namespace cgagen::symbolic
