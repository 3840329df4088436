// Expression forms the optimizer levels share: sizes and predicates, canonical coefficients, fractions
// over a common denominator (combine_fractions) and recursive collection in a set of symbols (collect_in).
#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <unordered_map>
#include <unordered_set>

#include "opt/internal.hpp"
#include "symbolic/dag.hpp"
#include "symbolic/multivector.hpp"

namespace cgagen::opt::detail {

using namespace GiNaC;

// The size of e for the work budget: its symbol occurrences. Unlike a node count this does not depend on
// GiNaC's process-dependent choices ((a-b)*x or -(b-a)*x), so budget decisions and notes are the same in
// every process.
size_t tree_size(const ex& e) { return symbolic::tree_symbol_count(e); }

size_t printed_size(const ex& e) {
  std::unordered_map<const basic*, size_t> memo;  // nodes of e, alive while e is
  auto power_of = [](const numeric& k, size_t base) {
    // x^k is printed as |k| factors (a negative k under a division); other exponents are one call of x.
    if (!k.is_integer()) return base;
    const long n = std::labs(k.to_long());
    return base * static_cast<size_t>(std::max(1L, n));
  };
  auto count = [&](auto&& self, const ex& x) -> size_t {
    if (symbolic::is_symbol(x)) return 1;
    if (x.nops() == 0) return 0;
    if (auto it = memo.find(symbolic::node_of(x)); it != memo.end()) return it->second;
    size_t n = 0;
    if (symbolic::is_mul(x)) {
      for (const auto& pair : symbolic::pairs_of(x)) n += power_of(ex_to<numeric>(pair.coeff), self(self, pair.rest));
    } else if (symbolic::is_add(x)) {
      for (const auto& pair : symbolic::pairs_of(x)) n += self(self, pair.rest);
    } else if (symbolic::is_power(x) && symbolic::is_numeric(x.op(1))) {
      n = power_of(ex_to<numeric>(x.op(1)), self(self, x.op(0)));
    } else {
      for (size_t i = 0; i < x.nops(); ++i) n += self(self, x.op(i));
    }
    memo.emplace(symbolic::node_of(x), n);
    return n;
  };
  return count(count, e);
}

bool is_atomic(const ex& e) { return symbolic::is_symbol_number_or_constant(e); }

bool has_denominator(const ex& e) { return symbolic::has_negative_power(e); }

void collect_symbols(const ex& e, ExSet& out) { symbolic::collect_symbols_into(e, out); }

Rat canonical(const ex& e) {
  ex x = expand(e);
  if (has_denominator(x) && symbolic::is_zero_rational(x)) return {0, 1};
  return {x, 1};
}

// e as (numerator, D) when e is a sum whose terms all have the same non-numeric denominator D (integer
// powers with negative exponents); nullopt otherwise.
std::optional<std::pair<ex, ex>> split_common_denominator(const ex& e) {
  if (!symbolic::is_add(e)) return std::nullopt;
  std::optional<ex> den;
  exvector nums;
  for (size_t i = 0; i < e.nops(); ++i) {
    const ex& t = e.op(i);
    exvector up, down;
    auto take = [&](const ex& f) {
      if (symbolic::is_power(f) && symbolic::is_numeric(f.op(1)) && ex_to<numeric>(f.op(1)).is_integer() &&
          ex_to<numeric>(f.op(1)).is_negative())
        down.push_back(pow(f.op(0), -f.op(1)));
      else
        up.push_back(f);
    };
    if (symbolic::is_mul(t))
      for (size_t j = 0; j < t.nops(); ++j) take(t.op(j));
    else
      take(t);
    ex d = dynallocate<mul>(down);
    if (symbolic::is_numeric(d)) return std::nullopt;
    if (!den) den = d;
    else if (!den->is_equal(d)) return std::nullopt;
    nums.push_back(dynallocate<mul>(up));
  }
  return std::make_pair(ex(dynallocate<add>(nums)), *den);
}

// Above this size (tree_size) of one argument of a call or root, combine_fractions keeps calls and roots
// opaque. The bundled scripts' arguments stay below 600 (circle3's radius); a fuzzer find had 10920.
constexpr size_t kMaxNormalNodes = 1000;

// Does e have a power with a negative integer exponent outside function calls and powers of non-integer
// exponent (what to_rational leaves of e)?
bool has_denominator_outside_calls(const ex& e) {
  std::unordered_set<const basic*> seen;
  auto is_integer = [](const ex& k) { return symbolic::is_numeric(k) && ex_to<numeric>(k).is_integer(); };
  auto walk = [&](auto&& self, const ex& x) -> bool {
    if (x.nops() == 0 || is_a<function>(x) || !seen.insert(symbolic::node_of(x)).second) return false;
    if (symbolic::is_add(x) || symbolic::is_mul(x)) {
      const bool product = symbolic::is_mul(x);
      for (const auto& p : symbolic::pairs_of(x)) {
        if (product && !is_integer(p.coeff)) continue;  // opaque
        if (product && ex_to<numeric>(p.coeff).is_negative()) return true;
        if (self(self, p.rest)) return true;
      }
      return false;
    }
    if (symbolic::is_power(x)) {
      if (!is_integer(x.op(1))) return false;  // opaque
      return ex_to<numeric>(x.op(1)).is_negative() || self(self, x.op(0));
    }
    for (size_t i = 0; i < x.nops(); ++i)
      if (self(self, x.op(i))) return true;
    return false;
  };
  return walk(walk, e);
}

// The tree_size of the largest argument of a function call or non-integer power in e.
size_t largest_call_argument(const ex& e) {
  size_t n = 0;
  std::unordered_set<const basic*> seen;
  auto is_integer = [](const ex& k) { return symbolic::is_numeric(k) && ex_to<numeric>(k).is_integer(); };
  // Over the stored nodes, each shared one once (a product's factor x^k is a pair (x, k) there).
  auto walk = [&](auto&& self, const ex& x) -> void {
    if (x.nops() == 0 || !seen.insert(symbolic::node_of(x)).second) return;
    if (symbolic::is_add(x) || symbolic::is_mul(x)) {
      const bool product = symbolic::is_mul(x);
      for (const auto& p : symbolic::pairs_of(x)) {
        if (product && !is_integer(p.coeff)) n = std::max(n, tree_size(p.rest));
        self(self, p.rest);
      }
      return;
    }
    if (is_a<function>(x))
      for (size_t i = 0; i < x.nops(); ++i) n = std::max(n, tree_size(x.op(i)));
    else if (symbolic::is_power(x) && !is_integer(x.op(1)))
      n = std::max(n, tree_size(x.op(0)));
    for (size_t i = 0; i < x.nops(); ++i) self(self, x.op(i));
  };
  walk(walk, e);
  return n;
}

bool combine_keeps(const Rat& r) {
  if (!has_denominator(r.num) || (symbolic::is_add(r.num) && r.num.nops() > 200)) return true;
  return largest_call_argument(r.num) > kMaxNormalNodes && !has_denominator_outside_calls(r.num);
}

Rat combine_fractions(const Rat& r) {
  if (!has_denominator(r.num) || (symbolic::is_add(r.num) && r.num.nops() > 200)) return r;
  // When every term has the same denominator D the terms over D stay as many (they are distinct monomials),
  // so only a common factor of the numerator and D can make the form shorter: one gcd instead of
  // numer_denom's gcd per term (seconds on circle3).
  if (auto split = split_common_denominator(r.num)) {
    // gcd takes polynomials over the rationals: function calls and roots become temporary symbols first.
    exmap repl;
    const ex n = split->first.to_polynomial(repl), d = split->second.to_polynomial(repl);
    if (symbolic::is_numeric(gcd(n, d))) return r;
  }
  // numer_denom also normalizes inside function arguments and roots, which simplifies small ones
  // (sqrt(t)^2 = t) but takes minutes on a large quotient under sqrt(abs(...)). When an argument has more
  // than kMaxNormalNodes nodes, calls and roots stay opaque (temporary symbols).
  exmap opaque;
  const bool large = largest_call_argument(r.num) > kMaxNormalNodes;
  // With calls and roots opaque, an expression without denominators outside them is an expanded polynomial
  // in symbols: numer_denom would give it back with denominator 1, longer by that 1 (r.num is expanded and
  // nonzero). Checked before to_rational, which substitutes its replacements into every opaque node.
  if (large && !has_denominator_outside_calls(r.num)) return r;
  ex nd = (large ? r.num.to_rational(opaque) : r.num).numer_denom();
  ex n = expand(nd.op(0)), d = expand(nd.op(1));
  if (large) n = expand(n.subs(opaque, kSymbolSubs)), d = expand(d.subs(opaque, kSymbolSubs));
  auto size = [](const ex& e) { return symbolic::is_add(e) ? e.nops() : size_t{1}; };
  if (n.is_zero()) return {0, 1};
  if (size(n) + size(d) >= size(r.num)) return r;
  if (symbolic::is_numeric(d)) return {expand(n / d), 1};
  return {n, d};
}

// An upper estimate of the number of terms of expand(e) when the symbols in `sizes` stand for sums of that
// many terms (used to keep -O1 from expanding products of large values).
namespace {
double estimate_terms_memo(const ex& e, const std::map<ex, double, ex_is_less>& sizes,
                           std::unordered_map<const basic*, std::pair<ex, double>>& memo) {
  if (symbolic::is_symbol(e)) {
    auto it = sizes.find(e);
    return it == sizes.end() ? 1 : it->second;
  }
  const bool sum = symbolic::is_add(e), product = symbolic::is_mul(e);
  const bool integer_power = symbolic::is_power(e) && symbolic::is_numeric(e.op(1)) && ex_to<numeric>(e.op(1)).is_pos_integer();
  if (!sum && !product && !integer_power) return 1;
  auto it = memo.find(symbolic::node_of(e));
  if (it != memo.end()) return it->second.second;
  double n;
  if (sum) {
    n = 0;
    for (size_t i = 0; i < e.nops(); ++i) n += estimate_terms_memo(e.op(i), sizes, memo);
  } else if (product) {
    n = 1;
    for (size_t i = 0; i < e.nops(); ++i) n *= estimate_terms_memo(e.op(i), sizes, memo);
  } else {
    n = std::pow(estimate_terms_memo(e.op(0), sizes, memo), ex_to<numeric>(e.op(1)).to_double());
  }
  memo.emplace(symbolic::node_of(e), std::make_pair(e, n));
  return n;
}
}  // namespace

double estimate_terms(const ex& e, const std::map<ex, double, ex_is_less>& sizes) {
  std::unordered_map<const basic*, std::pair<ex, double>> memo;
  return estimate_terms_memo(e, sizes, memo);
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
      const ex& base = symbolic::is_power(f) ? f.op(0) : f;
      auto it = index.find(base);
      if (it == index.end()) return false;
      if (!symbolic::is_power(f)) return s.degree[it->second] += 1, true;
      if (!symbolic::is_numeric(f.op(1)) || !ex_to<numeric>(f.op(1)).is_integer()) return false;
      s.degree[it->second] += ex_to<numeric>(f.op(1)).to_int();
      return true;
    };
    if (symbolic::is_mul(t)) {
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
  if (symbolic::is_add(e))
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


}  // namespace cgagen::opt::detail
