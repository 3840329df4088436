// The optimizer levels -O0, -O1, -O2: Kernel -> Program (see program.hpp and docs/generator.md). -O2 builds
// several candidate forms (expanded, collected in the inputs, the script's statements), runs the pass
// pipeline (pipeline.cpp) on each and keeps the cheapest.
#include <algorithm>
#include <cctype>
#include <stdexcept>
#include <unordered_map>

#include "opt/cse.hpp"
#include "opt/program.hpp"
#include "symbolic/dag.hpp"
#include "symbolic/multivector.hpp"
#include "symbolic/node_cache.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using namespace detail;

Level parse_level(const std::string& text) {
  if (text == "-O0" || text == "O0" || text == "0") return Level::O0;
  if (text == "-O1" || text == "O1" || text == "1") return Level::O1;
  if (text == "-O2" || text == "O2" || text == "2") return Level::O2;
  throw std::invalid_argument("unknown optimization level '" + text + "' (expected -O0, -O1 or -O2)");
}

namespace {

// Above this estimated size a value is not substituted into its users but kept as a temporary.
constexpr double kMaxInlineTerms = 4000;
// Above this size (tree_size, symbol occurrences counted as a tree) of a value with its earlier values
// substituted, it keeps them as temporaries too: the term estimate misses values that are sums under roots
// and divisors, and the zero test's normal() on such a form does not finish (Gaalop's GPS trilateration,
// whose distance checks reach 15 million). The bundled scripts stay below 11000, GPS's spheres at 92000.
constexpr size_t kMaxInlineTreeSize = 100000;
// Above this size (tree_size) of the -O1 form, -O1 emits and -O2 optimizes only the script's statement form.
// The bundled runtime kernels stay below 1300; paper A.1 has 8807 and circle3 208494.
constexpr size_t kMaxExpandedNodes = 4000;
// Past this size of the -O1 form (counted while substituting, over the output coefficients that
// combine_fractions keeps as they are and the values kept as temporaries: a lower bound of the final size)
// substitution stops: the statement form is certain, and substituting the rest would only cost time (a
// 200-line dcga script: 2 million symbol occurrences; 400 squarings M = M*M: seconds). The note then says
// "more than".
constexpr size_t kMaxCountedNodes = kMaxExpandedNodes;


std::string sanitize(const std::string& s) {
  std::string r;
  for (char c : s) r += (std::isalnum(static_cast<unsigned char>(c)) || c == '_') ? c : '_';
  return r;
}

int blade_pos(const KernelValue& v, algebra::BladeIndex b) {
  auto it = std::find(v.blades.begin(), v.blades.end(), b);
  return it == v.blades.end() ? -1 : static_cast<int>(it - v.blades.begin());
}

Program skeleton(const Kernel& k, Level level) {
  Program p;
  p.name = k.name;
  p.algebra = k.algebra;
  p.level = level;
  p.inputs = k.inputs;
  return p;
}

// -O0: every value coefficient as a temporary, as written.
Program optimize_o0(const Kernel& k) {
  Program p = skeleton(k, Level::O0);
  Namer namer(k.inputs);
  std::map<std::string, int> seen;
  for (const auto& v : k.values) {
    int n = ++seen[v.name];
    std::string prefix = n == 1 ? "v_" : "v" + std::to_string(n) + "_";
    for (size_t i = 0; i < v.blades.size(); ++i)
      p.temps.push_back({namer.fresh(prefix + sanitize(v.name) + "_" + algebra::blade_ident(v.blades[i])),
                         v.symbols[i], v.coeffs[i]});
  }
  for (const auto& o : k.outputs) {
    ProgramOutput po{o.name, {}};
    const auto& v = k.values.at(o.value);
    for (auto b : o.blades) {
      int i = blade_pos(v, b);
      po.slots.push_back({b, i < 0 ? ex(0) : ex(v.symbols[i])});
    }
    p.outputs.push_back(std::move(po));
  }
  return p;
}

// Values substituted into each other, only for the coefficients the outputs need. A value coefficient
// whose expansion would be too large keeps its earlier values as temporaries ("materialized").
struct Substituted {
  ExSet needed;                        // value symbols the outputs need (transitively)
  std::map<ex, Rat, ex_is_less> full;  // value symbol -> coefficient over inputs and materialized values
  std::vector<ex> materialized;        // value symbols kept as temporaries, in kernel order
  // Substitution stopped early: the -O1 form has more than kMaxCountedNodes symbol occurrences, `full`
  // is incomplete and only the statement form is built.
  bool over_count = false;
};

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
            counted += tree_size(s.full.at(u).value());
          }
        if (counted > kMaxCountedNodes) {
          s.over_count = true;
          return s;
        }
        r = canonical(shared.roots_expanded(shared.subs(v.coeffs[i])));
      }
      subst[sym] = r.value();
      sizes[sym] = is_a<add>(r.num) ? static_cast<double>(r.num.nops()) : 1.0;
      s.full[sym] = r;
      // An output coefficient that combine_fractions keeps is the -O1 slot as it stands.
      if (auto u = slot_uses.find(sym); u != slot_uses.end() && combine_keeps(r)) {
        counted += u->second * tree_size(r.num);
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
  Namer namer(k.inputs);
  const ExSet materialized(s.materialized.begin(), s.materialized.end());  // (a list scan per value was quadratic)
  for (const auto& v : k.values)
    for (size_t i = 0; i < v.blades.size(); ++i)
      if (materialized.count(v.symbols[i]))
        temps.push_back({namer.fresh("v_" + sanitize(v.name) + "_" + algebra::blade_ident(v.blades[i])), v.symbols[i],
                         s.full.at(v.symbols[i]).value()});
  return temps;
}

