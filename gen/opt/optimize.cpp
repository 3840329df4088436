// The optimizer levels -O0, -O1, -O2: Kernel -> Program (see program.hpp and docs/generator.md).
#include <algorithm>
#include <cmath>
#include <cctype>
#include <chrono>
#include <cstdint>
#include <cstdlib>
#include <iostream>
#include <optional>
#include <functional>
#include <set>
#include <stdexcept>
#include <tuple>

#include "opt/program.hpp"
#include "symbolic/multivector.hpp"

namespace cgagen::opt {

using namespace GiNaC;
using ExSet = std::set<ex, ex_is_less>;
using ExMap = std::map<ex, ex, ex_is_less>;

Level parse_level(const std::string& text) {
  if (text == "-O0" || text == "O0" || text == "0") return Level::O0;
  if (text == "-O1" || text == "O1" || text == "1") return Level::O1;
  if (text == "-O2" || text == "O2" || text == "2") return Level::O2;
  throw std::invalid_argument("unknown optimization level '" + text + "' (expected -O0, -O1 or -O2)");
}

SymbolNames symbol_names(const Program& program) {
  SymbolNames names;
  for (const auto& in : program.inputs)
    for (const auto& s : in.symbols) names[s] = s.get_name();
  for (const auto& t : program.temps) names[t.sym] = t.name;
  return names;
}

namespace {

// CGAGEN_TIMING=1 prints how long each optimizer phase takes (to stderr), for finding hot spots.
class PhaseTimer {
 public:
  explicit PhaseTimer(std::string what) : what_(std::move(what)), start_(std::chrono::steady_clock::now()) {}
  ~PhaseTimer() {
    static const bool on = std::getenv("CGAGEN_TIMING") != nullptr;
    if (!on) return;
    auto ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start_).count();
    std::cerr << "cgagen timing: " << what_ << " " << ms << " ms\n";
  }
 private:
  std::string what_;
  std::chrono::steady_clock::time_point start_;
};

// The size of e for the work budget: its symbol occurrences. Unlike a node count this does not depend on
// GiNaC's process-dependent choices ((a-b)*x or -(b-a)*x), so budget decisions and notes are the same in
// every process.
size_t tree_size(const ex& e) {
  size_t n = 0;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it) n += is_a<symbol>(*it);
  return n;
}

bool is_atomic(const ex& e) { return is_a<symbol>(e) || is_a<numeric>(e) || is_a<constant>(e); }

bool has_denominator(const ex& e) {
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (is_a<power>(*it) && is_a<numeric>(it->op(1)) && ex_to<numeric>(it->op(1)).is_negative()) return true;
  return false;
}

void collect_symbols(const ex& e, ExSet& out) {
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (is_a<symbol>(*it)) out.insert(*it);
}

// A coefficient as numerator / denominator, both expanded polynomials (in symbols and function calls).
struct Rat {
  ex num, den = 1;
  ex value() const { return den.is_equal(1) ? num : num / den; }
};

Rat canonical(const ex& e) {
  ex x = expand(e);
  if (has_denominator(x) && symbolic::is_zero_rational(x)) return {0, 1};
  return {x, 1};
}

// e as (numerator, D) when e is a sum whose terms all have the same non-numeric denominator D (integer
// powers with negative exponents); nullopt otherwise.
std::optional<std::pair<ex, ex>> split_common_denominator(const ex& e) {
  if (!is_a<add>(e)) return std::nullopt;
  std::optional<ex> den;
  exvector nums;
  for (size_t i = 0; i < e.nops(); ++i) {
    const ex& t = e.op(i);
    exvector up, down;
    auto take = [&](const ex& f) {
      if (is_a<power>(f) && is_a<numeric>(f.op(1)) && ex_to<numeric>(f.op(1)).is_integer() &&
          ex_to<numeric>(f.op(1)).is_negative())
        down.push_back(pow(f.op(0), -f.op(1)));
      else
        up.push_back(f);
    };
    if (is_a<mul>(t))
      for (size_t j = 0; j < t.nops(); ++j) take(t.op(j));
    else
      take(t);
    ex d = dynallocate<mul>(down);
    if (is_a<numeric>(d)) return std::nullopt;
    if (!den) den = d;
    else if (!den->is_equal(d)) return std::nullopt;
    nums.push_back(dynallocate<mul>(up));
  }
  return std::make_pair(ex(dynallocate<add>(nums)), *den);
}

// Brings a small output coefficient with denominators over one common denominator when that makes it
// shorter (u.u - 1 with u = x/n folds to 0 or to a plain expression).
// Above this size (tree_size) of one argument of a call or root, combine_fractions keeps calls and roots
// opaque. The bundled scripts' arguments stay below 600 (circle3's radius); a fuzzer find had 10920.
constexpr size_t kMaxNormalNodes = 1000;

