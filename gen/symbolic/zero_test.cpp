// Zero tests through a chain of definitions (zero_test.hpp): exact probes, double samples, two-precision
// evaluation, and the exact inlined test as the last resort.
#include "symbolic/zero_test.hpp"

#include "symbolic/dag.hpp"
#include "symbolic/multivector.hpp"
#include <algorithm>
#include <set>
#include <unordered_map>
#include <string>
#include <vector>

namespace cgagen::symbolic {

using GiNaC::ex;

namespace {

// Substitution options for maps whose keys are all symbols (the result is that of a plain subs()).
constexpr unsigned kSymbolSubs = GiNaC::subs_options::no_pattern | GiNaC::subs_options::pattern_is_not_product;

// Nodes of e as a tree (shared subexpressions counted at every use: what expand() and a preorder walk
// visit), counting stops past `cap`.
size_t tree_size(const ex& e, size_t cap) {
  size_t n = 1;
  for (size_t i = 0; i < e.nops() && n <= cap; ++i) n += tree_size(e.op(i), cap - n);
  return n;
}

// sqrt(X), abs(X) and X^k (k > 0) are zero exactly where X is: the zero test looks at X (sqrt(abs(P.P)) of
// a rotated point P, whose P.P cancels only once expanded).
ex zero_preserving_core(ex e) {
  for (;;) {
    if (GiNaC::is_a<GiNaC::power>(e) && GiNaC::is_a<GiNaC::numeric>(e.op(1)) &&
        GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_positive())
      e = e.op(0);
    else if (GiNaC::is_a<GiNaC::function>(e) && GiNaC::ex_to<GiNaC::function>(e).get_name() == "abs")
      e = e.op(0);
    else
      return e;
  }
}

// e with sin(u)^2 written as 1 - cos(u)^2 and expanded, so that the identity sin^2 + cos^2 = 1 (a rotor
// times its reverse, a rotated point squaring to 0) cancels in the expansion. Even powers of sin only:
// the result is a polynomial in cos(u) and sin(u) of degree <= 1 in sin(u), a normal form.
ex trig_reduced(const ex& e) {
  if (!e.has(GiNaC::sin(GiNaC::wild()))) return e;
  const ex w = GiNaC::wild();
  ex x = e.expand();
  x = x.subs(GiNaC::pow(GiNaC::sin(w), 2) == 1 - GiNaC::pow(GiNaC::cos(w), 2), GiNaC::subs_options::algebraic);
  return x.expand();
}

// Functions that are real-analytic wherever they are defined: a value built from them, from rational
// operations and from integer powers is identically zero when it vanishes on a set of positive measure, so
// sampling can prove it zero. abs, the selects of if/else, roots, log, asin, ... are not (abs(a*b) - a*b and
// sqrt(a^2) - a vanish on half of all points).
bool analytic_function(const std::string& name) {
  static const std::set<std::string> names = {"sin", "cos", "tan", "exp", "sinh", "cosh", "tanh", "atan"};
  return names.count(name) > 0;
}

// GiNaC's working precision for the evaluations of one scope (evalf rounds to it).
class PrecisionScope {
 public:
  explicit PrecisionScope(long digits) : saved_(GiNaC::Digits) { GiNaC::Digits = digits; }
  ~PrecisionScope() { GiNaC::Digits = saved_; }
  PrecisionScope(const PrecisionScope&) = delete;
  PrecisionScope& operator=(const PrecisionScope&) = delete;

