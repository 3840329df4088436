// exp and log of scalars, and the closed forms for bivectors and the rotors and motors they generate
// (docs/language.md, "exp and log").
//
// A bivector B squares to B B = a + b, a = <B B>_0 and b = <B B>_4, and b commutes with B. Where b b = 0
// (no part, or a nilpotent one: the 4-vector of a screw, a rotation with a translation along or off its axis)
// the series sum_k B^k / k! folds into
//     exp(B) = C(a) + S(a)/2 b + B (S(a) + S'(a) b),
//     C(a) = sum_m a^m / (2m)!,  S(a) = sum_m a^m / (2m+1)!,  S'(a) = dS/da = (C(a) - S(a)) / (2a),
// with C = cos t, S = sin t / t for a = -t^2 (rotations) and cosh t, sinh t / t for a = t^2 (boosts).
// Where b b = g is not 0, B is the sum of two commuting simple bivectors B1 + B2 (the invariant decomposition)
// with B_i^2 = l_i, l_1,2 = (a -+ sqrt(a^2 - g)) / 2, b = 2 B1 B2; with C_i = C(l_i), S_i = S(l_i),
//     exp(B) = exp(B1) exp(B2) = C1 C2 + S1 S2 / 2 b + B (A0 + A1 b),
//     A0 = (l2 C1 S2 - l1 S1 C2) / (l2 - l1),  A1 = (S1 C2 - C1 S2) / (2 (l2 - l1)).
// Supported where -g is visibly >= 0, so l1 <= 0 <= l2: a rotation with a dilation (and a translation) in CGA.
// log(M) inverts exp for M = exp(B) with rotation angle |t| < pi, from <M>_0, <M>_2 = B (A0 + A1 b) and
// <M>_4 = S1 S2 / 2 b (for one plane: S / 2 b): it finds the l_i, then B = <M>_2 (A0 - A1 b) / (A0^2 - A1^2 g).
// Near a zero l (and near l1 = l2) the closed forms are 0/0 (sin t / t) or lose digits to cancellation; there a
// select takes their Taylor series, so exp(0) = 1 and log(1) = 0 exactly, and small angles keep their digits.
#include <ginac/ginac.h>

#include <functional>

#include "algebra/algebra.hpp"
#include "expand/builtins.hpp"
#include "front/diagnostics.hpp"
#include "symbolic/select.hpp"

namespace cgagen::expand_builtins {

using front::CompileError;
using GiNaC::ex;
using GiNaC::numeric;

namespace {

// Is the expanded expression e >= 0 for every real value of its symbols, visibly (a sum of positive
// multiples of even powers)? Used to pick the closed form of exp.
bool manifestly_nonnegative(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    const auto& n = GiNaC::ex_to<GiNaC::numeric>(e);
    return n.is_real() && !n.is_negative();
  }
  if (GiNaC::is_a<GiNaC::add>(e) || GiNaC::is_a<GiNaC::mul>(e)) {
    for (size_t i = 0; i < e.nops(); ++i)
      if (!manifestly_nonnegative(e.op(i))) return false;
    return true;
  }
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const ex& p = e.op(1);
    return GiNaC::is_a<GiNaC::numeric>(p) && GiNaC::ex_to<GiNaC::numeric>(p).is_even();
  }
  return false;
}

// A square root of a manifestly nonnegative t, taking even powers out of the root where factoring shows
// them. Its sign may differ from sqrt(t); callers use it only in even functions (cos, sin(x)/x, ...).
ex root_of_square(const ex& t) {
  ex f = GiNaC::factor(t);
  ex out = 1, rest = 1;
  auto take = [&](const ex& factor) {
    if (GiNaC::is_a<GiNaC::power>(factor) && GiNaC::is_a<GiNaC::numeric>(factor.op(1)) &&
        GiNaC::ex_to<GiNaC::numeric>(factor.op(1)).is_even())
      out *= GiNaC::pow(factor.op(0), factor.op(1) / 2);
    else if (GiNaC::is_a<GiNaC::numeric>(factor))
      out *= GiNaC::sqrt(factor);
    else
      rest *= factor;
  };
  if (GiNaC::is_a<GiNaC::mul>(f))
    for (size_t i = 0; i < f.nops(); ++i) take(f.op(i));
  else
    take(f);
  return rest.is_equal(1) ? out : out * GiNaC::sqrt(rest);
}

// m without the terms that vanish once earlier values are inlined.
Multivector nonvanishing(Context& ctx, const Multivector& m) {
  return m.without([&](algebra::BladeIndex, const ex& c) { return ctx.vanishes(c); });
}