// The output slots at -O1: each needed blade's substituted coefficient; identically-zero blades dropped
// unless a pragma asked for them.
struct SlotPlan {
  std::string output;
  algebra::BladeIndex blade;
  Rat value;       // over inputs
  ex value_sym;    // the value coefficient's symbol, or 0 for a blade the value lacks
};

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

// The script's own statements as temporaries (each value expanded over earlier values, only those the
// outputs need), and the outputs as the values' symbols. A coefficient that is one input or one number (a
// point's x, its e0 coefficient 1) is substituted into its users instead: as a temporary it would leave
// products like 1*z that nothing folds later.
struct StatementForm {
  std::vector<Temp> temps;
  std::vector<ex> roots;  // one per output slot, in plan order
};

StatementForm statement_form(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans) {
  StatementForm f;
  exmap atomic;
  Namer namer(k.inputs);
  for (const auto& v : k.values)
    for (size_t i = 0; i < v.blades.size(); ++i)
      if (s.needed.count(v.symbols[i])) {
        ex c = canonical(atomic.empty() ? v.coeffs[i] : v.coeffs[i].subs(atomic, kSymbolSubs)).value();
        if (is_atomic(c))
          atomic[v.symbols[i]] = c;
        else
          f.temps.push_back({namer.fresh("v_" + sanitize(v.name) + "_" + algebra::blade_ident(v.blades[i])),
                             v.symbols[i], c});
      }
  for (const auto& slots : plans)
    for (const auto& sp : slots) {
      auto it = atomic.find(sp.value_sym);
      f.roots.push_back(it == atomic.end() ? sp.value_sym : it->second);
    }
  return f;
}

// The size (tree_size) of the expanded (-O1) form: what the CSE passes and the printer would work through.
size_t expanded_size(const std::vector<Temp>& kept, const std::vector<std::vector<SlotPlan>>& plans) {
  size_t n = 0;
  for (const auto& slots : plans)
    for (const auto& sp : slots) n += tree_size(sp.value.num) + tree_size(sp.value.den);
  for (const auto& t : kept) n += tree_size(t.value);
  return n;
}

