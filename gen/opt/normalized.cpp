// `#pragma normalized X`: the caller promises X ~X = 1. Each blade of X ~X gives a polynomial identity in
// X's coefficients (scalar part = 1, every other blade = 0); -O2 may rewrite the output polynomials with
// them. A rule replaces a monomial by a polynomial without it: from the scalar part, a square v^2 (v
// appearing there only squared) by (1 - the rest) / its coefficient; from another blade, one of its
// bilinear terms u*w by minus the rest over its coefficient. Each choice of rules (one per identity) gives
// more candidate forms; the cheapest form wins as always, so the plain forms stay candidates.
#include <algorithm>

#include "opt/levels.hpp"
#include "symbolic/multivector.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

namespace {

// The rules one normalized input offers: per identity, its candidate rules (identities without any are left
// out).
std::vector<std::vector<Rule>> normalization_rules(const KernelInput& in) {
  symbolic::Multivector x;
  for (size_t i = 0; i < in.blades.size(); ++i) x += symbolic::Multivector::blade(in.blades[i], in.symbols[i]);
  const symbolic::Multivector n = x * x.reverse();
  std::vector<std::vector<Rule>> out;
  for (const auto& [blade, c0] : n.terms()) {
    const ex c = expand(blade == 0 ? c0 - 1 : c0);  // c = 0 when the input is normalized
    if (!is_a<add>(c)) continue;
    std::vector<Rule> candidates;
    for (size_t t = 0; t < c.nops(); ++t) {
      const ex term = c.op(t);
      ExSet syms;
      collect_symbols(term, syms);
      const ex rest = c - term;
      const ex beta = term.subs([&] {
        exmap ones;
        for (const auto& v : syms) ones[v] = 1;
        return ones;
      }(), kSymbolSubs);
      if (!is_a<numeric>(beta) || beta.is_zero()) continue;
      std::vector<std::pair<ex, int>> lead;
      bool ok = true;
      for (const auto& v : syms) {
        const int d = term.degree(v);
        if (rest.has(v) && !(syms.size() == 2 && d == 1)) ok = false;  // a square must be v's only occurrence
        lead.push_back({v, d});
      }
      const bool square = syms.size() == 1 && lead[0].second == 2, bilinear = syms.size() == 2 && lead[0].second == 1 && lead[1].second == 1;
      if (!ok || !(square || bilinear)) continue;
      candidates.push_back({lead, expand(-rest / beta)});
    }
    // GiNaC's term order (and ex_is_less on symbols) changes from process to process: the rules are put in
    // the order of their monomials' text, so that the same variants come in the same order everywhere.
    auto key = [](const Rule& r) {
      std::vector<std::string> parts;
      for (const auto& [v, e] : r.lead) parts.push_back(ex_to<symbol>(v).get_name() + "^" + std::to_string(e));
      std::sort(parts.begin(), parts.end());
      std::string k;
      for (const auto& p : parts) k += p + "*";
      return k;
    };
    for (auto& r : candidates)
      std::sort(r.lead.begin(), r.lead.end(), [](const auto& a, const auto& b) {
        return ex_to<symbol>(a.first).get_name() < ex_to<symbol>(b.first).get_name();
      });
    std::sort(candidates.begin(), candidates.end(), [&](const Rule& a, const Rule& b) { return key(a) < key(b); });
    if (!candidates.empty()) out.push_back(std::move(candidates));
  }
  return out;
}

// p (expanded) with every occurrence of the rule's monomial replaced, as often as it divides a term.
ex apply_rule(const ex& p, const Rule& r) {
  auto one = [&](const ex& term) -> ex {
    int k = -1;
    for (const auto& [v, e] : r.lead) {
      if (!term.is_polynomial(v)) return term;
      const int d = term.degree(v) / e;
      k = k < 0 ? d : std::min(k, d);
    }
    if (k <= 0) return term;
    ex divisor = 1;
    for (const auto& [v, e] : r.lead) divisor *= pow(v, e * k);
    return expand(term / divisor * pow(r.rhs, k));
  };
  if (!is_a<add>(p)) return expand(one(p));
  exvector terms;
  for (size_t i = 0; i < p.nops(); ++i) terms.push_back(one(p.op(i)));
  return expand(dynallocate<add>(terms));
}

}  // namespace

// p rewritten with the rules until none applies (at most a few rounds; the rules' right sides do not
// contain their own monomials).
ex reduce_with(ex p, const std::vector<Rule>& rules) {
  for (int round = 0; round < 8; ++round) {
    ex before = p;
    for (const auto& r : rules) p = apply_rule(p, r);
    if (p.is_equal(before)) break;
  }
  return p;
}

// Every choice of one rule per identity of every normalized input (at most kMaxRuleSets, the first ones).
constexpr size_t kMaxRuleSets = 64;
std::vector<std::vector<Rule>> rule_sets(const Kernel& k) {
  std::vector<std::vector<Rule>> identities;
  for (const auto& name : k.normalized)
    for (const auto& in : k.inputs)
      if (in.name == name.name)
        for (auto& id : normalization_rules(in)) identities.push_back(std::move(id));
  if (identities.empty()) return {};
  std::vector<std::vector<Rule>> sets{{}};
  for (const auto& id : identities) {
    std::vector<std::vector<Rule>> next;
    for (const auto& set : sets)
      for (const auto& r : id)
        if (next.size() < kMaxRuleSets) {
          next.push_back(set);
          next.back().push_back(r);
        }
    sets = std::move(next);
  }
  return sets;
}

// `#pragma normalized` must name multivector inputs.
void check_normalized(const Kernel& k) {
  for (const auto& n : k.normalized) {
    auto in = std::find_if(k.inputs.begin(), k.inputs.end(), [&](const KernelInput& i) { return i.name == n.name; });
    if (in == k.inputs.end() || !in->is_multivector)
      throw front::CompileError(n.loc, "'#pragma normalized' names '" + n.name + "', which is not a multivector input " +
                                           "(declare it with '#pragma input " + n.name + " BLADE...')");
  }
}
}  // namespace cgagen::opt::detail