// A scalar as the expander's temporary where it is a long expression (Context::bind_if_long): the closed
// forms below nest the previous ones, and on long expressions GiNaC's normal() and expand() take minutes.
using Bind = std::function<ex(const ex&)>;

// C(a), S(a) and S'(a) (top of this file). `closed_c` and `closed_s` are C and S in closed form, for a whose
// square is not small; the Taylor polynomials below it.
struct Series {
  ex c, s, sp;
};

// The Taylor polynomials of C, S and S' to a^4: exact to double precision for |a| < 1/100.
ex taylor_c(const ex& a) { return 1 + a / 2 + GiNaC::pow(a, 2) / 24 + GiNaC::pow(a, 3) / 720 + GiNaC::pow(a, 4) / 40320; }
ex taylor_s(const ex& a) { return 1 + a / 6 + GiNaC::pow(a, 2) / 120 + GiNaC::pow(a, 3) / 5040 + GiNaC::pow(a, 4) / 362880; }
ex taylor_sp(const ex& a) {
  return numeric(1, 6) + a / 60 + GiNaC::pow(a, 2) / 1680 + GiNaC::pow(a, 3) / 90720 + GiNaC::pow(a, 4) / 7983360;
}

// v^2 < 1/10000: where the selects take the Taylor polynomials.
symbolic::Condition small_square(const ex& v) {
  symbolic::Condition small;
  small.op = symbolic::Condition::Op::Lt;
  small.a = v * v;
  small.b = numeric(1, 10000);
  return small;
}

Series fold(const ex& a, const ex& closed_c, const ex& closed_s, const Bind& bind) {
  if (a.is_zero()) return {1, 1, numeric(1, 6)};
  const symbolic::Condition small = small_square(a);
  return {bind(symbolic::make_select(small, taylor_c(a), closed_c)), bind(symbolic::make_select(small, taylor_s(a), closed_s)),
          bind(symbolic::make_select(small, taylor_sp(a), (closed_c - closed_s) / (2 * a)))};
}

// A0 and A1 of two commuting planes (top of this file). Their numerators are antisymmetric in (l1, l2), so the
// Taylor polynomials of C and S give numerators that (l2 - l1) divides exactly: near l1 = l2 the quotients are
// the series, elsewhere the closed forms.
struct Mix {
  ex a0, a1;
};

Mix mix(const ex& l1, const ex& l2, const Series& f1, const Series& f2, const Bind& bind) {
  static const GiNaC::symbol x("x"), y("y");
  static const std::pair<ex, ex> taylor = [] {
    const ex n0 = (y * taylor_c(x) * taylor_s(y) - x * taylor_s(x) * taylor_c(y)).expand(),
             n1 = (taylor_s(x) * taylor_c(y) - taylor_c(x) * taylor_s(y)).expand();
    return std::make_pair(GiNaC::quo(n0, y - x, y), GiNaC::quo(n1, y - x, y) / 2);
  }();
  const GiNaC::lst at{x == l1, y == l2};
  const ex d = l2 - l1;
  const symbolic::Condition near = small_square(d);
  return {bind(symbolic::make_select(near, taylor.first.subs(at), (l2 * f1.c * f2.s - l1 * f1.s * f2.c) / d)),
          bind(symbolic::make_select(near, taylor.second.subs(at), (f1.s * f2.c - f1.c * f2.s) / (2 * d)))};
}

// exp(B) for B*B = a + b with b*b = g, -g >= 0 (two commuting planes, l1 <= 0 <= l2).
Multivector exp_two_planes(const Multivector& b, const ex& a, const Multivector& four, const ex& g, const Bind& bind) {
  const ex r = bind(GiNaC::abs(root_of_square((a * a - g).expand())));
  const ex l1 = bind((a - r) / 2), l2 = bind((a + r) / 2);
  const ex t1 = bind(GiNaC::sqrt(-l1)), t2 = bind(GiNaC::sqrt(l2));
  const Series f1 = fold(l1, GiNaC::cos(t1), GiNaC::sin(t1) / t1, bind),
               f2 = fold(l2, GiNaC::cosh(t2), GiNaC::sinh(t2) / t2, bind);
  const Mix m = mix(l1, l2, f1, f2, bind);
  return Multivector(f1.c * f2.c) + (f1.s * f2.s / 2) * four + b * (m.a0 * Multivector(ex(1)) + m.a1 * four);
}

