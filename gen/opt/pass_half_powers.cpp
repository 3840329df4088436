// -O2 pass "half-powers": the powers y^(k/2) (k odd) of one base share one square root of it.
//
// GiNaC keeps sqrt(y) and 1/sqrt(y) as two powers of y (exponents 1/2 and -1/2), which no sharing pass sees as
// one value: the exponential of a line printed sin(t7) / std::sqrt(t3) beside t7 = std::sqrt(t3), a second
// root (a call, and in C++ its errno branch) for a value already computed. Here every base with two or more
// half-integer powers gets one temporary s = sqrt(y) (a temporary whose value is already sqrt(y) serves), and
// y^(k/2) becomes s^k: 1/sqrt(y) is 1/s, y^(3/2) is s*s*s instead of a pow() call. For y >= 0 the two are
// equal; for y < 0 both are NaN. A root used once is put back by the inlining pass.
#include <map>
#include <set>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

bool is_half_power(const ex& e) {
  if (!is_a<power>(e) || !is_a<numeric>(e.op(1))) return false;
  const numeric q = ex_to<numeric>(e.op(1));
  return q.is_rational() && !q.is_integer() && q.denom() == 2;
}

// The half-integer powers of e, each node once. The visited nodes are kept alive: op()
// of a product builds its power factors afresh, and a freed node's address can come back as another node.
void collect_half_powers(const ex& e, std::set<const basic*>& seen, std::vector<ex>& kept, std::vector<ex>& out) {
  if (!seen.insert(&ex_to<basic>(e)).second) return;
  kept.push_back(e);
  if (is_half_power(e)) out.push_back(e);
  for (size_t i = 0; i < e.nops(); ++i) collect_half_powers(e.op(i), seen, kept, out);
}

}  // namespace

void half_powers(CseState& st, std::vector<ex>& roots) {
  // Per base (by canonical key, so the order of new temporaries is the same in every process): the base,
  // its half powers as they occur, and a temporary already holding sqrt(base).
  struct Base {
    ex base;
    std::vector<ex> powers;
    const Temp* root = nullptr;
  };
  std::map<std::string, Base> bases;
  auto scan = [&](const ex& e) {
    std::set<const basic*> seen;
    std::vector<ex> kept, found;
    collect_half_powers(e, seen, kept, found);
    for (const ex& p : found) {
      Base& b = bases[st.keys.key(p.op(0))];
      b.base = p.op(0);
      b.powers.push_back(p);
    }
  };
  for (const auto& t : st.temps) scan(t.value);
  for (const auto& r : roots) scan(r);
  for (const auto& t : st.temps)
    if (is_half_power(t.value) && ex_to<numeric>(t.value.op(1)) == numeric(1, 2))
      if (auto it = bases.find(st.keys.key(t.value.op(0))); it != bases.end() && !it->second.root)
        it->second.root = &t;

  exmap replace;
  std::set<ex, ex_is_less> roots_of;  // the temporaries holding a root: their value stays sqrt(base)
  std::vector<Temp> added;
  for (auto& [key, b] : bases) {
    if (b.powers.size() < 2) continue;
    ex s;
    if (b.root) {
      s = b.root->sym;
      roots_of.insert(s);
    } else {
      added.push_back(st.make_temp(sqrt(b.base)));
      s = added.back().sym;
      roots_of.insert(s);
    }
    for (const ex& p : b.powers) replace[p] = pow(s, 2 * ex_to<numeric>(p.op(1)));
  }
  if (replace.empty()) return;
  constexpr unsigned kExact = subs_options::no_pattern;
  st.temps.insert(st.temps.end(), added.begin(), added.end());
  // A root's own value keeps its square root; the powers of other bases inside its base are replaced.
  for (auto& t : st.temps)
    t.value = roots_of.count(t.sym) ? sqrt(t.value.op(0).subs(replace, kExact)) : t.value.subs(replace, kExact);
  for (auto& r : roots) r = r.subs(replace, kExact);
  topo_sort(st);
}

}  // namespace cgagen::opt::detail
