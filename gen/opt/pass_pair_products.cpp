// -O2 pass "pair products": the factor pair shared by most products becomes a temporary, greedily and
// repeatedly (ab c, ab d, ab e -> t = ab; t c, t d, t e), products rebuilt from the pairs.
#include <algorithm>
#include <functional>
#include <set>
#include <tuple>

#include "opt/cse.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

ex core_of(const ex& m) {
  ex c = 1;
  for (size_t i = 0; i < m.nops(); ++i)
    if (!is_a<numeric>(m.op(i))) c *= m.op(i);
  return c;
}

namespace {

class PairProducts {
 public:
  explicit PairProducts(CseState& s) : st(s) {}
  // Factors of a product core, powers with small integer exponents spelled out.
  static bool core_atoms(const ex& m, std::vector<ex>& atoms) {
    atoms.clear();
    for (size_t i = 0; i < m.nops(); ++i) {
      const ex& f = m.op(i);
      if (is_a<numeric>(f)) continue;
      if (is_a<power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_pos_integer() &&
          ex_to<numeric>(f.op(1)).to_int() <= 8) {
        for (int k = 0; k < ex_to<numeric>(f.op(1)).to_int(); ++k) atoms.push_back(f.op(0));
      } else {
        atoms.push_back(f);
      }
    }
    return atoms.size() >= 2;
  }


  void gather_muls(const ex& e, symbolic::ExHashSet& visited, std::vector<ex>& order) {
    if (is_atomic(e) || !visited.insert(e).second) return;
    for (const ex& c : ordered_children(e, st.keys)) gather_muls(c, visited, order);
    if (is_a<mul>(e)) {
      ex core = core_of(e);
      if (is_a<mul>(core) && !st.cores.count(core)) {
        std::vector<ex> atoms;
        if (core_atoms(core, atoms)) {
          st.cores[core] = atoms;
          order.push_back(core);
        }
      }
    }
  }