// log(M) for M = exp(B1 + B2) with B1^2 = l1 = -t1^2 <= 0 <= l2 = t2^2 = B2^2. With X = sinh^2 t2 and
// Y = sin^2 t1: q = <<M>_2^2>_0 = X - Y - 2XY and p = -<<M>_4^2>_0 = XY, so X and Y are the roots of
// z^2 - d z - p = 0 (X) and of z^2 + d z - p (Y), d = q + 2p; each is taken in the form without cancellation.
Multivector log_two_planes(const ex& m0, const Multivector& m2, const Multivector& m4, const ex& q, const ex& p,
                           const Bind& bind) {
  const ex d = bind(q + 2 * p), e = bind(GiNaC::sqrt(d * d + 4 * p));
  symbolic::Condition d_nonneg;
  d_nonneg.op = symbolic::Condition::Op::Ge;
  d_nonneg.a = d;
  d_nonneg.b = 0;
  symbolic::Condition e_zero;
  e_zero.op = symbolic::Condition::Op::Eq;
  e_zero.a = e;
  e_zero.b = 0;
  const ex x = bind(symbolic::make_select(d_nonneg, (d + e) / 2, symbolic::make_select(e_zero, 0, 2 * p / (e - d))));
  const ex y = bind(symbolic::make_select(d_nonneg, symbolic::make_select(e_zero, 0, 2 * p / (d + e)), (e - d) / 2));
  const ex ch2 = bind(GiNaC::sqrt(1 + x)), sh2 = bind(GiNaC::sqrt(x)), s1 = bind(GiNaC::sqrt(y)), c1 = bind(m0 / ch2);
  const ex t1 = bind(GiNaC::atan2(s1, c1)), t2 = bind(GiNaC::log(sh2 + ch2));
  const ex l1 = bind(-t1 * t1), l2 = bind(t2 * t2);
  const Series f1 = fold(l1, c1, s1 / t1, bind), f2 = fold(l2, ch2, sh2 / t2, bind);
  const Mix m = mix(l1, l2, f1, f2, bind);
  const Multivector b = bind(2 / (f1.s * f2.s)) * m4;
  const ex g = 4 * l1 * l2;
  const Multivector out = m2 * (m.a0 * Multivector(ex(1)) - m.a1 * b);
  return out.grade(2) * bind(1 / (m.a0 * m.a0 - m.a1 * m.a1 * g));
}

}  // namespace

Multivector exponential(const Call& c) {
  const front::SourceLoc at = c.expr.args[0]->loc;
  Multivector b = c.ctx.scalar_part_if_scalar(c.args[0]);
  if (b.is_scalar()) return Multivector(GiNaC::exp(b.scalar()));
  b = c.ctx.bind_if_long(b, at);
  const Bind bind = [&](const ex& e) { return c.ctx.bind_if_long(Multivector(e), at).scalar(); };
  b = c.ctx.bivector_part_if_bivector(b);
  if (!b.is_homogeneous(2)) throw CompileError(at, "'exp' takes a scalar or a bivector, got " + describe(b));
  if (b.terms().size() == 1) {
    // c * blade: B*B = c^2 * blade^2, and blade^2 = u is a number, so the sign needs nothing of c; cos,
    // sinh(x)/x, ... are even, so c serves as theta. exp(c blade) = cos(c s) + sin(c s)/s blade with
    // s = sqrt(-u) (u < 0), cosh/sinh with s = sqrt(u) (u > 0): in a user algebra whose basis is not
    // orthonormal u need not be +-1.
    const auto& [k, coeff] = *b.terms().begin();
    const Multivector unit = Multivector::blade(k) * Multivector::blade(k);
    if (unit.is_scalar() && GiNaC::is_a<GiNaC::numeric>(unit.scalar())) {
      const GiNaC::numeric u = GiNaC::ex_to<GiNaC::numeric>(unit.scalar());
      const Multivector unit_blade = Multivector::blade(k);
      if (u.is_zero()) return Multivector(ex(1)) + b;
      const ex s = GiNaC::sqrt(GiNaC::abs(u));
      if (u.is_negative()) return Multivector(GiNaC::cos(coeff * s)) + (GiNaC::sin(coeff * s) / s) * unit_blade;
      return Multivector(GiNaC::cosh(coeff * s)) + (GiNaC::sinh(coeff * s) / s) * unit_blade;
    }
  }
  const Multivector sq = nonvanishing(c.ctx, b * b);
  const ex a = sq.scalar();
  const Multivector four = sq.grade(4);
  if (!(sq - Multivector(a) - four).is_zero())
    throw CompileError(at, "'exp' of a bivector B whose square has grades other than 0 and 4 (an algebra of more "
                           "than 5 dimensions): write the product of the exps of its commuting parts");
  const Multivector g = nonvanishing(c.ctx, four * four);
  if (!g.is_zero()) {
    if (!g.is_scalar() || !manifestly_nonnegative((-g.scalar()).expand()))
      throw CompileError(at, "'exp' of a bivector B of two commuting planes is supported where one is a rotation "
                             "and the other a boost (<B*B>_4 squared visibly <= 0, as a rotation with a dilation); "
                             "write the product of the exps of its commuting parts");
    return exp_two_planes(b, a, four, g.scalar(), bind);
  }
  Series f;
  if (a.is_zero()) {
    f = fold(a, 1, 1, bind);
  } else if (manifestly_nonnegative((-a).expand())) {  // a = -t^2: a rotation (with a translation)
    const ex t = root_of_square((-a).expand());
    f = fold(a, GiNaC::cos(t), GiNaC::sin(t) / t, bind);
  } else if (manifestly_nonnegative(a)) {  // a = t^2: a boost
    const ex t = root_of_square(a);
    f = fold(a, GiNaC::cosh(t), GiNaC::sinh(t) / t, bind);
  } else {
    // The sign of a is not visible (a = (x y + z)^2 expanded): the kernel chooses at run time, branch-free,
    // between the rotation (a < 0) and the boost (a > 0) forms; near a = 0 (the null, translation-like case)
    // the Taylor select of fold() takes over, whose series serve both signs. t = sqrt(|a|) keeps the branch not
    // taken finite.
    const ex t = bind(GiNaC::sqrt(GiNaC::abs(a)));
    symbolic::Condition rotation;
    rotation.op = symbolic::Condition::Op::Lt;
    rotation.a = a;
    rotation.b = 0;
    f = fold(a, bind(symbolic::make_select(rotation, GiNaC::cos(t), GiNaC::cosh(t))),
             bind(symbolic::make_select(rotation, GiNaC::sin(t) / t, GiNaC::sinh(t) / t)), bind);
  }
  return Multivector(f.c) + (f.s / 2) * four + b * (f.s * Multivector(ex(1)) + f.sp * four);
}

