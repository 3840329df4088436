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
  for (auto t : st.temps) {
    if (!merged.empty()) t.value = orient_sums(t.value.subs(merged, kSymbolSubs), st.keys);
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
  for (auto& r : roots) r = orient_sums(r.subs(merged, kSymbolSubs), st.keys);
}

}  // namespace cgagen::opt::detail