 private:
  long saved_;
};

// The precision of step 4: rounding noise ~1e-120 of a value's magnitude stays below 1e-50 under square
// and fourth roots.
constexpr long kDigits = 120;

}  // namespace

ex ZeroTests::next_sample() {
  sample_state_ = sample_state_ * 6364136223846793005ull + 1442695040888963407ull;
  return GiNaC::numeric(0.3 + 1.4 * static_cast<double>(sample_state_ >> 11) / 9007199254740992.0);
}

double ZeroTests::next_signed_value() {
  signed_state_ = signed_state_ * 6364136223846793005ull + 1442695040888963407ull;
  const double m = 0.3 + 1.4 * static_cast<double>(signed_state_ >> 11) / 9007199254740992.0;
  return (signed_state_ >> 7) & 1 ? -m : m;
}

void ZeroTests::add_input(const GiNaC::symbol& sym) {
  samples_[sym] = next_sample();
  const double a = next_signed_value();
  signed_samples_[0][sym] = GiNaC::numeric(a);
  signed_samples_[1][sym] = GiNaC::numeric(-a);
  signed_samples_[2][sym] = GiNaC::numeric(next_signed_value());
  probes_.add_input(sym);
  for (size_t p = 0; p < kPrecisePoints; ++p) {
    // An exact rational of either sign with magnitude in [0.3, 1.7): the same number at both precisions.
    precise_state_ = precise_state_ * 6364136223846793005ull + 1442695040888963407ull;
    const long steps = static_cast<long>((precise_state_ >> 20) % 1400000);
    GiNaC::numeric v = GiNaC::numeric(300000 + steps, 1000000);
    if ((precise_state_ >> 9) & 1) v = -v;
    precise_[p][sym] = Precise{v, GiNaC::abs(v)};
  }
}

void ZeroTests::define(const GiNaC::symbol& sym, const ex& definition, const std::optional<ex>& sample) {
  if (sample) samples_[sym] = *sample;  // else computed when a later sample needs it
  probes_.define(sym, definition);
  definitions_[sym] = definition;
  if (!varies(definition)) constant_values_.insert(sym);
  if (analytic(definition)) analytic_values_.insert(sym);
}

// Does e depend on an input (directly or through a value)? A value of constants alone is a constant.
bool ZeroTests::varies(const ex& e) const {
  return visit_nodes_once(e, [&](const ex& x) { return GiNaC::is_a<GiNaC::symbol>(x) && !constant_values_.count(x); });
}

// Is e analytic (see analytic_function) in the inputs, through the values it uses? A non-analytic piece of
// constants alone (sqrt(2), abs(-3)) is a constant.
bool ZeroTests::analytic(const ex& e) const {
  const bool bad = visit_nodes_once(e, [&](const ex& x) {
    if (GiNaC::is_a<GiNaC::symbol>(x)) return definitions_.count(x) > 0 && !analytic_values_.count(x);
    if (GiNaC::is_a<GiNaC::power>(x)) {
      const ex& k = x.op(1);
      const bool integer = GiNaC::is_a<GiNaC::numeric>(k) && GiNaC::ex_to<GiNaC::numeric>(k).is_integer();
      return !integer && (varies(x.op(0)) || varies(k));
    }
    if (GiNaC::is_a<GiNaC::mul>(x)) {
      for (const auto& p : pairs_of(x))
        if (!GiNaC::ex_to<GiNaC::numeric>(p.coeff).is_integer() && varies(p.rest)) return true;
      return false;
    }
    if (GiNaC::is_a<GiNaC::function>(x))
      return !analytic_function(GiNaC::ex_to<GiNaC::function>(x).get_name()) && varies(x);
    return false;
  });
  return !bad;
}

// GiNaC's own evalf walks an expression as a tree, so on a DAG with shared subtrees it can take exponential
// time. The memoized evalf_at covers every node the expander builds; GiNaC's is the fallback for what it
// does not, and only where the tree is small: a tree of more than this many nodes counts as not evaluable.
static constexpr size_t kMaxFallbackNodes = 20000;

bool ZeroTests::probably_nonzero(const ex& c) { return probes_.test(c) == ProbePoints::Verdict::Nonzero; }

// c at signed point k (a number, possibly complex), or 0 where it cannot be evaluated there. The value
// symbols c uses get their samples first, at all points (a value symbol has them at all or none).
ex ZeroTests::signed_sample(const ex& c, size_t k) {
  define_dependencies_first(
      c, [&](const ex& sym) { return definitions_.count(sym) && !signed_samples_[0].count(sym); },
      [&](const ex& sym) -> const ex& { return definitions_.at(sym); },
      [&](const ex& sym) {
        const ex& def = definitions_.at(sym);
        for (size_t j = 0; j < signed_samples_.size(); ++j) signed_samples_[j][sym] = sample_at_signed_point(def, j);
      });
  return sample_at_signed_point(c, k);
}

ex ZeroTests::sample_at_signed_point(const ex& c, size_t k) {
  try {
    // The keys are symbols: no pattern matching, and GiNaC need not scan the map for products at each sum.
    auto fast = evalf_at(c, signed_samples_[k]);  // no expression built
    if (!fast && tree_larger_than(c, kMaxFallbackNodes)) return GiNaC::numeric(0);
    ex v = fast ? ex(*fast) : GiNaC::evalf(c.subs(signed_samples_[k], kSymbolSubs));
    if (GiNaC::is_a<GiNaC::numeric>(v)) return v;
  } catch (const std::exception&) {
    // a pole at this point
  }
  return GiNaC::numeric(0);
}

std::optional<ex> ZeroTests::sample(const ex& c) {
  // A value symbol's sample is computed at the first sample that uses it (the expander skips the sample of
  // coefficients the exact probes prove nonzero); it is the same whenever it is computed.
  define_dependencies_first(
      c, [&](const ex& sym) { return definitions_.count(sym) && !samples_.count(sym); },
      [&](const ex& sym) -> const ex& { return definitions_.at(sym); },
      [&](const ex& sym) { samples_[sym] = evaluate_at_sample(definitions_.at(sym)).value_or(GiNaC::numeric(0)); });
  const std::optional<ex> at = evaluate_at_sample(c);
  if (!at) return ex(GiNaC::numeric(0));
  const ex& v = *at;
  if (!GiNaC::is_a<GiNaC::numeric>(v)) return v;
  if (GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(v)) > GiNaC::numeric(1e-8)) return v;
  if (vanishes(c)) return std::nullopt;
  return v;
}

