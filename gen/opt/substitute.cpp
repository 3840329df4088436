// -O1's and -O2's first step: the script's values substituted into each other (only what the outputs need;
// a value too large to inline stays a temporary, "materialized"), and the plan of output slots built from
// the substituted values (identically-zero blades dropped unless a pragma asked for them).
#include <unordered_map>

#include "opt/levels.hpp"
#include "symbolic/node_cache.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

// Above this estimated size a value is not substituted into its users but kept as a temporary.
constexpr double kMaxInlineTerms = 4000;
// Above this size (tree_size, symbol occurrences counted as a tree) of a value with its earlier values
// substituted, it keeps them as temporaries too: the term estimate misses values that are sums under roots
// and divisors, and the zero test's normal() on such a form does not finish (Gaalop's GPS trilateration,
// whose distance checks reach 15 million). The bundled scripts stay below 11000, GPS's spheres at 92000.
constexpr size_t kMaxInlineTreeSize = 100000;
// Above this size (printed_size) of one needed value with its earlier values substituted and expanded, the
// -O1 form is taken as over its budget (kMaxExpandedNodes) and substitution stops: the value becomes part of
// an output or a temporary, unless later values cancel it, and substituting it further costs time
// quadratic in the script (a chain M = M*R: each M is one term longer than the one before, of one degree
// more; 800 steps took 15 s). The budget itself, not a multiple: the work up to the stop grows with the
// square of the limit (twice the budget cost the 800-step chain 0.75 G of its 3.7 G instructions), and a
// value that large whose later users cancel it has not been seen; the bundled scripts' values that -O1
// keeps expanded stay far below.
constexpr size_t kMaxValueNodes = kMaxExpandedNodes;

// e.subs(at, kSymbolSubs) for a map from symbols to values, computing each shared node once across all
// calls (the outputs of a normalized value share one root of a large sum), and the result with each power
// of non-integer exponent expanded once (expand() would expand that root's argument again for every
// coefficient it appears in). Valid while `at` only grows; clear() when an entry changes.
class SharedSubs {
 public:
  explicit SharedSubs(const exmap& at) : at_(at) {}
  void clear() { subs_.clear(); }

  ex subs(const ex& e) {
    if (is_a<symbol>(e)) {
      auto it = at_.find(e);
      return it == at_.end() ? e : it->second;
    }
    if (e.nops() == 0) return e;
    if (auto it = subs_.find(symbolic::node_of(e)); it != subs_.end()) return it->second.second;
    ex r;
    if (is_a<add>(e) || is_a<mul>(e)) {
      const bool product = is_a<mul>(e);
      const auto& pairs = symbolic::pairs_of(e);
      exvector parts;
      parts.reserve(pairs.size() + 1);
      for (const auto& p : pairs) parts.push_back(product ? pow(subs(p.rest), p.coeff) : subs(p.rest) * p.coeff);
      if (e.nops() > pairs.size()) parts.push_back(e.op(e.nops() - 1));  // the numeric overall coefficient
      r = product ? ex(dynallocate<mul>(parts)) : ex(dynallocate<add>(parts));
    } else if (is_a<power>(e)) {
      r = pow(subs(e.op(0)), subs(e.op(1)));
    } else {
      r = e.subs(at_, kSymbolSubs);
    }
    subs_.emplace(symbolic::node_of(e), std::make_pair(e, r));
    return r;
  }

  // e with every power of non-integer exponent outside function arguments replaced by its expansion
  // (what expand(e) does to it, flagged expanded, so that expand(e) takes it as it is).
  ex roots_expanded(const ex& e) {
    if (e.nops() == 0 || is_a<function>(e)) return e;  // expand() leaves function arguments alone
    if (auto it = roots_.find(symbolic::node_of(e)); it != roots_.end()) return it->second.second;
    ex r;
    if (is_a<power>(e) && !(is_a<numeric>(e.op(1)) && ex_to<numeric>(e.op(1)).is_integer())) {
      r = e.expand();
    } else {
      struct Op : map_function {
        SharedSubs& self;
        explicit Op(SharedSubs& s) : self(s) {}
        ex operator()(const ex& x) override { return self.roots_expanded(x); }
      } op(*this);
      r = e.map(op);
    }
    roots_.emplace(symbolic::node_of(e), std::make_pair(e, r));
    return r;
  }

 private:
  const exmap& at_;
  std::unordered_map<const basic*, std::pair<ex, ex>> subs_, roots_;  // node -> (node kept alive, result)
};

}  // namespace

