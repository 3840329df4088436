// -O2 pass "equal temporaries": a temporary whose value is the same expression as an earlier one's (or its
// negation) is replaced by that one. The sharing passes work on one form at a time and the factoring makes
// new inner sums late, so two statements of a script that compute the same difference (t4 = t2 - t3;
// t5 = t2 - t3) can each keep their own; this pass runs last and merges them by canonical key, repeating
// down the list (a merge can make two later temporaries equal).
#include <map>
#include <string>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

void merge_equal_temps(CseState& st, std::vector<ex>& roots) {
  exmap merged;                          // dropped temporary -> its earlier equal (or minus it)
  std::map<std::string, ex> first;       // canonical key of a kept temporary's value -> its symbol
  std::vector<Temp> kept;
  // e with the merged temporaries it uses replaced. GiNaC's subs() scans its whole map on every call, so
  // each expression gets a map of only the symbols it has (one map for all was quadratic in the temporaries).
  auto replaced = [&](const ex& e) {
    if (merged.empty()) return e;
    ExSet used;
    collect_symbols(e, used);
    exmap local;
    for (const auto& u : used)
      if (auto it = merged.find(u); it != merged.end()) local.insert(*it);
    return orient_sums(local.empty() ? e : e.subs(local, kSymbolSubs), st.keys);
  };
  for (auto t : st.temps) {
    t.value = replaced(t.value);
    if (is_atomic(t.value)) {
      kept.push_back(t);
      continue;
    }
    const std::string key = st.keys.key(t.value);
    if (auto it = first.find(key); it != first.end()) {
      merged[t.sym] = it->second;
      continue;
    }
    if (auto it = first.find(st.keys.key(-t.value)); it != first.end()) {
      merged[t.sym] = -it->second;
      continue;
    }
    first.emplace(key, t.sym);
    kept.push_back(t);
  }
  if (merged.empty()) return;
  st.temps = std::move(kept);
  for (auto& r : roots) r = replaced(r);
}

}  // namespace cgagen::opt::detail
