// exp and log of scalars, and the closed forms for bivectors and the rotors and motors they generate
// (docs/language.md, "exp and log").
//
// A bivector B squares to B B = a + b, a = <B B>_0 and b = <B B>_4, and b commutes with B. Where b b = 0
// (no part, or a nilpotent one: the 4-vector of a screw, a rotation with a translation along or off its axis)
// the series sum_k B^k / k! folds into
//     exp(B) = C(a) + S(a)/2 b + B (S(a) + S'(a) b),
//     C(a) = sum_m a^m / (2m)!,  S(a) = sum_m a^m / (2m+1)!,  S'(a) = dS/da = (C(a) - S(a)) / (2a),
// with C = cos t, S = sin t / t for a = -t^2 (rotations) and cosh t, sinh t / t for a = t^2 (boosts). A b with
// b b != 0 (a rotation with a dilation in CGA, which has two commuting planes with squares of both signs) is
// refused: write the product of the exps of its commuting parts.
// log(M) inverts exp for M = exp(B) with |t| < pi: from <M>_0 = C, <M>_2 = B (S + S' b) and <M>_4 = S/2 b,
// <<M>_2^2>_0 = a S^2 = -sin^2 t (a rotation) or sinh^2 t (a boost) gives t, and then
//     B = <M>_2 / S - 2 S' / S^3 <M>_2 <M>_4.
// Near a = 0 the closed forms are 0/0 (sin t / t) or lose digits to cancellation (C - S); there a select
// takes their Taylor series instead, so exp(0) = 1 and log(1) = 0 exactly, and a small angle keeps its digits.
#include <ginac/ginac.h>

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
  Multivector r = m;
  for (const auto& [b, c] : m.terms())
    if (ctx.vanishes(c)) r.set(b, 0);
  return r;
}

// C(a), S(a) and S'(a) (top of this file). `closed_c` and `closed_s` are C and S in closed form, for a whose
// square is not small; the Taylor series (to a^4, exact to double precision for |a| < 1/100) below it.
struct Series {
  ex c, s, sp;
};

Series fold(const ex& a, const ex& closed_c, const ex& closed_s) {
  const ex taylor_c = 1 + a / 2 + GiNaC::pow(a, 2) / 24 + GiNaC::pow(a, 3) / 720 + GiNaC::pow(a, 4) / 40320;
  const ex taylor_s = 1 + a / 6 + GiNaC::pow(a, 2) / 120 + GiNaC::pow(a, 3) / 5040 + GiNaC::pow(a, 4) / 362880;
  const ex taylor_sp =
      numeric(1, 6) + a / 60 + GiNaC::pow(a, 2) / 1680 + GiNaC::pow(a, 3) / 90720 + GiNaC::pow(a, 4) / 7983360;
  if (a.is_zero()) return {1, 1, numeric(1, 6)};
  symbolic::Condition small;
  small.op = symbolic::Condition::Op::Lt;
  small.a = a * a;
  small.b = numeric(1, 10000);
  return {symbolic::make_select(small, taylor_c, closed_c), symbolic::make_select(small, taylor_s, closed_s),
          symbolic::make_select(small, taylor_sp, (closed_c - closed_s) / (2 * a))};
}

}  // namespace

Multivector exponential(const Call& c) {
  Multivector b = c.ctx.scalar_part_if_scalar(c.args[0]);
  if (b.is_scalar()) return Multivector(GiNaC::exp(b.scalar()));
  const front::SourceLoc at = c.expr.args[0]->loc;
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
  if (!(sq - Multivector(a) - four).is_zero() || !nonvanishing(c.ctx, four * four).is_zero())
    throw CompileError(at, "'exp' of a bivector B whose square's 4-vector part <B*B>_4 does not square to 0 (two "
                           "commuting planes, such as a rotation with a dilation): write the product of the exps "
                           "of its commuting parts");
  Series f;
  if (a.is_zero()) {
    f = fold(a, 1, 1);
  } else if (manifestly_nonnegative((-a).expand())) {  // a = -t^2: a rotation (with a translation)
    const ex t = root_of_square((-a).expand());
    f = fold(a, GiNaC::cos(t), GiNaC::sin(t) / t);
  } else if (manifestly_nonnegative(a)) {  // a = t^2: a boost
    const ex t = root_of_square(a);
    f = fold(a, GiNaC::cosh(t), GiNaC::sinh(t) / t);
  } else {
    // (The square is not printed: GiNaC's term order differs between processes, and messages must not.)
    throw CompileError(at, "'exp': cannot tell the sign of the square of its bivector argument B: <B*B>_0 must be "
                           "visibly <= 0 (a rotation) or >= 0 (a boost)");
  }
  return Multivector(f.c) + (f.s / 2) * four + b * (f.s * Multivector(ex(1)) + f.sp * four);
}

Multivector logarithm(const Call& c) {
  const Multivector x = c.ctx.scalar_part_if_scalar(c.args[0]);
  if (x.is_scalar()) return Multivector(GiNaC::log(x.scalar()));
  const front::SourceLoc at = c.expr.args[0]->loc;
  const Multivector m = nonvanishing(c.ctx, x);
  const Multivector m2 = m.grade(2), m4 = m.grade(4);
  const ex m0 = m.scalar();
  if (!(m - Multivector(m0) - m2 - m4).is_zero() || m2.is_zero())
    throw CompileError(at, "'log' takes a positive scalar, or a rotor or motor (a scalar and a bivector, and a "
                           "4-vector for a screw), got " + describe(m));
  if (!nonvanishing(c.ctx, m4 * m4).is_zero())
    throw CompileError(at, "'log' of a motor whose 4-vector part does not square to 0 (two commuting planes, "
                           "such as a rotation with a dilation) is not supported");
  const ex q = nonvanishing(c.ctx, m2 * m2).scalar();  // a S^2: -sin^2 t or sinh^2 t
  Series f;
  if (manifestly_nonnegative((-q).expand())) {
    const ex r = GiNaC::sqrt((-q).expand()), t = GiNaC::atan2(r, m0);
    f = fold(-t * t, m0, r / t);
  } else if (manifestly_nonnegative(q)) {
    const ex r = GiNaC::sqrt(q), t = GiNaC::log(r + GiNaC::sqrt(q + 1));
    f = fold(t * t, m0, r / t);
  } else {
    throw CompileError(at, "'log': cannot tell the sign of <B*B>_0 for the bivector part B of its argument: it "
                           "must be visibly <= 0 (a rotor) or >= 0 (a boost)");
  }
  const Multivector out = m2 / f.s - (2 * f.sp / GiNaC::pow(f.s, 3)) * (m2 * m4);
  return out.grade(2);
}

}  // namespace cgagen::expand_builtins
