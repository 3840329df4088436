// The inverse of a multivector (inverse.hpp): versor form, Clifford-conjugate form, then the adjugate.
#include "expand/inverse.hpp"

#include <algorithm>

#include "algebra/algebra.hpp"
#include "expand/builtins.hpp"
#include "expand/cost.hpp"

namespace cgagen::expand_inverse {

namespace {

// The adjugate's size limit, in terms summed over its blades. The inverse of a full 4D multivector (STA) stays
// below 500, that of a 5D scalar plus four bivectors below 150.
constexpr std::size_t kMaxAdjugateTerms = 1000;

// The adjugate of x for an algebra of n vectors: with N = 2^ceil(n/2), U_1 = x, C_k = (N/k) <U_k>_0,
// U_k = x (U_(k-1) - C_(k-1)), and adj(x) = U_(N-1) - C_(N-1) (up to a sign that cancels in adj / (x adj)).
Multivector adjugate(const Multivector& x, int n) {
  const int big_n = 1 << ((n + 1) / 2);
  Multivector u = x;
  GiNaC::ex c = big_n * u.scalar();
  for (int k = 2; k < big_n; ++k) {
    u = x * (u - Multivector(c));
    c = GiNaC::numeric(big_n, k) * u.scalar();
    // The recursion's terms grow as the k-th power of x's: a general motor with dilation blades (12 blades
    // in CGA) would take minutes to print and compile. Past the limit the caller is told how to say that x
    // is a versor, whose inverse is ~x / (x ~x).
    if (expand_cost::terms(u) > kMaxAdjugateTerms)
      throw NotInvertible{"the general inverse of this multivector (with blades " + expand_builtins::blade_list(x) +
                          ") is over cgagen's work budget (its adjugate passes " + std::to_string(kMaxAdjugateTerms) +
                          " terms); if it is a versor for the inputs passed (d*~d a scalar), name it and say so "
                          "with '#pragma versor NAME'"};
  }
  return u - Multivector(c);
}

}  // namespace

Inverse inverse(const Multivector& x, const std::function<bool(const GiNaC::ex&)>& vanishes) {
  // m's scalar part when every other blade vanishes (then zero when that vanishes too), else m.
  auto scalar_part_if_scalar = [&](const Multivector& m) {
    const Multivector r = m.without([&](algebra::BladeIndex b, const GiNaC::ex& c) { return b != 0 && vanishes(c); });
    return r.is_scalar() && !r.is_zero() && vanishes(r.scalar()) ? Multivector() : r;
  };
  const Multivector rev = x.reverse();
  const Multivector norm = scalar_part_if_scalar(x * rev);
  if (norm.is_scalar()) {
    if (norm.is_zero()) throw NotInvertible{"cannot divide by a null multivector (d*~d = 0)"};
    return {rev, norm.scalar()};
  }
  const Multivector conj = rev.involute();
  const Multivector cnorm = scalar_part_if_scalar(x * conj);
  if (cnorm.is_scalar()) {
    if (cnorm.is_zero())
      throw NotInvertible{"cannot divide by this multivector: it has no inverse (d*conjugate(d) = 0)"};
    return {conj, cnorm.scalar()};
  }
  // The recursion is proved for nondegenerate algebras. A degenerate one is a subalgebra of the nondegenerate
  // algebra with a pair e+, e- per null vector, so its null vectors may have to count twice; the shorter
  // recursion is tried first, and the product x adj(x) decides.
  const algebra::Algebra& alg = algebra::current();
  const auto& metric = alg.spec().metric;
  const int nulls = static_cast<int>(std::count(metric.begin(), metric.end(), 0));
  Multivector adj = adjugate(x, alg.dimension());
  Multivector det = scalar_part_if_scalar(x * adj);
  if (!det.is_scalar() && nulls > 0 && (alg.dimension() + 1) / 2 != (alg.dimension() + nulls + 1) / 2) {
    adj = adjugate(x, alg.dimension() + nulls);
    det = scalar_part_if_scalar(x * adj);
  }
  if (!det.is_scalar())
    throw NotInvertible{"cannot divide by this multivector: d*adj(d) is not a scalar (it has blades " +
                        expand_builtins::blade_list(det.grade_above(0)) + ")"};
  if (det.is_zero())
    throw NotInvertible{"cannot divide by this multivector: it has no inverse (its determinant d*adj(d) is 0)"};
  return {adj, det.scalar()};
}

Inverse versor_inverse(const Multivector& x, const std::function<bool(const GiNaC::ex&)>& vanishes) {
  const Multivector rev = x.reverse();
  const GiNaC::ex norm = graded_product(Multivector::Graded::Scalar, x, rev).scalar();
  if (norm.is_zero() || vanishes(norm)) throw NotInvertible{"cannot divide by a null multivector (d*~d = 0)"};
  return {rev, norm};
}

}  // namespace cgagen::expand_inverse