std::optional<ex> ZeroTests::evaluate_at_sample(const ex& c) {
  try {
    auto fast = evalf_at(c, samples_, &kept_sample_values_);  // no expression built
    if (!fast && tree_larger_than(c, kMaxFallbackNodes)) return std::nullopt;
    return fast ? ex(*fast) : GiNaC::evalf(c.subs(samples_, kSymbolSubs));
  } catch (const std::exception&) {
    return std::nullopt;
  }
}

bool ZeroTests::vanishes(const ex& c) {
  switch (probes_.test(c)) {
    case ProbePoints::Verdict::Zero: return true;
    case ProbePoints::Verdict::Nonzero: return false;
    case ProbePoints::Verdict::Unknown: break;
    // Past degree 2^40 no sample vouches for a zero, and the exact expansion is out of reach (though it can
    // pass the term-count check and then spend a minute on huge coefficients): the coefficient is kept.
    case ProbePoints::Verdict::ZeroPastDegree: return false;
  }
  // Far from 0 at a signed point: not identically zero (rounding at that size cannot reach 1e-6).
  for (size_t k = 0; k < signed_samples_.size(); ++k)
    if (GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(signed_sample(c, k))) > GiNaC::numeric(1, 1000000)) return false;
  const ex core = zero_preserving_core(c);
  switch (precise_verdict(core)) {
    case Verdict::Zero:
      if (analytic(core)) return true;
      break;  // sampled zeros of abs, selects, roots, ... prove nothing
    case Verdict::Nonzero: return false;
    case Verdict::Unknown: break;
  }
  return exactly_zero(c);
}

// c's value and magnitude at precise point `point`, or nullopt where it has none there (a pole, a function
// left unevaluated). The value symbols c uses get theirs first.
std::optional<ZeroTests::Precise> ZeroTests::precise_value(const ex& c, size_t point) {
  PreciseMap& at = precise_[point];
  PrecisionScope digits(kDigits);
  define_dependencies_first(
      c, [&](const ex& sym) { return definitions_.count(sym) && !at.count(sym); },
      [&](const ex& sym) -> const ex& { return definitions_.at(sym); },
      [&](const ex& sym) { at[sym] = evaluate_precise(definitions_.at(sym), at); });
  return evaluate_precise(c, at);
}