// The tree_size of the largest argument of a function call or non-integer power in e.
size_t largest_call_argument(const ex& e) {
  size_t n = 0;
  for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it) {
    if (is_a<function>(*it))
      for (size_t i = 0; i < it->nops(); ++i) n = std::max(n, tree_size(it->op(i)));
    else if (is_a<power>(*it) && !(is_a<numeric>(it->op(1)) && ex_to<numeric>(it->op(1)).is_integer()))
      n = std::max(n, tree_size(it->op(0)));
  }
  return n;
}

Rat combine_fractions(const Rat& r) {
  if (!has_denominator(r.num) || (is_a<add>(r.num) && r.num.nops() > 200)) return r;
  // When every term has the same denominator D the terms over D stay as many (they are distinct monomials),
  // so only a common factor of the numerator and D can make the form shorter: one gcd instead of
  // numer_denom's gcd per term (seconds on circle3).
  if (auto split = split_common_denominator(r.num)) {
    // gcd takes polynomials over the rationals: function calls and roots become temporary symbols first.
    exmap repl;
    const ex n = split->first.to_polynomial(repl), d = split->second.to_polynomial(repl);
    if (is_a<numeric>(gcd(n, d))) return r;
  }
  // numer_denom also normalizes inside function arguments and roots, which simplifies small ones
  // (sqrt(t)^2 = t) but takes minutes on a large quotient under sqrt(abs(...)). When an argument has more
  // than kMaxNormalNodes nodes, calls and roots stay opaque (temporary symbols).
  exmap opaque;
  const bool large = largest_call_argument(r.num) > kMaxNormalNodes;
  ex nd = (large ? r.num.to_rational(opaque) : r.num).numer_denom();
  ex n = expand(nd.op(0)), d = expand(nd.op(1));
  if (large) n = expand(n.subs(opaque, subs_options::no_pattern)), d = expand(d.subs(opaque, subs_options::no_pattern));
  auto size = [](const ex& e) { return is_a<add>(e) ? e.nops() : size_t{1}; };
  if (n.is_zero()) return {0, 1};
  if (size(n) + size(d) >= size(r.num)) return r;
  if (is_a<numeric>(d)) return {expand(n / d), 1};
  return {n, d};
}

// An upper estimate of the number of terms of expand(e) when the symbols in `sizes` stand for sums of that
// many terms (used to keep -O1 from expanding products of large values).
double estimate_terms(const ex& e, const std::map<ex, double, ex_is_less>& sizes) {
  if (is_a<symbol>(e)) {
    auto it = sizes.find(e);
    return it == sizes.end() ? 1 : it->second;
  }
  if (is_a<add>(e)) {
    double n = 0;
    for (size_t i = 0; i < e.nops(); ++i) n += estimate_terms(e.op(i), sizes);
    return n;
  }
  if (is_a<mul>(e)) {
    double n = 1;
    for (size_t i = 0; i < e.nops(); ++i) n *= estimate_terms(e.op(i), sizes);
    return n;
  }
  if (is_a<power>(e) && is_a<numeric>(e.op(1)) && ex_to<numeric>(e.op(1)).is_pos_integer())
    return std::pow(estimate_terms(e.op(0), sizes), ex_to<numeric>(e.op(1)).to_double());
  return 1;
}

// e (an expanded sum) collected recursively: a polynomial in xs[0] whose coefficients are polynomials in
// xs[1], and so on. Like GiNaC's collect(e, lst) but near-linear in the size of e (GiNaC's takes seconds on
// a few hundred terms) and defined for every e: only direct factors x^n (n an integer) count, symbols under
// roots, functions or denominator sums stay in the coefficients. Each term is split once (rebuilding a
// product re-evaluates its factors, costly when one is a large denominator).
ex collect_in(const ex& e, const std::vector<ex>& xs) {
  struct Split {
    std::vector<int> degree;  // per xs
    ex rest;
  };
  std::map<ex, size_t, ex_is_less> index;
  for (size_t i = 0; i < xs.size(); ++i) index.emplace(xs[i], i);
  auto split = [&](const ex& t) {
    Split s{std::vector<int>(xs.size(), 0), 1};
    auto power_of = [&](const ex& f) -> bool {
      const ex& base = is_a<power>(f) ? f.op(0) : f;
      auto it = index.find(base);
      if (it == index.end()) return false;
      if (!is_a<power>(f)) return s.degree[it->second] += 1, true;
      if (!is_a<numeric>(f.op(1)) || !ex_to<numeric>(f.op(1)).is_integer()) return false;
      s.degree[it->second] += ex_to<numeric>(f.op(1)).to_int();
      return true;
    };
    if (is_a<mul>(t)) {
      exvector rest;
      for (size_t j = 0; j < t.nops(); ++j)
        if (!power_of(t.op(j))) rest.push_back(t.op(j));
      s.rest = dynallocate<mul>(rest);
    } else if (!power_of(t)) {
      s.rest = t;
    }
    return s;
  };
  std::vector<Split> terms;
  if (is_a<add>(e))
    for (size_t i = 0; i < e.nops(); ++i) terms.push_back(split(e.op(i)));
  else
    terms.push_back(split(e));
  std::function<ex(const std::vector<const Split*>&, size_t)> build = [&](const std::vector<const Split*>& group,
                                                                          size_t k) -> ex {
    if (k == xs.size()) {
      exvector rests;
      for (const Split* s : group) rests.push_back(s->rest);
      return dynallocate<add>(rests);
    }
    std::map<int, std::vector<const Split*>> by_degree;
    for (const Split* s : group) by_degree[s->degree[k]].push_back(s);
    exvector out;
    for (const auto& [d, sub] : by_degree) out.push_back(pow(xs[k], d) * build(sub, k + 1));
    return dynallocate<add>(out);
  };
  std::vector<const Split*> all;
  for (const auto& t : terms) all.push_back(&t);
  return build(all, 0);
}