std::string over_budget_note(const char* level, size_t size, bool over_count) {
  return std::string(level) + " kept the script's statement form: the expanded form has " +
         (over_count ? "more than " + std::to_string(kMaxCountedNodes) : std::to_string(size)) +
         " symbol occurrences (budget " + std::to_string(kMaxExpandedNodes) + ")";
}

Program optimize_o1(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans) {
  Program p = skeleton(k, Level::O1);
  p.temps = materialized_temps(k, s);
  const size_t size = s.over_count ? 0 : expanded_size(p.temps, plans);
  if (s.over_count || size > kMaxExpandedNodes) {
    StatementForm f = statement_form(k, s, plans);
    p.temps = std::move(f.temps);
    p.notes.push_back(over_budget_note("-O1", size, s.over_count));
    size_t ri = 0;
    for (size_t oi = 0; oi < k.outputs.size(); ++oi) {
      ProgramOutput po{k.outputs[oi].name, {}};
      for (const auto& sp : plans[oi]) po.slots.push_back({sp.blade, f.roots.at(ri++)});
      p.outputs.push_back(std::move(po));
    }
    return p;
  }
  for (size_t oi = 0; oi < k.outputs.size(); ++oi) {
    ProgramOutput po{k.outputs[oi].name, {}};
    for (const auto& sp : plans[oi]) po.slots.push_back({sp.blade, sp.value.value()});
    p.outputs.push_back(std::move(po));
  }
  return p;
}

// ---------------------------------------------------------------------------------------------------------
// -O2: common subexpressions.

Program finish_o2(const Kernel& k, std::vector<Temp> in_temps, std::vector<ex> roots,
                  const std::vector<std::vector<SlotPlan>>& plans) {
  CseState cse(k.inputs, in_temps);
  run_cse(cse, roots);
  Program p = skeleton(k, Level::O2);
  p.temps = cse.temps;
  size_t ri = 0;
  for (size_t oi = 0; oi < k.outputs.size(); ++oi) {
    ProgramOutput po{k.outputs[oi].name, {}};
    for (const auto& sp : plans[oi]) po.slots.push_back({sp.blade, roots.at(ri++)});
    p.outputs.push_back(std::move(po));
  }
  // Number the temporaries in evaluation order.
  Namer namer(k.inputs);
  for (size_t i = 0; i < p.temps.size(); ++i) p.temps[i].name = namer.fresh("t" + std::to_string(i));
  return p;
}

long program_cost(const Program& p) { return program_stats(p).total.weighted(); }

// ---------------------------------------------------------------------------------------------------------
// `#pragma normalized X`: the caller promises X ~X = 1. Each blade of X ~X gives a polynomial identity in
// X's coefficients (scalar part = 1, every other blade = 0); -O2 may rewrite the output polynomials with
// them. A rule replaces a monomial by a polynomial without it: from the scalar part, a square v^2 (v
// appearing there only squared) by (1 - the rest) / its coefficient; from another blade, one of its
// bilinear terms u*w by minus the rest over its coefficient. Each choice of rules (one per identity) gives
// more candidate forms; the cheapest form wins as always, so the plain forms stay candidates.

struct Rule {
  std::vector<std::pair<ex, int>> lead;  // the monomial's symbols and exponents
  ex rhs;                                // what the monomial equals
};

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

