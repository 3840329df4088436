// Branch-free selects (see select.hpp).
#include "symbolic/select.hpp"

namespace cgagen::symbolic {

using namespace GiNaC;

namespace {

// The comparison of two real numbers; nullopt when either is not a real number.
template <class Cmp>
ex fold(const ex& a, const ex& b, const ex& x, const ex& y, Cmp cmp, ex held) {
  if (x.is_equal(y)) return x;
  if (is_a<numeric>(a) && is_a<numeric>(b) && ex_to<numeric>(a).is_real() && ex_to<numeric>(b).is_real())
    return cmp(ex_to<numeric>(a), ex_to<numeric>(b)) ? x : y;
  return held;
}

ex lt_eval(const ex& a, const ex& b, const ex& x, const ex& y) {
  return fold(a, b, x, y, [](const numeric& p, const numeric& q) { return p < q; },
              select_lt(a, b, x, y).hold());
}
ex le_eval(const ex& a, const ex& b, const ex& x, const ex& y) {
  return fold(a, b, x, y, [](const numeric& p, const numeric& q) { return p <= q; },
              select_le(a, b, x, y).hold());
}
ex eq_eval(const ex& a, const ex& b, const ex& x, const ex& y) {
  if (a.is_equal(b)) return x;
  return fold(a, b, x, y, [](const numeric& p, const numeric& q) { return p == q; },
              select_eq(a, b, x, y).hold());
}

// A comparison of numbers evaluates the branch it takes only: nested selects (exp and log nest their Taylor
// selects) would otherwise cost 2^depth evaluations.
template <class Cmp>
ex fold_evalf(const ex& a, const ex& b, const ex& x, const ex& y, Cmp cmp, ex (*make)(const ex&, const ex&, const ex&, const ex&)) {
  const ex ea = a.evalf(), eb = b.evalf();
  if (is_a<numeric>(ea) && is_a<numeric>(eb) && ex_to<numeric>(ea).is_real() && ex_to<numeric>(eb).is_real())
    return (cmp(ex_to<numeric>(ea), ex_to<numeric>(eb)) ? x : y).evalf();
  return make(ea, eb, x.evalf(), y.evalf());
}
ex make_lt(const ex& a, const ex& b, const ex& x, const ex& y) { return select_lt(a, b, x, y); }
ex make_le(const ex& a, const ex& b, const ex& x, const ex& y) { return select_le(a, b, x, y); }
ex make_eq(const ex& a, const ex& b, const ex& x, const ex& y) { return select_eq(a, b, x, y); }
ex lt_evalf(const ex& a, const ex& b, const ex& x, const ex& y) {
  return fold_evalf(a, b, x, y, [](const numeric& p, const numeric& q) { return p < q; }, make_lt);
}
ex le_evalf(const ex& a, const ex& b, const ex& x, const ex& y) {
  return fold_evalf(a, b, x, y, [](const numeric& p, const numeric& q) { return p <= q; }, make_le);
}
ex eq_evalf(const ex& a, const ex& b, const ex& x, const ex& y) {
  return fold_evalf(a, b, x, y, [](const numeric& p, const numeric& q) { return p == q; }, make_eq);
}

// The arguments are real (kernel symbols are realsymbols): conjugation acts on the branches only.
ex lt_conj(const ex& a, const ex& b, const ex& x, const ex& y) { return select_lt(a, b, x.conjugate(), y.conjugate()); }
ex le_conj(const ex& a, const ex& b, const ex& x, const ex& y) { return select_le(a, b, x.conjugate(), y.conjugate()); }
ex eq_conj(const ex& a, const ex& b, const ex& x, const ex& y) { return select_eq(a, b, x.conjugate(), y.conjugate()); }
ex lt_re(const ex& a, const ex& b, const ex& x, const ex& y) { return select_lt(a, b, x.real_part(), y.real_part()); }
ex le_re(const ex& a, const ex& b, const ex& x, const ex& y) { return select_le(a, b, x.real_part(), y.real_part()); }
ex eq_re(const ex& a, const ex& b, const ex& x, const ex& y) { return select_eq(a, b, x.real_part(), y.real_part()); }
ex lt_im(const ex& a, const ex& b, const ex& x, const ex& y) { return select_lt(a, b, x.imag_part(), y.imag_part()); }
ex le_im(const ex& a, const ex& b, const ex& x, const ex& y) { return select_le(a, b, x.imag_part(), y.imag_part()); }
ex eq_im(const ex& a, const ex& b, const ex& x, const ex& y) { return select_eq(a, b, x.imag_part(), y.imag_part()); }

// Derivatives (derivative kernels, expand/jacobian.cpp): a select differentiates its taken branch, so the
// partial derivative by x is the select of 1 and 0, by y of 0 and 1, and by the compared values 0 (the
// comparison is piecewise constant).
template <ex (*make)(const ex&, const ex&, const ex&, const ex&)>
ex select_deriv(const ex& a, const ex& b, const ex&, const ex&, unsigned param) {
  if (param == 2) return make(a, b, 1, 0);
  if (param == 3) return make(a, b, 0, 1);
  return 0;
}

}  // namespace

REGISTER_FUNCTION(select_lt, eval_func(lt_eval).evalf_func(lt_evalf).conjugate_func(lt_conj).real_part_func(lt_re).imag_part_func(lt_im).derivative_func(select_deriv<make_lt>))
REGISTER_FUNCTION(select_le, eval_func(le_eval).evalf_func(le_evalf).conjugate_func(le_conj).real_part_func(le_re).imag_part_func(le_im).derivative_func(select_deriv<make_le>))
REGISTER_FUNCTION(select_eq, eval_func(eq_eval).evalf_func(eq_evalf).conjugate_func(eq_conj).real_part_func(eq_re).imag_part_func(eq_im).derivative_func(select_deriv<make_eq>))

ex make_select(const Condition& c, const ex& x, const ex& y) {
  if (x.is_equal(y)) return x;
  using Op = Condition::Op;
  switch (c.op) {
    case Op::Lt: return select_lt(c.a, c.b, x, y);
    case Op::Le: return select_le(c.a, c.b, x, y);
    case Op::Gt: return select_lt(c.b, c.a, x, y);  // a > b is b < a
    case Op::Ge: return select_le(c.b, c.a, x, y);
    case Op::Eq: return select_eq(c.a, c.b, x, y);
    case Op::Ne: return select_eq(c.a, c.b, y, x);
    case Op::Not: return make_select(*c.l, y, x);
    case Op::And: return make_select(*c.l, make_select(*c.r, x, y), y);
    case Op::Or: return make_select(*c.l, x, make_select(*c.r, x, y));
  }
  return y;
}

bool is_select(const ex& e) {
  if (!is_a<function>(e)) return false;
  const std::string& n = ex_to<function>(e).get_name();
  return n == "select_lt" || n == "select_le" || n == "select_eq";
}

std::string select_operator(const ex& e) {
  const std::string& n = ex_to<function>(e).get_name();
  return n == "select_lt" ? "<" : n == "select_le" ? "<=" : "==";
}

bool select_holds(const std::string& op, double a, double b) {
  return op == "<" ? a < b : op == "<=" ? a <= b : a == b;
}

}  // namespace cgagen::symbolic