// e's value at the point whose symbols' values `at` holds, with its magnitude: what the value would be if
// no term cancelled (sums add the magnitudes of their terms). Rounding noise in the value is ~10^-kDigits
// of the magnitude; a value that is not identically zero is, at a random point, a sizeable fraction of it.
std::optional<ZeroTests::Precise> ZeroTests::evaluate_precise(const ex& e, const PreciseMap& at) {
  using GiNaC::numeric;
  std::unordered_map<const GiNaC::basic*, std::optional<Precise>> memo;  // nodes of e, alive while e is
  auto number = [](const ex& x) -> std::optional<numeric> {
    const ex f = GiNaC::evalf(x);
    if (!GiNaC::is_a<numeric>(f)) return std::nullopt;
    return GiNaC::ex_to<numeric>(f);
  };
  auto eval = [&](auto&& self, const ex& x) -> std::optional<Precise> {
    if (GiNaC::is_a<numeric>(x)) {
      auto v = number(x);
      if (!v) return std::nullopt;
      return Precise{*v, GiNaC::abs(*v)};
    }
    if (auto it = memo.find(node_of(x)); it != memo.end()) return it->second;
    std::optional<Precise> r;
    if (GiNaC::is_a<GiNaC::symbol>(x)) {
      if (auto it = at.find(x); it != at.end()) r = it->second;
    } else if (GiNaC::is_a<GiNaC::add>(x) || GiNaC::is_a<GiNaC::mul>(x)) {
      const bool product = GiNaC::is_a<GiNaC::mul>(x);
      Precise acc{numeric(product ? 1 : 0), numeric(product ? 1 : 0)};
      bool ok = true;
      for (const auto& p : pairs_of(x)) {
        auto t = self(self, p.rest);
        if (!t) { ok = false; break; }
        const numeric& k = GiNaC::ex_to<numeric>(p.coeff);
        if (product) {
          acc.value = acc.value * (k.is_equal(numeric(1)) ? t->value : t->value.power(k));
          // A divisor's magnitude is its value: dividing by a cancelled sum is dividing by that sum.
          acc.magnitude = acc.magnitude * (k.is_positive() ? t->magnitude.power(k) : GiNaC::abs(t->value).power(k));
        } else {
          acc.value = acc.value + t->value * k;
          acc.magnitude = acc.magnitude + t->magnitude * GiNaC::abs(k);
        }
      }
      if (ok && x.nops() > pairs_of(x).size()) {  // the numeric overall coefficient
        const numeric& oc = GiNaC::ex_to<numeric>(x.op(x.nops() - 1));
        if (product) acc = {acc.value * oc, acc.magnitude * GiNaC::abs(oc)};
        else acc = {acc.value + oc, acc.magnitude + GiNaC::abs(oc)};
      }
      if (ok) r = Precise{*number(acc.value), *number(acc.magnitude)};
    } else if (GiNaC::is_a<GiNaC::power>(x)) {
      auto b = self(self, x.op(0)), k = self(self, x.op(1));
      if (b && k) {
        auto v = number(GiNaC::pow(b->value, k->value));
        const bool numeric_exponent = GiNaC::is_a<numeric>(x.op(1));
        const numeric& kk = k->value;
        if (v) {
          if (numeric_exponent && kk.is_real() && kk.is_positive()) r = Precise{*v, *number(b->magnitude.power(kk))};
          else r = Precise{*v, GiNaC::abs(*v)};
        }
      }
    } else if (GiNaC::is_a<GiNaC::function>(x)) {
      GiNaC::exvector args;
      std::optional<Precise> first;
      bool ok = true;
      for (size_t i = 0; i < x.nops() && ok; ++i) {
        auto a = self(self, x.op(i));
        if (a) args.push_back(a->value);
        else ok = false;
        if (i == 0) first = a;
      }
      if (ok) {
        auto v = number(GiNaC::function(GiNaC::ex_to<GiNaC::function>(x).get_serial(), args));
        // abs keeps its argument's magnitude (|noise| is noise); other functions are taken at their value.
        if (v) r = Precise{*v, GiNaC::ex_to<GiNaC::function>(x).get_name() == "abs" && first ? first->magnitude : GiNaC::abs(*v)};
      }
    }
    memo.emplace(node_of(x), r);
    return r;
  };
  try {
    return eval(eval, e);
  } catch (const std::exception&) {
    return std::nullopt;  // a pole at this point
  }
}

// Step 4 of the header: the value relative to its magnitude at each precise point.
ZeroTests::Verdict ZeroTests::precise_verdict(const ex& c) {
  const GiNaC::numeric zero_below("1e-50"), nonzero_above("1e-30");
  bool all_zero = true;
  for (size_t p = 0; p < kPrecisePoints; ++p) {
    const auto at = precise_value(c, p);
    if (!at) return Verdict::Unknown;
    const GiNaC::numeric v = GiNaC::abs(at->value);
    if (v <= zero_below * at->magnitude) continue;
    all_zero = false;
    if (v >= nonzero_above * at->magnitude) return Verdict::Nonzero;
  }
  return all_zero ? Verdict::Zero : Verdict::Unknown;
}