// Above this estimated size a value is not substituted into its users but kept as a temporary.
constexpr double kMaxInlineTerms = 4000;
// Above this size (tree_size) of the -O1 form, -O1 emits and -O2 optimizes only the script's statement form.
// The bundled runtime kernels stay below 1300; paper A.1 has 8807 and circle3 208494.
constexpr size_t kMaxExpandedNodes = 4000;

// Unique identifier generation, avoiding the inputs' names.
class Namer {
 public:
  explicit Namer(const std::vector<KernelInput>& inputs) {
    for (const auto& in : inputs) {
      taken_.insert(in.name);
      for (const auto& s : in.symbols) taken_.insert(s.get_name());
    }
  }
  std::string fresh(std::string base) {
    while (taken_.count(base)) base += "_";
    taken_.insert(base);
    return base;
  }
 private:
  std::set<std::string> taken_;
};

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
};

Substituted substitute(const Kernel& k) {
  Substituted s;
  for (const auto& o : k.outputs)
    for (const auto& sym : k.values.at(o.value).symbols) s.needed.insert(sym);
  for (auto v = k.values.rbegin(); v != k.values.rend(); ++v)
    for (size_t i = 0; i < v->blades.size(); ++i)
      if (s.needed.count(v->symbols[i])) collect_symbols(v->coeffs[i], s.needed);
  exmap subst;
  std::map<ex, double, ex_is_less> sizes;
  ExSet materialized;
  for (const auto& v : k.values)
    for (size_t i = 0; i < v.blades.size(); ++i) {
      const ex& sym = v.symbols[i];
      if (!s.needed.count(sym)) continue;
      Rat r;
      if (estimate_terms(v.coeffs[i], sizes) <= kMaxInlineTerms) {
        r = canonical(v.coeffs[i].subs(subst, subs_options::no_pattern));
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
          }
        r = canonical(v.coeffs[i].subs(subst, subs_options::no_pattern));
      }
      subst[sym] = r.value();
      sizes[sym] = is_a<add>(r.num) ? static_cast<double>(r.num.nops()) : 1.0;
      s.full[sym] = r;
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
  for (const auto& v : k.values)
    for (size_t i = 0; i < v.blades.size(); ++i)
      if (std::find_if(s.materialized.begin(), s.materialized.end(),
                       [&](const ex& m) { return m.is_equal(v.symbols[i]); }) != s.materialized.end())
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
      if (i >= 0) {
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
        ex c = canonical(atomic.empty() ? v.coeffs[i] : v.coeffs[i].subs(atomic, subs_options::no_pattern)).value();
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

std::string over_budget_note(const char* level, size_t size) {
  return std::string(level) + " kept the script's statement form: the expanded form has " + std::to_string(size) +
         " symbol occurrences (budget " + std::to_string(kMaxExpandedNodes) + ")";
}

Program optimize_o1(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans) {
  Program p = skeleton(k, Level::O1);
  p.temps = materialized_temps(k, s);
  const size_t size = expanded_size(p.temps, plans);
  if (size > kMaxExpandedNodes) {
    StatementForm f = statement_form(k, s, plans);
    p.temps = std::move(f.temps);
    p.notes.push_back(over_budget_note("-O1", size));
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

class Cse {
 public:
  Cse(const std::vector<KernelInput>& inputs, const std::vector<Temp>& temps) : namer_(inputs), keys_(names_) {
    for (const auto& in : inputs)
      for (const auto& s : in.symbols) names_[s] = s.get_name();
    for (const auto& t : temps) {
      names_[t.sym] = namer_.fresh(t.name);
      in_temps_.push_back(t);
    }
  }

  // Runs every pass; roots are the output slot expressions (in order).
  void run(std::vector<ex>& roots) {
    { PhaseTimer t("  cse orient"); orient_all(roots); }
    { PhaseTimer t("  cse pairs"); pair_products(roots); }
    topo_sort();
    { PhaseTimer t("  cse orient"); orient_all(roots); }
    { PhaseTimer t("  cse subtrees"); shared_subtrees(roots); }
    { PhaseTimer t("  cse orient"); orient_all(roots); }
    { PhaseTimer t("  cse negations"); fold_negations(roots); }
    { PhaseTimer t("  cse inline"); inline_single_use(roots); }
    { PhaseTimer t("  cse factors"); factor_all_sums(roots); }
    drop_aliases(roots);
    { PhaseTimer t("  cse orient"); orient_all(roots); }
    { PhaseTimer t("  cse negations"); fold_negations(roots); }
  }

  std::vector<Temp> temps() const { return in_temps_; }

 private:
  // Every expression with its sums oriented by the keys (lower.hpp), so that equal subexpressions are equal
  // trees whatever signs GiNaC's hash-dependent term order gave them.
  void orient_all(std::vector<ex>& roots) {
    for (auto& t : in_temps_) t.value = orient_sums(t.value, keys_);
    for (auto& r : roots) r = orient_sums(r, keys_);
  }

  // Orders the temporaries so that each comes after those it uses (stable otherwise).
  void topo_sort() {
    std::map<ex, size_t, ex_is_less> index;
    for (size_t i = 0; i < in_temps_.size(); ++i) index[in_temps_[i].sym] = i;
    std::vector<int> state(in_temps_.size(), 0);
    std::vector<Temp> out;
    std::function<void(size_t)> visit = [&](size_t i) {
      if (state[i] == 2) return;
      if (state[i] == 1) throw std::logic_error("cgagen optimizer: cyclic temporaries");
      state[i] = 1;
      ExSet syms;
      collect_symbols(in_temps_[i].value, syms);
      std::vector<size_t> deps;
      for (const auto& s : syms)
        if (auto it = index.find(s); it != index.end()) deps.push_back(it->second);
      std::sort(deps.begin(), deps.end());
      for (size_t d : deps) visit(d);
      state[i] = 2;
      out.push_back(in_temps_[i]);
    };
    for (size_t i = 0; i < in_temps_.size(); ++i) visit(i);
    in_temps_ = std::move(out);
  }

  Temp make_temp(const ex& value) {
    realsymbol s("t" + std::to_string(counter_++));
    std::string name = namer_.fresh(s.get_name());
    names_[s] = name;
    return Temp{name, s, value};
  }

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

  static ex core_of(const ex& m) {
    ex c = 1;
    for (size_t i = 0; i < m.nops(); ++i)
      if (!is_a<numeric>(m.op(i))) c *= m.op(i);
    return c;
  }

  void gather_muls(const ex& e, ExSet& visited, std::vector<ex>& order) {
    if (is_atomic(e) || !visited.insert(e).second) return;
    for (const ex& c : ordered_children(e, keys_)) gather_muls(c, visited, order);
    if (is_a<mul>(e)) {
      ex core = core_of(e);
      if (is_a<mul>(core) && !cores_.count(core)) {
        std::vector<ex> atoms;
        if (core_atoms(core, atoms)) {
          cores_[core] = atoms;
          order.push_back(core);
        }
      }
    }
  }

  // Greedy extraction of the factor pair shared by most products (repeatedly).
  void pair_products(std::vector<ex>& roots) {
    ExSet visited;
    std::vector<ex> order;
    for (const auto& t : in_temps_) gather_muls(t.value, visited, order);
    for (const auto& r : roots) gather_muls(r, visited, order);
    if (order.empty()) return;
    // Atoms are interned as ids; pair counts are kept up to date incrementally (only the cores holding a
    // chosen pair are recounted), and ties go to the pair first in canonical key order.
    std::vector<ex> atom_ex;
    std::vector<std::string> atom_key;
    std::map<ex, int, ex_is_less> atom_id;
    std::vector<std::set<size_t>> cores_with;  // atom id -> indices into `order` of the cores holding it
    auto intern = [&](const ex& a) {
      auto [it, fresh] = atom_id.emplace(a, static_cast<int>(atom_ex.size()));
      if (fresh) {
        atom_ex.push_back(a);
        atom_key.push_back(keys_.magnitude(a) + "|" + keys_.key(a));
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
    auto tally = [&](size_t c, int delta) {
      for (const Pair& pk : pairs_of(ids[c])) {
        int& n = count[pk];
        n += delta;
        if (n == 0) count.erase(pk);
      }
    };
    for (size_t c = 0; c < order.size(); ++c) {
      for (const auto& a : cores_[order[c]]) ids[c].push_back(intern(a));
      for (int id : ids[c]) cores_with[id].insert(c);
      tally(c, +1);
    }
    std::vector<Temp> pair_temps;
    std::vector<std::pair<ex, ex>> pair_atoms;
    for (int iter = 0; iter < 100000; ++iter) {
      const Pair* best = nullptr;
      int best_count = 1;
      for (const auto& [pk, n] : count) {
        if (n < 2 || n < best_count) continue;
        if (!best || n > best_count ||
            std::tie(atom_key[pk.first], atom_key[pk.second]) < std::tie(atom_key[best->first], atom_key[best->second]))
          best_count = n, best = &pk;
      }
      if (!best) break;
      const auto ia = best->first, ib = best->second;  // not a structured binding: clang 14 cannot capture one
      const ex a = atom_ex[ia], b = atom_ex[ib];
      Temp t = make_temp(a * b);
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
      auto& atoms = cores_[order[c]];
      atoms.clear();
      for (int id : ids[c]) atoms.push_back(atom_ex[id]);
    }
    if (pair_temps.empty()) return;
    ExMap memo;
    // A pair's own product may be one of the rewritten cores (then it would refer to itself): build it
    // from its two atoms.
    for (size_t i = 0; i < pair_temps.size(); ++i)
      pair_temps[i].value = rebuild_products(pair_atoms[i].first, memo) * rebuild_products(pair_atoms[i].second, memo);
    for (auto& t : in_temps_) t.value = rebuild_products(t.value, memo);
    for (auto& r : roots) r = rebuild_products(r, memo);
    // Pair temporaries only involve input atoms and earlier pairs; the atoms may reference input temps, so
    // they go after those.
    in_temps_.insert(in_temps_.end(), pair_temps.begin(), pair_temps.end());
  }

  ex rebuild_products(const ex& e, ExMap& memo) {
    if (is_atomic(e)) return e;
    auto it = memo.find(e);
    if (it != memo.end()) return it->second;
    ex r;
    if (is_a<mul>(e)) {
      ex core = core_of(e);
      auto c = cores_.find(core);
      numeric coeff = 1;
      for (size_t i = 0; i < e.nops(); ++i)
        if (is_a<numeric>(e.op(i))) coeff *= ex_to<numeric>(e.op(i));
      if (c != cores_.end()) {
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

  ex rebuild_children(const ex& e, ExMap& memo) {
    struct F : map_function {
      Cse* self;
      ExMap* memo;
      ex operator()(const ex& x) override { return self->rebuild_products(x, *memo); }
    } f;
    f.self = this;
    f.memo = &memo;
    return e.map(f);
  }

  // Hash-consed subtrees used at least twice become temporaries.
  static ex node_of(const ex& e) {
    if (is_a<mul>(e)) {
      for (size_t i = 0; i < e.nops(); ++i)
        if (is_a<numeric>(e.op(i))) return core_of(e);
    }
    return e;
  }

  void count_uses(const ex& e, std::map<ex, int, ex_is_less>& uses) {
    if (is_atomic(e)) return;
    ex n = node_of(e);
    if (is_atomic(n)) return;
    if (++uses[n] > 1) return;
    for (const ex& c : ordered_children(n, keys_)) {
      count_uses(c, uses);
      // An integer power prints its base several times.
      if (is_a<power>(n) && !is_atomic(c) && is_a<numeric>(n.op(1)) && ex_to<numeric>(n.op(1)).is_integer() &&
          abs(ex_to<numeric>(n.op(1))) >= 2 && c.is_equal(n.op(0)))
        count_uses(c, uses);
    }
  }

  ex share(const ex& e, const std::map<ex, int, ex_is_less>& uses, ExMap& memo, std::vector<Temp>& out) {
    if (is_atomic(e)) return e;
    auto it = memo.find(e);
    if (it != memo.end()) return it->second;
    ex n = node_of(e);
    ex r;
    if (!n.is_equal(e)) {
      r = (e / n) * share(n, uses, memo, out);  // e / n is the numeric coefficient
    } else {
      for (const ex& c : ordered_children(e, keys_)) share(c, uses, memo, out);
      struct F : map_function {
        Cse* self;
        const std::map<ex, int, ex_is_less>* uses;
        ExMap* memo;
        std::vector<Temp>* out;
        ex operator()(const ex& x) override { return self->share(x, *uses, *memo, *out); }
      } f;
      f.self = this, f.uses = &uses, f.memo = &memo, f.out = &out;
      r = e.map(f);
      auto u = uses.find(e);
      if (u != uses.end() && u->second >= 2 && count_ops(r, keys_).total() > 0) {
        Temp t = make_temp(r);
        out.push_back(t);
        r = t.sym;
      }
    }
    memo[e] = r;
    return r;
  }

  void shared_subtrees(std::vector<ex>& roots) {
    std::map<ex, int, ex_is_less> uses;
    for (const auto& t : in_temps_) count_uses(t.value, uses);
    for (const auto& r : roots) count_uses(r, uses);
    ExMap memo;
    std::vector<Temp> out;
    for (auto t : in_temps_) {
      t.value = share(t.value, uses, memo, out);
      out.push_back(t);
    }
    for (auto& r : roots) r = share(r, uses, memo, out);
    in_temps_ = std::move(out);
  }

  // A temporary whose value prints with a leading minus, or is a sum whose first term (by key) is negative,
  // is stored negated; its users absorb the sign.
  void fold_negations(std::vector<ex>& roots) {
    exmap flip;
    for (auto& t : in_temps_) {
      if (!flip.empty()) t.value = orient_sums(t.value.subs(flip, subs_options::no_pattern), keys_);
      if (keys_.sign(t.value) < 0) {
        t.value = -t.value;
        flip[t.sym] = -t.sym;
      }
    }
    if (!flip.empty())
      for (auto& r : roots) r = orient_sums(r.subs(flip, subs_options::no_pattern), keys_);
  }

  // Temporaries used once are put back into their user; unused ones are dropped.
  void inline_single_use(std::vector<ex>& roots) {
    // Occurrences of each temporary's symbol per expression (node k < T: temporary k, else root k - T),
    // kept up to date as values change, so a pass costs the size of the program, not temps x program.
    const size_t nt = in_temps_.size();
    std::map<ex, size_t, ex_is_less> temp_index;
    for (size_t i = 0; i < nt; ++i) temp_index[in_temps_[i].sym] = i;
    std::vector<std::map<size_t, int>> occ(nt);  // temp -> node -> occurrences
    auto account = [&](const ex& e, size_t node, int delta) {
      for (auto it = e.preorder_begin(); it != e.preorder_end(); ++it)
        if (is_a<symbol>(*it))
          if (auto ti = temp_index.find(*it); ti != temp_index.end())
            if ((occ[ti->second][node] += delta) == 0) occ[ti->second].erase(node);
    };
    auto value_of = [&](size_t node) -> ex& { return node < nt ? in_temps_[node].value : roots[node - nt]; };
    for (size_t i = 0; i < nt; ++i) account(in_temps_[i].value, i, +1);
    for (size_t r = 0; r < roots.size(); ++r) account(roots[r], nt + r, +1);
    std::vector<bool> alive(nt, true);
    for (size_t i = nt; i-- > 0;) {
      const Temp t = in_temps_[i];
      int uses = 0;
      for (const auto& [node, n] : occ[i]) uses += n;
      if (uses >= 2) continue;
      if (uses == 1) {
        const size_t user = occ[i].begin()->first;
        ex& target = value_of(user);
        ex v = target.subs(exmap{{t.sym, t.value}}, subs_options::no_pattern);
        // GiNaC may re-simplify on substitution; keep the temporary when that would cost more.
        if (user < nt && count_ops(v, keys_).weighted() >
                             count_ops(target, keys_).weighted() + count_ops(t.value, keys_).weighted())
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
      if (alive[i]) kept.push_back(in_temps_[i]);
    in_temps_ = std::move(kept);
  }

  // A temporary whose value is a lone symbol or number (a form can leave `t1 = t0`) is replaced by that value.
  void drop_aliases(std::vector<ex>& roots) {
    exmap alias;
    std::vector<Temp> kept;
    for (auto t : in_temps_) {
      if (!alias.empty()) t.value = t.value.subs(alias, subs_options::no_pattern);
      if (is_atomic(t.value))
        alias[t.sym] = t.value;
      else
        kept.push_back(t);
    }
    in_temps_ = std::move(kept);
    if (!alias.empty())
      for (auto& r : roots) r = orient_sums(r.subs(alias, subs_options::no_pattern), keys_);
  }

  // Every sum of the program factored (factor_sum), innermost first. Runs last, on the sums the sharing
  // passes left: a factored form hides products from them.
  void factor_all_sums(std::vector<ex>& roots) {
    ExMap memo;
    std::vector<Temp> out;
    for (auto t : in_temps_) {
      t.value = factor_sums(t.value, memo, out);
      out.push_back(t);
    }
    for (auto& r : roots) r = factor_sums(r, memo, out);
    in_temps_ = std::move(out);
  }

  // The numeric factor of a product term (1 when it has none).
  static numeric numeric_factor(const ex& term) {
    if (is_a<mul>(term))
      for (size_t i = 0; i < term.nops(); ++i)
        if (is_a<numeric>(term.op(i))) return ex_to<numeric>(term.op(i));
    return numeric(1);
  }

  ex factor_sums(const ex& e, ExMap& memo, std::vector<Temp>& out) {
    if (is_atomic(e)) return e;
    if (auto it = memo.find(e); it != memo.end()) return it->second;
    std::vector<ex> children = ordered_children(e, keys_);  // in key order: temporaries are made in that order
    ExMap done;
    for (const ex& c : children) done[c] = factor_sums(c, memo, out);
    struct F : map_function {
      const ExMap* done;
      ex operator()(const ex& x) override {
        auto it = done->find(x);
        return it == done->end() ? x : it->second;
      }
    } f;
    f.done = &done;
    ex r = e.map(f);
    if (is_a<add>(r)) r = factor_sum(r, out);
    memo[e] = r;
    return r;
  }

  // The symbols that are direct factors of a product term (not under a power).
  static std::vector<ex> direct_symbols(const ex& term) {
    std::vector<ex> out;
    if (is_a<mul>(term))
      for (size_t i = 0; i < term.nops(); ++i)
        if (is_a<symbol>(term.op(i))) out.push_back(term.op(i));
    return out;
  }

  // One sum: first a symbol that is a direct factor of several terms is taken out of them (greedy, the most
  // shared first: ab + ac + ad -> a (b + c + d), 2 mul fewer), the inner sums treated the same way; then the
  // terms sharing a numeric factor are grouped.
  ex factor_sum(const ex& sum, std::vector<Temp>& out) {
    const ex r = factor_symbols(sum, out);
    return is_a<add>(r) ? group_numeric_factors(r, out) : r;
  }

  // A sum with the symbols that several terms share taken out (see factor_sum).
  ex factor_symbols(const ex& sum, std::vector<Temp>& out) {
    std::vector<ex> terms = ordered_children(sum, keys_);
    ex factored = 0;
    for (;;) {
      std::map<ex, int, ex_is_less> uses;
      for (const ex& t : terms)
        for (const ex& a : direct_symbols(t)) ++uses[a];
      ex best;
      int best_uses = 1;
      for (const auto& [a, n] : uses)  // ties: the smaller key, so the choice does not depend on GiNaC's order
        if (n > best_uses || (n == best_uses && n > 1 && keys_.less(a, best))) best = a, best_uses = n;
      if (best_uses < 2) break;
      ex inner = 0;
      std::vector<ex> rest;
      for (const ex& t : terms) {
        const auto syms = direct_symbols(t);
        if (std::any_of(syms.begin(), syms.end(), [&](const ex& a) { return a.is_equal(best); }))
          inner += t / best;
        else
          rest.push_back(t);
      }
      if (is_a<add>(inner)) {
        // The inner sum factored the same way; a numeric factor all its terms share goes in front of the
        // product (c a (b + d) rather than a (c b + c d)), where GiNaC keeps it undistributed.
        inner = factor_symbols(orient_sums(inner, keys_), out);
        const numeric c = is_a<add>(inner) ? common_numeric_factor(inner) : numeric(1);
        factored += c * best * inner_sum(orient_sums(inner / c, keys_), out);
      } else {
        factored += best * inner;
      }
      terms = std::move(rest);
    }
    ex r = factored;
    for (const ex& t : terms) r += t;
    return orient_sums(r, keys_);
  }

  // An inner sum of factor_symbols as a temporary, one per distinct sum (by canonical key): the same
  // (a + b) c comes out of several outputs. Keyed by text, not by GiNaC's structural order, so that which
  // sums are shared cannot depend on hash order.
  ex inner_sum(const ex& sum, std::vector<Temp>& out) {
    if (!is_a<add>(sum)) return sum;
    ex oriented = sum;
    int sign = 1;
    if (keys_.sign(oriented) < 0) oriented = -oriented, sign = -1;
    const std::string& key = keys_.key(oriented);
    auto it = inner_sums_.find(key);
    if (it == inner_sums_.end()) {
      Temp t = make_temp(oriented);
      out.push_back(t);
      it = inner_sums_.emplace(key, t.sym).first;
    }
    return sign * it->second;
  }

  // |c| when every term of the sum has the numeric factor +-c, else 1.
  static numeric common_numeric_factor(const ex& sum) {
    numeric c = abs(numeric_factor(sum.op(0)));
    for (size_t i = 1; i < sum.nops(); ++i)
      if (!abs(numeric_factor(sum.op(i))).is_equal(c)) return 1;
    return c.is_zero() ? numeric(1) : c;
  }

  // Terms of the sum that carry the same numeric factor c (|c| != 1) become c times a temporary of their sum:
  // 2ab + 2cd - 2ef costs 6 mul, 2 t with t = ab + cd - ef 4. GiNaC distributes a number over a bare sum
  // (2 (a + b) is 2a + 2b to it), hence the temporary.
  ex group_numeric_factors(const ex& sum, std::vector<Temp>& out) {
    // Terms grouped by |numeric factor|, groups in the order of their first term by key.
    std::vector<std::pair<numeric, std::vector<ex>>> groups;
    ex rest = 0;
    for (const ex& term : ordered_children(sum, keys_)) {
      const numeric c = abs(numeric_factor(term));
      if (c.is_equal(numeric(1)) || c.is_zero()) {
        rest += term;
        continue;
      }
      auto g = std::find_if(groups.begin(), groups.end(), [&](const auto& x) { return x.first.is_equal(c); });
      if (g == groups.end())
        groups.push_back({c, {term}});
      else
        g->second.push_back(term);
    }
    bool changed = false;
    for (const auto& [c, terms] : groups) {
      if (terms.size() < 2) {
        rest += terms.front();
        continue;
      }
      ex inner = 0;
      for (const ex& term : terms) inner += term / c;
      inner = orient_sums(inner, keys_);
      ex factor = c;
      if (keys_.sign(inner) < 0) inner = -inner, factor = -c;
      Temp t = make_temp(inner);
      out.push_back(t);
      rest += factor * t.sym;
      changed = true;
    }
    return changed ? orient_sums(rest, keys_) : sum;
  }

  std::map<std::string, ex> inner_sums_;  // inner_sum's temporaries by key
  Namer namer_;
  SymbolNames names_;
  CanonicalKeys keys_;
  std::vector<Temp> in_temps_;
  std::map<ex, std::vector<ex>, ex_is_less> cores_;
  int counter_ = 0;
};

Program finish_o2(const Kernel& k, std::vector<Temp> in_temps, std::vector<ex> roots,
                  const std::vector<std::vector<SlotPlan>>& plans) {
  Cse cse(k.inputs, in_temps);
  cse.run(roots);
  Program p = skeleton(k, Level::O2);
  p.temps = cse.temps();
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

Program optimize_o2(const Kernel& k, const Substituted& s, const std::vector<std::vector<SlotPlan>>& plans) {
  std::vector<Program> variants;
  auto roots_with = [&](auto&& f) {
    std::vector<ex> roots;
    for (const auto& slots : plans)
      for (const auto& sp : slots) roots.push_back(f(sp));
    return roots;
  };
  // 1. The expanded -O1 forms, and 2. the same collected in the inputs, unless the -O1 form is too large
  //    for the CSE passes to finish in time; on such scripts the statement form (3) has always been far
  //    cheaper anyway (paper A.1: 328 against 1516, circle3: 165 against 1402 weighted ops).
  const std::vector<Temp> kept = materialized_temps(k, s);
  const size_t size = expanded_size(kept, plans);
  std::vector<std::string> notes;
  if (size > kMaxExpandedNodes) {
    notes.push_back(over_budget_note("-O2", size));
  } else {
    {
      PhaseTimer t("variant expanded");
      variants.push_back(
          finish_o2(k, kept, roots_with([](const SlotPlan& sp) { return sp.value.value(); }), plans));
    }
    std::vector<std::vector<ex>> groups;
    std::vector<ex> scalars;
    for (const auto& in : k.inputs)
      if (!in.is_multivector) scalars.push_back(in.symbols.at(0));
    if (!scalars.empty()) groups.push_back(scalars);
    for (const auto& in : k.inputs)
      if (in.is_multivector) groups.emplace_back(in.symbols.begin(), in.symbols.end());
    for (const auto& g : groups) {
      std::vector<ex> roots;
      PhaseTimer t("variant collected");
      roots = roots_with([&](const SlotPlan& sp) {
        ex n = collect_in(sp.value.num, g);
        return sp.value.den.is_equal(1) ? n : n / collect_in(sp.value.den, g);
      });
      variants.push_back(finish_o2(k, kept, roots, plans));
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
  long best_cost = program_cost(variants[0]);
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
  if (level == Level::O0) return optimize_o0(kernel);
  PhaseTimer all("optimize");
  Substituted s = [&] { PhaseTimer t("substitute"); return substitute(kernel); }();
  auto plans = [&] { PhaseTimer t("plan slots"); return plan_slots(kernel, s); }();
  if (level == Level::O1) return optimize_o1(kernel, s, plans);
  return optimize_o2(kernel, s, plans);
}

}  // namespace

ProgramStats program_stats(const Program& p) {
  SymbolNames names = symbol_names(p);
  CanonicalKeys keys(names);
  ProgramStats st;
  st.temp_count = p.temps.size();
  std::map<ex, size_t, ex_is_less> index;
  std::vector<OpCounts> temp_ops;
  std::vector<ExSet> deps;  // each temp's transitive temp dependencies
  for (size_t i = 0; i < p.temps.size(); ++i) {
    index[p.temps[i].sym] = i;
    temp_ops.push_back(count_ops(p.temps[i].value, keys));
    st.temps += temp_ops.back();
  }
  auto temp_deps = [&](const ex& e) {
    std::set<size_t> out, todo;
    ExSet syms;
    collect_symbols(e, syms);
    for (const auto& s : syms)
      if (index.count(s)) todo.insert(index[s]);
    while (!todo.empty()) {
      size_t i = *todo.begin();
      todo.erase(todo.begin());
      if (!out.insert(i).second) continue;
      ExSet s2;
      collect_symbols(p.temps[i].value, s2);
      for (const auto& s : s2)
        if (index.count(s) && !out.count(index[s])) todo.insert(index[s]);
    }
    return out;
  };
  st.total = st.temps;
  for (const auto& o : p.outputs) {
    OpCounts own;
    std::set<size_t> used;
    for (const auto& slot : o.slots) {
      own += count_ops(slot.value, keys);
      auto d = temp_deps(slot.value);
      used.insert(d.begin(), d.end());
    }
    st.total += own;
    for (size_t i : used) own += temp_ops[i];
    st.outputs.push_back({o.name, own});
  }
  return st;
}

}  // namespace cgagen::opt
