// The expander's cost model (cost.hpp).
#include "expand/cost.hpp"

namespace cgagen::expand_cost {

std::size_t coefficient_terms(const GiNaC::ex& c) { return GiNaC::is_a<GiNaC::add>(c) ? c.nops() : 1; }

std::size_t terms(const symbolic::Multivector& m) {
  std::size_t n = 0;
  for (const auto& [b, c] : m.terms()) n += coefficient_terms(c);
  return n;
}

bool bindable(const symbolic::Multivector& m) {
  for (const auto& [b, c] : m.terms())
    if (coefficient_terms(c) > 1) return true;
  return false;
}

std::size_t product_terms(algebra::ProductKind kind, const symbolic::Multivector& a, const symbolic::Multivector& b) {
  std::size_t n = 0;
  for (const auto& [i, ca] : a.terms()) {
    const std::size_t ta = coefficient_terms(ca);
    for (const auto& [j, cb] : b.terms())
      if (!algebra::product(kind, i, j).empty()) n += ta * coefficient_terms(cb);
  }
  return n;
}

BindPlan plan_product(algebra::ProductKind kind, const symbolic::Multivector& a, const symbolic::Multivector& b) {
  BindPlan plan;
  if (product_terms(kind, a, b) <= kBindProductTerms) return plan;
  // Terms per blade: the operand whose coefficients are longer gains most from becoming symbols.
  const double da = a.is_zero() ? 0 : static_cast<double>(terms(a)) / static_cast<double>(a.terms().size());
  const double db = b.is_zero() ? 0 : static_cast<double>(terms(b)) / static_cast<double>(b.terms().size());
  const bool a_first = da >= db;
  bool& first = a_first ? plan.a : plan.b;
  bool& second = a_first ? plan.b : plan.a;
  const symbolic::Multivector& fm = a_first ? a : b;
  const symbolic::Multivector& sm = a_first ? b : a;
  if (bindable(fm)) first = true;
  // With the first operand's coefficients single symbols, the product has (blades of it) x (terms of the
  // other) terms.
  std::size_t after = 0;
  for (const auto& [i, c] : fm.terms())
    for (const auto& [j, d] : sm.terms())
      if (!algebra::product(kind, a_first ? i : j, a_first ? j : i).empty())
        after += (first ? 1 : coefficient_terms(c)) * coefficient_terms(d);
  if (after > kBindProductTerms && bindable(sm)) second = true;
  return plan;
}

}  // namespace cgagen::expand_cost
