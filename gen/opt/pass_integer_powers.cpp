// -O2 pass "integer-powers": the integer powers of one symbol built from each other (x^4 = x^2 x^2).
//
// The printing rules spell x^n as n - 1 multiplications, each power on its own: the small-angle series of the
// exponentials and logarithms use θ², θ⁴, θ⁶ and θ⁸ of one angle, 1 + 3 + 5 + 7 multiplications. Here the
// powers |n| >= 2 that a symbol is raised to become temporaries, each the product of two smaller ones or of
// the square of one (an addition chain: n even from n/2, else from the largest smaller power and the
// difference, both made on the way), so those four cost 4 multiplications. Negative powers read the same
// temporaries (x^-3 = 1 / x³). A symbol is rewritten only when that costs fewer multiplications than the
// powers as printed, each counted once (they are shared subtrees by now, or are made so here).
#include <map>
#include <set>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

// The integer powers x^n (|n| >= 2) of symbols in e, each node once. The visited nodes are kept alive: op()
// of a product builds its power factors afresh, and a freed node's address can come back as another node.
void collect_powers(const ex& e, std::set<const basic*>& seen, std::vector<ex>& kept, std::vector<ex>& out) {
  if (!seen.insert(&ex_to<basic>(e)).second) return;
  kept.push_back(e);
  if (is_a<power>(e) && is_a<symbol>(e.op(0)) && e.op(1).info(info_flags::integer) &&
      abs(ex_to<numeric>(e.op(1))) >= 2)
    out.push_back(e);
  for (size_t i = 0; i < e.nops(); ++i) collect_powers(e.op(i), seen, kept, out);
}

}  // namespace

void integer_powers(CseState& st, std::vector<ex>& roots) {
  // Per symbol (by name, so that new temporaries come in the same order in every process): the exponents
  // |n| it is raised to, and the power nodes as they occur.
  struct Base {
    ex symbol;
    std::set<long> exponents;
    std::vector<ex> nodes;
  };
  std::map<std::string, Base> bases;
  auto scan = [&](const ex& e) {
    std::set<const basic*> seen;
    std::vector<ex> kept, found;
    collect_powers(e, seen, kept, found);
    for (const ex& p : found) {
      Base& b = bases[st.keys.key(p.op(0))];
      b.symbol = p.op(0);
      b.exponents.insert(std::abs(ex_to<numeric>(p.op(1)).to_long()));
      b.nodes.push_back(p);
    }
  };
  for (const auto& t : st.temps) scan(t.value);
  for (const auto& r : roots) scan(r);

  exmap replace;
  std::vector<Temp> added;
  for (auto& [key, b] : bases) {
    // The chain: every exponent asked for, and what building them needs on the way.
    std::map<long, std::pair<long, long>> chain;  // n -> (p, q), x^n = x^p x^q; x^1 is the symbol
    auto need = [&](auto&& self, long n) -> void {
      if (n == 1 || chain.count(n)) return;
      long p = n / 2, q = n - n / 2;
      if (n % 2 != 0) {
        // The largest power already in the chain below n, else n - 1.
        p = 1;
        for (const auto& [m, _] : chain)
          if (m < n) p = std::max(p, m);
        if (p == 1) p = n - 1;
        q = n - p;
      }
      self(self, p), self(self, q);
      chain[n] = {p, q};
    };
    for (long n : b.exponents) need(need, n);
    long printed = 0;
    for (long n : b.exponents) printed += n - 1;
    if (static_cast<long>(chain.size()) >= printed) continue;
    std::map<long, ex> sym{{1, b.symbol}};
    for (const auto& [n, pq] : chain) {
      added.push_back(st.make_temp(sym.at(pq.first) * sym.at(pq.second)));
      sym[n] = added.back().sym;
    }
    for (const ex& node : b.nodes) {
      const long n = ex_to<numeric>(node.op(1)).to_long();
      replace[node] = n > 0 ? sym.at(n) : pow(sym.at(-n), -1);
    }
  }
  if (replace.empty()) return;
  constexpr unsigned kExact = subs_options::no_pattern;
  for (auto& t : st.temps) t.value = t.value.subs(replace, kExact);
  for (auto& r : roots) r = r.subs(replace, kExact);
  st.temps.insert(st.temps.end(), added.begin(), added.end());
  topo_sort(st);
}

}  // namespace cgagen::opt::detail