// The exact test: the chain of values inlined and expanded. Past this many tree nodes it would take minutes
// and gigabytes, so the coefficient is kept: a coefficient kept that is in fact zero costs code, never a
// wrong value.
constexpr size_t kMaxInlinedNodes = 200000;

namespace {

// Whether expand(e) could have more than `cap` terms: a sum has at most the sum of its terms' counts, a
// product the product of its factors', a positive integer power the power of its base's; anything else is
// one term. Each node is counted once (inlined values share their subexpressions), saturating at cap + 1.
bool expansion_larger_than(const ex& e, size_t cap) {
  std::unordered_map<const GiNaC::basic*, size_t> memo;
  auto sat_mul = [cap](size_t a, size_t b) { return a != 0 && b > (cap + 1) / a ? cap + 1 : std::min(a * b, cap + 1); };
  auto terms = [&](auto&& self, const ex& x) -> size_t {
    if (x.nops() == 0 || GiNaC::is_a<GiNaC::function>(x)) return 1;
    if (auto it = memo.find(node_of(x)); it != memo.end()) return it->second;
    size_t n = 1;
    if (GiNaC::is_a<GiNaC::add>(x)) {
      n = 0;
      for (size_t i = 0; i < x.nops(); ++i) n = std::min(n + self(self, x.op(i)), cap + 1);
    } else if (GiNaC::is_a<GiNaC::mul>(x)) {
      for (size_t i = 0; i < x.nops(); ++i) n = sat_mul(n, self(self, x.op(i)));
    } else if (GiNaC::is_a<GiNaC::power>(x) && GiNaC::is_a<GiNaC::numeric>(x.op(1)) &&
               GiNaC::ex_to<GiNaC::numeric>(x.op(1)).is_pos_integer()) {
      const size_t base = self(self, x.op(0));
      const long k = GiNaC::ex_to<GiNaC::numeric>(x.op(1)).to_long();
      for (long i = 0; i < k && n <= cap; ++i) n = sat_mul(n, base);
    }
    memo.emplace(node_of(x), n);
    return n;
  };
  return terms(terms, e) > cap;
}

}  // namespace

bool ZeroTests::exactly_zero(const ex& c) {
  met_over_cap_ = false;
  const ex inlined = inline_values(c);
  if (met_over_cap_ || tree_size(inlined, kMaxInlinedNodes) > kMaxInlinedNodes) return false;
  return is_identically_zero(trig_reduced(zero_preserving_core(inlined)));
}

// e with every value symbol replaced by its definition, recursively, down to the inputs.
ex ZeroTests::inline_values(const ex& e) {
  GiNaC::exmap subs;
  collect_inlined(e, subs);
  return subs.empty() ? e : e.subs(subs, kSymbolSubs);
}

void ZeroTests::collect_inlined(const ex& e, GiNaC::exmap& subs) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    auto def = definitions_.find(e);
    if (def == definitions_.end() || subs.count(e)) return;
    if (over_cap_.count(e)) {
      met_over_cap_ = true;
      return;
    }
    auto done = inlined_.find(e);
    if (done == inlined_.end()) {
      // The size is checked before expanding: each squaring M = M*M doubles the expanded size, and expanding
      // the 128th would not finish. A definition past the cap makes every test that inlines it inexact.
      const bool outer = met_over_cap_;
      met_over_cap_ = false;
      const ex body = inline_values(def->second);
      const bool inner_over_cap = met_over_cap_;
      met_over_cap_ = outer;
      if (inner_over_cap || tree_larger_than(body, kMaxInlinedNodes) || expansion_larger_than(body, kMaxInlinedNodes)) {
        over_cap_.insert(e);
        met_over_cap_ = true;
        return;
      }
      done = inlined_.emplace(e, body.expand()).first;
    }
    subs[e] = done->second;
    return;
  }
  for (size_t i = 0; i < e.nops(); ++i) collect_inlined(e.op(i), subs);
}

}  // namespace cgagen::symbolic
