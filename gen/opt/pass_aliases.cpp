// -O2 pass "aliases": a temporary whose value is one symbol or number is replaced by that value.
#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// A temporary whose value is a lone symbol or number (a form can leave `t1 = t0`) is replaced by that value.
void drop_aliases(CseState& st, std::vector<ex>& roots) {
  exmap alias;
  std::vector<Temp> kept;
  for (auto t : st.temps) {
    if (!alias.empty()) t.value = t.value.subs(alias, kSymbolSubs);
    if (is_atomic(t.value))
      alias[t.sym] = t.value;
    else
      kept.push_back(t);
  }
  st.temps = std::move(kept);
  if (!alias.empty())
    for (auto& r : roots) r = orient_sums(r.subs(alias, kSymbolSubs), st.keys);
}

}  // namespace cgagen::opt::detail
