// -O2 pass "numeric factors": terms of a sum sharing a numeric factor c become c times a temporary of
// their sum (run by the sum-factoring pass on each sum it leaves).
#include <algorithm>
#include <utility>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// The numeric factor of a product term (1 when it has none).
numeric numeric_factor(const ex& term) {
  if (is_a<mul>(term))
    for (size_t i = 0; i < term.nops(); ++i)
      if (is_a<numeric>(term.op(i))) return ex_to<numeric>(term.op(i));
  return numeric(1);
}

// Terms of the sum that carry the same numeric factor c (|c| != 1) become c times a temporary of their sum:
// 2ab + 2cd - 2ef costs 6 mul, 2 t with t = ab + cd - ef 4. GiNaC distributes a number over a bare sum
// (2 (a + b) is 2a + 2b to it), hence the temporary.
ex group_numeric_factors(CseState& st, const ex& sum, std::vector<Temp>& out) {
  // Terms grouped by |numeric factor|, groups in the order of their first term by key.
  std::vector<std::pair<numeric, std::vector<ex>>> groups;
  ex rest = 0;
  for (const ex& term : ordered_children(sum, st.keys)) {
    const numeric c = abs(numeric_factor(term));
    if (c.is_equal(numeric(1)) || c.is_zero()) {
      rest += term;
      continue;
    }
    auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& x) { return x.first.is_equal(c); });
    if (g == groups.end())
      groups.push_back({c, {term}});
    else
      g->second.push_back(term);
  }
  bool changed = false;
  for (const auto& [c, terms] : groups) {
    if (terms.size() < 2) {
      rest += terms.front();
      continue;
    }
    ex inner = 0;
    for (const ex& term : terms) inner += term / c;
    inner = orient_sums(inner, st.keys);
    ex factor = c;
    if (st.keys.sign(inner) < 0) inner = -inner, factor = -c;
    Temp t = st.make_temp(inner);
    out.push_back(t);
    rest += factor * t.sym;
    changed = true;
  }
  return changed ? orient_sums(rest, st.keys) : sum;
}

}  // namespace cgagen::opt::detail
