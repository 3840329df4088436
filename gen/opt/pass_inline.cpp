// -O2 pass "single-use inlining": a temporary used once goes back into its user; an unused one is dropped.
#include <algorithm>
#include <map>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// A temporary is not inlined where its user would pass this many symbol occurrences or this depth (the
// bundled and test scripts stay below 350 and 9). A chain of single-use temporaries (M = M*R: one blade's
// coefficient feeds only the next one's) would otherwise become one expression as deep as the script, and
// each inlining walks its user and keys its new nodes: time and memory quadratic in the script.
constexpr size_t kMaxInlinedSymbols = 1000;
constexpr size_t kMaxInlinedDepth = 32;

// Temporaries used once are put back into their user; unused ones are dropped.
void inline_single_use(CseState& st, std::vector<ex>& roots) {
  // Occurrences of each temporary's symbol per expression (node k < T: temporary k, else root k - T),
  // kept up to date as values change, so a pass costs the size of the program, not temps x program.
  const size_t nt = st.temps.size();
  symbolic::ExHashMap<size_t> temp_index;
  for (size_t i = 0; i < nt; ++i) temp_index[st.temps[i].sym] = i;
  std::vector<std::map<size_t, int>> occ(nt);  // temp -> node -> occurrences
  // Each expression's symbol occurrences and depth (as a tree; a symbol or number has depth 0).
  std::vector<size_t> size(nt + roots.size(), 0), depth(nt + roots.size(), 0);
  auto account = [&](const ex& e, size_t node, int delta) {
    size_t n = 0;
    auto walk = [&](auto&& self, const ex& x) -> size_t {
      if (is_a<symbol>(x)) {
        ++n;
        if (auto ti = temp_index.find(x); ti != temp_index.end())
          if ((occ[ti->second][node] += delta) == 0) occ[ti->second].erase(node);
        return 0;
      }
      size_t d = 0;
      for (size_t k = 0; k < x.nops(); ++k) d = std::max(d, self(self, x.op(k)) + 1);
      return d;
    };
    const size_t d = walk(walk, e);
    if (delta > 0) size[node] = n, depth[node] = d;
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
      if (size[user] + size[i] > kMaxInlinedSymbols || depth[user] + depth[i] > kMaxInlinedDepth) continue;
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