Program optimize_o2(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans_in) {
  std::vector<Program> variants;
  const std::vector<std::vector<SlotPlan>>* current = &plans_in;
  auto roots_with = [&](auto&& f) {
    std::vector<ex> roots;
    for (const auto& slots : *current)
      for (const auto& sp : slots) roots.push_back(f(sp));
    return roots;
  };
  const auto& plans = plans_in;
  // 1. The expanded -O1 forms, and 2. the same collected in the inputs, unless the -O1 form is too large
  //    for the CSE passes to finish in time; on such scripts the statement form (3) has always been far
  //    cheaper anyway (paper A.1: 328 against 1516, circle3: 165 against 1402 weighted ops).
  const std::vector<Temp> kept = materialized_temps(k, s);
  const size_t size = s.over_count ? 0 : expanded_size(kept, plans);
  std::vector<std::string> notes;
  if (s.over_count || size > kMaxExpandedNodes) {
    notes.push_back(over_budget_note("-O2", size, s.over_count));
  } else {
    std::vector<std::vector<ex>> groups;
    std::vector<ex> scalars;
    for (const auto& in : k.inputs)
      if (!in.is_multivector) scalars.push_back(in.symbols.at(0));
    if (!scalars.empty()) groups.push_back(scalars);
    for (const auto& in : k.inputs)
      if (in.is_multivector) groups.emplace_back(in.symbols.begin(), in.symbols.end());
    auto add_forms = [&] {
      {
        PhaseTimer t("variant expanded");
        variants.push_back(
            finish_o2(k, kept, roots_with([](const SlotPlan& sp) { return sp.value.value(); }), plans));
      }
      for (const auto& g : groups) {
        std::vector<ex> roots;
        PhaseTimer t("variant collected");
        roots = roots_with([&](const SlotPlan& sp) {
          ex n = collect_in(sp.value.num, g);
          return sp.value.den.is_equal(1) ? n : n / collect_in(sp.value.den, g);
        });
        variants.push_back(finish_o2(k, kept, roots, plans));
      }
    };
    add_forms();
    // The same forms of the outputs rewritten with each choice of normalization rules.
    for (const auto& rules : rule_sets(k)) {
      std::vector<std::vector<SlotPlan>> reduced = plans;
      for (auto& slots : reduced)
        for (auto& sp : slots) sp.value = {reduce_with(sp.value.num, rules), reduce_with(sp.value.den, rules)};
      current = &reduced;
      add_forms();
      current = &plans_in;
    }
  }
  // 3. The script's own statements (each value expanded over earlier values), which keeps products like
  //    (M X) ~M factored.
  {
    StatementForm f = statement_form(k, s, plans);
    PhaseTimer t("variant statements");
    variants.push_back(finish_o2(k, f.temps, f.roots, plans));
  }
  PhaseTimer tc("costs");
  size_t best = 0;
  long best_cost = variants.size() > 1 ? program_cost(variants[0]) : 0;  // one form: nothing to compare
  for (size_t i = 1; i < variants.size(); ++i) {
    long c = program_cost(variants[i]);
    if (c < best_cost) best = i, best_cost = c;
  }
  variants[best].notes = notes;
  return variants[best];
}

}  // namespace

namespace {
Program optimize_level(const Kernel& kernel, Level level);
}  // namespace

Program optimize(const Kernel& kernel, Level level) {
  // A fault of GiNaC's inside the optimizer is a bug of cgagen's, but the user still gets a located error
  // (at the first output), never a library's message without a location.
  symbolic::NodeCacheScope caches;
  algebra::Using in(kernel.algebra);
  try {
    return optimize_level(kernel, level);
  } catch (const front::CompileError&) {
    throw;
  } catch (const std::exception& e) {
    const front::SourceLoc at = kernel.outputs.empty() ? front::SourceLoc{1, 1} : kernel.outputs.front().loc;
    throw front::CompileError(at, std::string("cgagen could not optimize this kernel at -O") +
                                      std::to_string(static_cast<int>(level)) + " (" + e.what() +
                                      "); -O0 still works; please report the script");
  }
}

namespace {

Program optimize_level(const Kernel& kernel, Level level) {
  check_normalized(kernel);
  if (level == Level::O0) return optimize_o0(kernel);
  PhaseTimer all("optimize");
  Substituted s = [&] { PhaseTimer t("substitute"); return substitute(kernel); }();
  auto plans = [&] { PhaseTimer t("plan slots"); return plan_slots(kernel, s); }();
  if (level == Level::O1) return optimize_o1(kernel, s, plans);
  return optimize_o2(kernel, s, plans);
}

}  // namespace

}  // namespace cgagen::opt
