// -O2 pass "single-use inlining": a temporary used once goes back into its user; an unused one is dropped.
#include <map>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// Temporaries used once are put back into their user; unused ones are dropped.
void inline_single_use(CseState& st, std::vector<ex>& roots) {
  // Occurrences of each temporary's symbol per expression (node k < T: temporary k, else root k - T),
  // kept up to date as values change, so a pass costs the size of the program, not temps x program.
  const size_t nt = st.temps.size();
  symbolic::ExHashMap<size_t> temp_index;
  for (size_t i = 0; i < nt; ++i) temp_index[st.temps[i].sym] = i;
  std::vector<std::map<size_t, int>> occ(nt);  // temp -> node -> occurrences
  auto account = [&](const ex& e, size_t node, int delta) {
    for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (is_a<symbol>(*it))
        if (auto ti = temp_index.find(*it); ti != temp_index.end())
          if ((occ[ti->second][node] += delta) == 0) occ[ti->second].erase(node);
  };
  auto value_of = [&](size_t node) -> ex& { return node < nt ? st.temps[node].value : roots[node - nt]; };
  for (size_t i = 0; i < nt; ++i) account(st.temps[i].value, i, +1);
  for (size_t r = 0; r < roots.size(); ++r) account(roots[r], nt + r, +1);
  std::vector<bool> alive(nt, true);
  for (size_t i = nt; i-- > 0;) {
    const Temp t = st.temps[i];
    int uses = 0;
    for (const auto& [node, n] : occ[i]) uses += n;
    if (uses >= 2) continue;
    if (uses == 1) {
      const size_t user = occ[i].begin()->first;
      ex& target = value_of(user);
      ex v = target.subs(exmap{{t.sym, t.value}}, kSymbolSubs);
      // GiNaC may re-simplify on substitution; keep the temporary when that would cost more.
      if (user < nt && count_ops(v, st.keys).weighted() >
                           count_ops(target, st.keys).weighted() + count_ops(t.value, st.keys).weighted())
        continue;
      account(target, user, -1);
      target = v;
      account(target, user, +1);
    }
    account(t.value, i, -1);
    alive[i] = false;
  }
  std::vector<Temp> kept;
  for (size_t i = 0; i < nt; ++i)
    if (alive[i]) kept.push_back(st.temps[i]);
  st.temps = std::move(kept);
}

}  // namespace cgagen::opt::detail