Multivector logarithm(const Call& c) {
  const front::SourceLoc at = c.expr.args[0]->loc;
  const Multivector x = c.ctx.scalar_part_if_scalar(c.args[0]);
  if (x.is_scalar()) return Multivector(GiNaC::log(x.scalar()));
  const Multivector m = c.ctx.bind_if_long(nonvanishing(c.ctx, x), at);
  const Bind bind = [&](const ex& e) { return c.ctx.bind_if_long(Multivector(e), at).scalar(); };
  const Multivector m2 = m.grade(2), m4 = m.grade(4);
  const ex m0 = m.scalar();
  if (!(m - Multivector(m0) - m2 - m4).is_zero() || m2.is_zero())
    throw CompileError(at, "'log' takes a positive scalar, or a rotor or motor (a scalar and a bivector, and a "
                           "4-vector for a screw), got " + describe(m));
  const ex q = nonvanishing(c.ctx, m2 * m2).scalar();  // one plane: a S^2, -sin^2 t or sinh^2 t
  const Multivector m44 = nonvanishing(c.ctx, m4 * m4);
  if (!m44.is_zero()) {
    if (!m44.is_scalar() || !manifestly_nonnegative((-m44.scalar()).expand()))
      throw CompileError(at, "'log' of a motor of two commuting planes is supported where one is a rotation and "
                             "the other a boost (its 4-vector part squared visibly <= 0, as a rotation with a "
                             "dilation)");
    return log_two_planes(m0, m2, m4, q, -m44.scalar(), bind);
  }
  Series f;
  if (manifestly_nonnegative((-q).expand())) {
    const ex r = bind(GiNaC::sqrt((-q).expand())), t = bind(GiNaC::atan2(r, m0));
    f = fold(-t * t, m0, r / t, bind);
  } else if (manifestly_nonnegative(q)) {
    const ex r = bind(GiNaC::sqrt(q)), t = bind(GiNaC::log(r + GiNaC::sqrt(q + 1)));
    f = fold(t * t, m0, r / t, bind);
  } else {
    throw CompileError(at, "'log': cannot tell the sign of <B*B>_0 for the bivector part B of its argument: it "
                           "must be visibly <= 0 (a rotor) or >= 0 (a boost)");
  }
  const Multivector out = m2 / f.s - (2 * f.sp / GiNaC::pow(f.s, 3)) * (m2 * m4);
  return out.grade(2);
}

}  // namespace cgagen::expand_builtins
