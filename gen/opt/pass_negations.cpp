// -O2 pass "negations": a temporary that prints with a leading minus is stored negated.
#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// A temporary whose value prints with a leading minus, or is a sum whose first term (by key) is negative,
// is stored negated; its users absorb the sign.
void fold_negations(CseState& st, std::vector<ex>& roots) {
  exmap flip;
  for (auto& t : st.temps) {
    if (!flip.empty()) t.value = orient_sums(t.value.subs(flip, kSymbolSubs), st.keys);
    if (st.keys.sign(t.value) < 0) {
      t.value = -t.value;
      flip[t.sym] = -t.sym;
    }
  }
  if (!flip.empty())
    for (auto& r : roots) r = orient_sums(r.subs(flip, kSymbolSubs), st.keys);
}

}  // namespace cgagen::opt::detail