  // Greedy extraction of the factor pair shared by most products (repeatedly).
  void pair_products(std::vector<ex>& roots) {
    symbolic::ExHashSet visited;
    std::vector<ex> order;
    for (const auto& t : st.temps) gather_muls(t.value, visited, order);
    for (const auto& r : roots) gather_muls(r, visited, order);
    if (order.empty()) return;
    // Atoms are interned as ids; pair counts are kept up to date incrementally (only the cores holding a
    // chosen pair are recounted), and ties go to the pair first in canonical key order.
    std::vector<ex> atom_ex;
    std::vector<std::string> atom_key;
    symbolic::ExHashMap<int> atom_id;
    std::vector<std::set<size_t>> cores_with;  // atom id -> indices into `order` of the cores holding it
    auto intern = [&](const ex& a) {
      auto [it, fresh] = atom_id.emplace(a, static_cast<int>(atom_ex.size()));
      if (fresh) {
        atom_ex.push_back(a);
        atom_key.push_back(st.keys.magnitude(a) + "|" + st.keys.key(a));
        cores_with.emplace_back();
      }
      return it->second;
    };
    using Pair = std::pair<int, int>;  // (first, second) in key order
    auto make_pair_of = [&](int x, int y) { return atom_key[y] < atom_key[x] ? Pair{y, x} : Pair{x, y}; };
    std::vector<std::vector<int>> ids(order.size());
    std::map<Pair, int> count;
    auto pairs_of = [&](const std::vector<int>& v) {
      std::set<Pair> here;
      for (size_t i = 0; i < v.size(); ++i)
        for (size_t j = i + 1; j < v.size(); ++j) here.insert(make_pair_of(v[i], v[j]));
      return here;
    };
    // The pairs ordered best first (most cores, then first in key order), kept in step with `count`, so that
    // each greedy step takes the best pair at once: scanning every pair per step was quadratic in the
    // program's size (an 80-joint chain has thousands of pairs and as many steps).
    struct Better {
      const std::vector<std::string>* keys;
      bool operator()(const std::pair<int, Pair>& x, const std::pair<int, Pair>& y) const {
        if (x.first != y.first) return x.first > y.first;
        return std::tie((*keys)[x.second.first], (*keys)[x.second.second]) <
               std::tie((*keys)[y.second.first], (*keys)[y.second.second]);
      }
    };
    std::set<std::pair<int, Pair>, Better> ranked(Better{&atom_key});
    auto tally = [&](size_t c, int delta) {
      for (const Pair& pk : pairs_of(ids[c])) {
        int& n = count[pk];
        if (n >= 2) ranked.erase({n, pk});
        n += delta;
        if (n >= 2) ranked.insert({n, pk});
        if (n == 0) count.erase(pk);
      }
    };
    for (size_t c = 0; c < order.size(); ++c) {
      for (const auto& a : st.cores[order[c]]) ids[c].push_back(intern(a));
      for (int id : ids[c]) cores_with[id].insert(c);
      tally(c, +1);
    }
    std::vector<Temp> pair_temps;
    std::vector<std::pair<ex, ex>> pair_atoms;
    for (int iter = 0; iter < 100000; ++iter) {
      if (ranked.empty()) break;
      const Pair best = ranked.begin()->second;
      const auto ia = best.first, ib = best.second;  // not a structured binding: clang 14 cannot capture one
      const ex a = atom_ex[ia], b = atom_ex[ib];
      Temp t = st.make_temp(a * b);
      pair_temps.push_back(t);
      pair_atoms.push_back({a, b});
      const int it_id = intern(t.sym);
      const std::set<size_t> holders = cores_with[ia];
      for (size_t c : holders) {
        auto& v = ids[c];
        auto has_pair = [&] {
          auto pa = std::find(v.begin(), v.end(), ia);
          if (pa == v.end()) return false;
          return ia == ib ? std::find(pa + 1, v.end(), ib) != v.end() : std::find(v.begin(), v.end(), ib) != v.end();
        };
        if (!has_pair()) continue;
        tally(c, -1);
        while (has_pair()) {
          v.erase(std::find(v.begin(), v.end(), ia));
          v.erase(std::find(v.begin(), v.end(), ib));
          v.push_back(it_id);
        }
        for (int x : {ia, ib})
          if (std::find(v.begin(), v.end(), x) == v.end()) cores_with[x].erase(c);
        cores_with[it_id].insert(c);
        tally(c, +1);
      }
    }
    for (size_t c = 0; c < order.size(); ++c) {
      auto& atoms = st.cores[order[c]];
      atoms.clear();
      for (int id : ids[c]) atoms.push_back(atom_ex[id]);
    }
    if (pair_temps.empty()) return;
    ExMemo memo;
    // A pair's own product may be one of the rewritten cores (then it would refer to itself): build it
    // from its two atoms.
    for (size_t i = 0; i < pair_temps.size(); ++i)
      pair_temps[i].value = rebuild_products(pair_atoms[i].first, memo) * rebuild_products(pair_atoms[i].second, memo);
    for (auto& t : st.temps) t.value = rebuild_products(t.value, memo);
    for (auto& r : roots) r = rebuild_products(r, memo);
    // Pair temporaries only involve input atoms and earlier pairs; the atoms may reference input temps, so
    // they go after those.
    st.temps.insert(st.temps.end(), pair_temps.begin(), pair_temps.end());
  }

  ex rebuild_products(const ex& e, ExMemo& memo) {
    if (is_atomic(e)) return e;
    auto it = memo.find(e);
    if (it != memo.end()) return it->second;
    ex r;
    if (is_a<mul>(e)) {
      ex core = core_of(e);
      auto c = st.cores.find(core);
      numeric coeff = 1;
      for (size_t i = 0; i < e.nops(); ++i)
        if (is_a<numeric>(e.op(i))) coeff *= ex_to<numeric>(e.op(i));
      if (c != st.cores.end()) {
        ex prod = 1;
        for (const auto& a : c->second) prod *= rebuild_products(a, memo);
        r = coeff * prod;
      } else {
        r = rebuild_children(e, memo);
      }
    } else {
      r = rebuild_children(e, memo);
    }
    memo[e] = r;
    return r;
  }

  ex rebuild_children(const ex& e, ExMemo& memo) {
    struct F : map_function {
      PairProducts* self;
      ExMemo* memo;
      ex operator()(const ex& x) override { return self->rebuild_products(x, *memo); }
    } f;
    f.self = this;
    f.memo = &memo;
    return e.map(f);
  }

 private:
  CseState& st;
};

}  // namespace

void pair_products(CseState& st, std::vector<ex>& roots) { PairProducts(st).pair_products(roots); }

}  // namespace cgagen::opt::detail