Substituted substitute(const Kernel& k) {
  Substituted s;
  // How many output slots each value coefficient fills: their sizes add up to the -O1 form's size.
  std::map<ex, size_t, ex_is_less> slot_uses;
  for (const auto& o : k.outputs) {
    const auto& v = k.values.at(o.value);
    for (const auto& sym : v.symbols) s.needed.insert(sym);
    for (auto b : o.blades)
      if (int i = blade_pos(v, b); i >= 0) ++slot_uses[v.symbols[static_cast<size_t>(i)]];
  }
  size_t counted = 0;  // a lower bound of expanded_size(): output slots known so far
  for (auto v = k.values.rbegin(); v != k.values.rend(); ++v)
    for (size_t i = 0; i < v->blades.size(); ++i)
      if (s.needed.count(v->symbols[i])) collect_symbols(v->coeffs[i], s.needed);
  exmap subst;
  SharedSubs shared(subst);
  std::map<ex, double, ex_is_less> sizes;
  ExSet materialized;
  for (const auto& v : k.values)
    for (size_t i = 0; i < v.blades.size(); ++i) {
      const ex& sym = v.symbols[i];
      if (!s.needed.count(sym)) continue;
      Rat r;
      ex inlined;
      if (estimate_terms(v.coeffs[i], sizes) <= kMaxInlineTerms &&
          tree_size(inlined = shared.subs(v.coeffs[i])) <= kMaxInlineTreeSize) {
        r = canonical(shared.roots_expanded(inlined));
      } else {
        ExSet used;
        collect_symbols(v.coeffs[i], used);
        for (const auto& u : used)
          // A value that is one input or one number (a point's x, its e0 coefficient 1) stays substituted:
          // as a temporary it would only turn 1*z into products the later levels cannot fold.
          if (s.full.count(u) && !materialized.count(u) && !is_atomic(s.full.at(u).value())) {
            materialized.insert(u);
            subst.erase(u);
            sizes.erase(u);
            shared.clear();
            // A materialized value is a temporary of the -O1 form: its size counts towards that form's.
            counted += printed_size(s.full.at(u).value());
          }
        if (counted > kMaxCountedNodes) {
          s.over_count = true;
          return s;
        }
        r = canonical(shared.roots_expanded(shared.subs(v.coeffs[i])));
      }
      if (printed_size(r.num) > kMaxValueNodes) {
        s.over_count = true;
        return s;
      }
      subst[sym] = r.value();
      sizes[sym] = is_a<add>(r.num) ? static_cast<double>(r.num.nops()) : 1.0;
      s.full[sym] = r;
      // An output coefficient that combine_fractions keeps is the -O1 slot as it stands.
      if (auto u = slot_uses.find(sym); u != slot_uses.end() && combine_keeps(r)) {
        counted += u->second * printed_size(r.num);
        if (counted > kMaxCountedNodes) {
          s.over_count = true;
          return s;
        }
      }
    }
  for (const auto& v : k.values)
    for (const auto& sym : v.symbols)
      if (materialized.count(sym)) s.materialized.push_back(sym);
  return s;
}

// The materialized values as temporaries (named after the script's values).
std::vector<Temp> materialized_temps(const Kernel& k, const Substituted& s) {
  std::vector<Temp> temps;
  const ValueNames names(k);
  const ExSet materialized(s.materialized.begin(), s.materialized.end());  // (a list scan per value was quadratic)
  for (size_t vi = 0; vi < k.values.size(); ++vi) {
    const auto& v = k.values[vi];
    for (size_t i = 0; i < v.blades.size(); ++i)
      if (materialized.count(v.symbols[i]))
        temps.push_back({names.of(vi, i), v.symbols[i], s.full.at(v.symbols[i]).value()});
  }
  return temps;
}

std::vector<std::vector<SlotPlan>> plan_slots(const Kernel& k, const Substituted& s) {
  std::vector<std::vector<SlotPlan>> plans;
  for (const auto& o : k.outputs) {
    const auto& v = k.values.at(o.value);
    const bool keep_zeros = o.from_pragma;  // pragma'd blades are always returned, zero ones as literal 0
    std::vector<SlotPlan> slots;
    for (auto b : o.blades) {
      int i = blade_pos(v, b);
      SlotPlan sp{o.name, b, {0, 1}, ex(0)};
      if (i >= 0 && s.over_count) {
        // Only the statement form is built: the blade is the value's (the expander dropped the blades whose
        // coefficients vanish), its value is the value's symbol.
        sp.value = {v.symbols[i], 1};
        sp.value_sym = v.symbols[i];
      } else if (i >= 0) {
        sp.value = combine_fractions(s.full.at(v.symbols[i]));
        sp.value_sym = v.symbols[i];
      }
      if (sp.value.num.is_zero()) {
        sp.value_sym = 0;
        if (!keep_zeros) continue;
      }
      slots.push_back(sp);
    }
    if (slots.empty() && !o.blades.empty()) slots.push_back({o.name, o.blades.front(), {0, 1}, ex(0)});
    plans.push_back(std::move(slots));
  }
  return plans;
}
}  // namespace cgagen::opt::detail
