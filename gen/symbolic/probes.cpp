// Exact evaluation at fixed points modulo a prime, for zero tests (see probes.hpp).
#include "symbolic/probes.hpp"

#include <algorithm>
#include <exception>
#include <optional>
#include <unordered_map>

#include "symbolic/dag.hpp"

namespace cgagen::symbolic {
namespace {

constexpr std::uint64_t kPrime = (std::uint64_t{1} << 61) - 1;

std::uint64_t mul_mod(std::uint64_t a, std::uint64_t b) {
  return static_cast<std::uint64_t>(static_cast<unsigned __int128>(a) * b % kPrime);
}

std::uint64_t reduce(const GiNaC::numeric& integer) {  // integer mod p, in [0, p)
  // Most coefficients are small integers: reduced in machine words, without cln's allocating mod.
  if (integer.int_length() < 62) {
    const long v = integer.to_long();  // |v| < 2^62
    const std::uint64_t m = static_cast<std::uint64_t>(v < 0 ? -v : v) % kPrime;
    return v < 0 && m != 0 ? kPrime - m : m;
  }
  GiNaC::numeric m = GiNaC::mod(integer, GiNaC::numeric(static_cast<long>(kPrime)));
  return static_cast<std::uint64_t>(m.to_long());
}

std::uint64_t add_mod(std::uint64_t a, std::uint64_t b) {
  const std::uint64_t r = a + b;  // a, b < p < 2^61: no overflow
  return r >= kPrime ? r - kPrime : r;
}

std::uint64_t pow_mod(std::uint64_t a, std::uint64_t e) {
  std::uint64_t r = 1;
  for (; e; e >>= 1, a = mul_mod(a, a))
    if (e & 1) r = mul_mod(r, a);
  return r;
}

std::uint64_t inverse_mod(std::uint64_t a) { return pow_mod(a, kPrime - 2); }  // a != 0 (Fermat)

// The next value of a fixed-seed generator, in [1, p): a probe point's coordinate.
std::uint64_t draw(std::uint64_t& state) {
  state = state * 6364136223846793005ull + 1442695040888963407ull;
  return 1 + (state >> 3) % (kPrime - 1);
}

// A rational number modulo p; nullopt when its denominator is a multiple of p.
std::optional<std::uint64_t> number_mod(const GiNaC::numeric& n) {
  if (n.is_integer()) return reduce(n);
  if (!n.is_rational()) return std::nullopt;
  const std::uint64_t den = reduce(n.denom());
  if (den == 0) return std::nullopt;
  return mul_mod(reduce(n.numer()), inverse_mod(den));
}

// Nodes the probes take as independent inputs: function applications, constants (Pi), powers but integer ones.
bool opaque_node(const GiNaC::ex& x) {
  const symbolic::Kind k = symbolic::kind_of(x);
  if (k == symbolic::Kind::Function || k == symbolic::Kind::Constant) return true;
  return k == symbolic::Kind::Power &&
         !(symbolic::is_numeric(x.op(1)) && GiNaC::ex_to<GiNaC::numeric>(x.op(1)).is_integer());
}

// e at one point, modulo p, computed directly on GiNaC's stored nodes (each shared node once); nullopt when
// e is not a rational function of known symbols or has a pole there. Exact: the same value as
// substituting the point's rationals and reducing, except where an intermediate denominator is a multiple
// of p (probability ~2^-61 per operation).
// A symbol without a value in `at` for which unknown(symbol) holds sets *unknown_met (the caller then gives
// it one and asks again); other symbols without a value make e's value nullopt.
// An opaque node (a function application, a constant, a non-integer power) gets opaque(node): a value drawn
// for it as if it were one more input, the same for structurally equal nodes; meeting one, or a symbol in
// `opaque_symbols`, sets *opaque_met.
template <class Values, class Unknown, class Opaque, class OpaqueSymbols>
std::optional<std::uint64_t> value_at(const GiNaC::ex& e, const Values& at, Unknown&& unknown, bool* unknown_met,
                                      Opaque&& opaque, const OpaqueSymbols& opaque_symbols, bool* opaque_met) {
  std::unordered_map<const GiNaC::basic*, std::optional<std::uint64_t>> memo;
  auto eval = [&](auto&& self, const GiNaC::ex& x) -> std::optional<std::uint64_t> {
    if (symbolic::is_numeric(x)) return number_mod(GiNaC::ex_to<GiNaC::numeric>(x));
    if (auto it = memo.find(symbolic::node_of(x)); it != memo.end()) return it->second;  // symbols too
    std::optional<std::uint64_t> v;
    if (symbolic::is_symbol(x)) {
      if (auto it = at.find(x); it != at.end()) {
        v = it->second;  // none where it did not evaluate
        if (opaque_symbols.count(x)) *opaque_met = true;
      } else if (unknown(x)) {
        *unknown_met = true;
      }
    } else if (opaque_node(x)) {
      v = opaque(x);
      *opaque_met = true;
    } else if (symbolic::is_add(x) || symbolic::is_mul(x)) {
      const bool product = symbolic::is_mul(x);
      const auto& pairs = symbolic::pairs_of(x);
      std::uint64_t acc = product ? 1 : 0;
      bool ok = true;
      for (const auto& p : pairs) {
        const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(p.coeff);
        if (product && !c.is_integer()) {  // rest^c, a root: opaque
          acc = mul_mod(acc, opaque(GiNaC::pow(p.rest, c)));
          *opaque_met = true;
          continue;
        }
        auto r = self(self, p.rest);
        if (!r) { ok = false; break; }
        if (product) {
          std::uint64_t base = *r;
          if (c.is_negative()) {
            if (base == 0) { ok = false; break; }  // a pole
            base = inverse_mod(base);
          }
          acc = mul_mod(acc, pow_mod(base, static_cast<std::uint64_t>(GiNaC::abs(c).to_long())));
        } else {
          auto cm = number_mod(c);
          if (!cm) { ok = false; break; }
          acc = add_mod(acc, mul_mod(*cm, *r));
        }
      }
      if (ok && x.nops() > pairs.size()) {  // the numeric overall coefficient
        auto oc = number_mod(GiNaC::ex_to<GiNaC::numeric>(x.op(x.nops() - 1)));
        if (!oc) ok = false;
        else acc = product ? mul_mod(acc, *oc) : add_mod(acc, *oc);
      }
      if (ok) v = acc;
    } else if (symbolic::is_power(x) && symbolic::is_numeric(x.op(1)) &&
               GiNaC::ex_to<GiNaC::numeric>(x.op(1)).is_integer()) {
      auto r = self(self, x.op(0));
      const GiNaC::numeric& k = GiNaC::ex_to<GiNaC::numeric>(x.op(1));
      if (r && !(k.is_negative() && *r == 0))
        v = pow_mod(k.is_negative() ? inverse_mod(*r) : *r, static_cast<std::uint64_t>(GiNaC::abs(k).to_long()));
    }
    memo.emplace(symbolic::node_of(x), v);
    return v;
  };
  return eval(eval, e);
}

// Degree arithmetic saturates at kHuge (far above any kMaxDegree): a bound past it means "unbounded".
constexpr std::uint64_t kHuge = std::uint64_t{1} << 62;
std::uint64_t add_sat(std::uint64_t a, std::uint64_t b) { return a + b >= kHuge ? kHuge : a + b; }
std::uint64_t mul_sat(std::uint64_t a, std::uint64_t b) {
  return a != 0 && b >= kHuge / a ? kHuge : a * b;
}

// An integer exponent that fits a machine word (larger ones: the degree is unbounded).
bool word_sized(const GiNaC::numeric& k) { return GiNaC::abs(k).int_length() <= 62; }

using Factor = RationalDegree::Factor;
constexpr std::size_t kMaxFactors = 32;  // past it, a denominator is merged into one factor of its own

std::uint64_t denominator_degree(const RationalDegree& d) {
  std::uint64_t r = 0;
  for (const Factor& f : d.denominator) r = add_sat(r, mul_sat(f.degree, f.power));
  return r;
}

// Adds power·b's factors to a's (a product), or takes each factor's larger power (a common denominator).
void merge_factors(std::vector<Factor>& a, const std::vector<Factor>& b, std::uint64_t power, bool lcm) {
  std::vector<Factor> out;
  out.reserve(a.size() + b.size());
  std::size_t i = 0, j = 0;
  while (i < a.size() || j < b.size()) {
    if (j == b.size() || (i < a.size() && a[i].id < b[j].id)) {
      out.push_back(a[i++]);
    } else if (i == a.size() || b[j].id < a[i].id) {
      out.push_back({b[j].id, b[j].degree, mul_sat(b[j].power, power)});
      ++j;
    } else {
      const std::uint64_t pb = mul_sat(b[j].power, power);
      out.push_back({a[i].id, a[i].degree, lcm ? std::max(a[i].power, pb) : add_sat(a[i].power, pb)});
      ++i, ++j;
    }
  }
  a = std::move(out);
}

// Many distinct factors become one factor named by `node` with the low bit set (so it is never taken for
// the inverse of that node): sound, since a product of factors is a factor, and it bounds the work per sum.
void bound_factors(RationalDegree& d, const GiNaC::basic* node) {
  if (d.denominator.size() <= kMaxFactors) return;
  d.denominator = {Factor{reinterpret_cast<std::uintptr_t>(node) | 1u, denominator_degree(d), 1}};
}

// Degree bounds of e as value_at evaluates it (the same nodes, the same operations); symbols' bounds come
// from `symbol_degree`. Each shared node once.
template <class SymbolDegree>
RationalDegree degree_of(const GiNaC::ex& e, SymbolDegree&& symbol_degree) {
  std::unordered_map<const GiNaC::basic*, RationalDegree> memo;
  const RationalDegree unbounded{kHuge, {}};
  auto power_into = [](RationalDegree& acc, const RationalDegree& r, const GiNaC::basic* base, long k) {
    const std::uint64_t n = static_cast<std::uint64_t>(k < 0 ? -k : k);
    if (k >= 0) {  // (N/D)^k
      acc.numerator = add_sat(acc.numerator, mul_sat(n, r.numerator));
      merge_factors(acc.denominator, r.denominator, n, false);
    } else {  // (D/N)^k: N becomes a factor named by its node
      acc.numerator = add_sat(acc.numerator, mul_sat(n, denominator_degree(r)));
      merge_factors(acc.denominator, {Factor{reinterpret_cast<std::uintptr_t>(base), r.numerator, 1}}, n, false);
    }
  };
  auto walk = [&](auto&& self, const GiNaC::ex& x) -> RationalDegree {
    if (symbolic::is_numeric(x)) return {};
    if (auto it = memo.find(symbolic::node_of(x)); it != memo.end()) return it->second;
    RationalDegree d = unbounded;
    if (symbolic::is_symbol(x)) {
      d = symbol_degree(x);
    } else if (opaque_node(x)) {
      d = {1, {}};  // an input
    } else if (symbolic::is_mul(x)) {
      d = {};
      for (const auto& p : symbolic::pairs_of(x)) {
        const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(p.coeff);
        if (!c.is_integer()) {  // an opaque root: an input
          d.numerator = add_sat(d.numerator, 1);
          continue;
        }
        if (!word_sized(c)) { d = unbounded; break; }
        power_into(d, self(self, p.rest), symbolic::node_of(p.rest), c.to_long());
      }
    } else if (symbolic::is_add(x)) {
      std::vector<RationalDegree> terms;
      d = {};
      for (const auto& p : symbolic::pairs_of(x)) {
        terms.push_back(self(self, p.rest));
        merge_factors(d.denominator, terms.back().denominator, 1, true);
      }
      const std::uint64_t common = denominator_degree(d);
      d.numerator = common;  // a numeric overall coefficient: common · c
      for (const RationalDegree& t : terms)
        d.numerator = std::max(d.numerator, add_sat(t.numerator, common - std::min(common, denominator_degree(t))));
    } else if (symbolic::is_power(x) && !opaque_node(x) && word_sized(GiNaC::ex_to<GiNaC::numeric>(x.op(1)))) {
      d = {};
      power_into(d, self(self, x.op(0)), symbolic::node_of(x.op(0)), GiNaC::ex_to<GiNaC::numeric>(x.op(1)).to_long());
    }
    bound_factors(d, symbolic::node_of(x));
    memo.emplace(symbolic::node_of(x), d);
    return d;
  };
  return walk(walk, e);
}

}  // namespace

void ProbePoints::add_input(const GiNaC::symbol& s) {
  for (auto& at : at_) at[s] = draw(state_);
  degrees_[s] = RationalDegree{1, {}};
}

void ProbePoints::define(const GiNaC::symbol& s, const GiNaC::ex& definition) { definitions_.emplace(s, definition); }

// e at point k. The defined symbols e depends on get their values there first, when e meets one without.
// Sets *opaque_met when the value takes an opaque node as an input (probes.hpp).
std::optional<std::uint64_t> ProbePoints::value_at_point(const GiNaC::ex& e, int k, bool* opaque_met) {
  Values& at = at_[static_cast<std::size_t>(k)];
  auto& drawn = opaque_values_[static_cast<std::size_t>(k)];
  auto opaque = [&](const GiNaC::ex& node) {
    auto [it, added] = drawn.try_emplace(node, 0);
    if (added) it->second = draw(opaque_state_);
    return it->second;
  };
  auto pending = [&](const GiNaC::ex& s) { return !at.count(s) && definitions_.count(s); };
  bool met_pending = false;
  std::optional<std::uint64_t> v = value_at(e, at, pending, &met_pending, opaque, opaque_symbols_, opaque_met);
  if (!met_pending) return v;
  symbolic::define_dependencies_first(
      e, pending, [&](const GiNaC::ex& s) -> const GiNaC::ex& { return definitions_.at(s); },
      [&](const GiNaC::ex& s) {
        bool unused = false, through_opaque = false;
        at[s] = value_at(definitions_.at(s), at, pending, &unused, opaque, opaque_symbols_, &through_opaque);
        if (through_opaque) opaque_symbols_.emplace(s, true);
      });
  bool unused = false;
  return value_at(e, at, pending, &unused, opaque, opaque_symbols_, opaque_met);
}

// Bounds of e's numerator degree. The defined symbols e depends on get theirs first (iteratively: chains of
// definitions can be thousands deep).
std::uint64_t ProbePoints::numerator_degree(const GiNaC::ex& e) {
  auto pending = [&](const GiNaC::ex& s) { return !degrees_.count(s) && definitions_.count(s); };
  auto symbol_degree = [&](const GiNaC::ex& s) {
    auto it = degrees_.find(s);
    return it != degrees_.end() ? it->second : RationalDegree{kHuge, {}};
  };
  symbolic::define_dependencies_first(
      e, pending, [&](const GiNaC::ex& s) -> const GiNaC::ex& { return definitions_.at(s); },
      [&](const GiNaC::ex& s) { degrees_[s] = degree_of(definitions_.at(s), symbol_degree); });
  return degree_of(e, symbol_degree).numerator;
}

ProbePoints::Verdict ProbePoints::test(const GiNaC::ex& e) {
  int zeros = 0;
  bool opaque = false;
  for (int k = 0; k < kPoints; ++k) {
    auto v = value_at_point(e, k, &opaque);
    if (!v) continue;
    // Opaque inputs may be related (sin^2 + cos^2 = 1): a nonzero there proves nothing.
    if (*v != 0) return opaque ? Verdict::Unknown : Verdict::Nonzero;
    ++zeros;
  }
  // Only a zero verdict needs the degree: a nonzero value proves itself.
  if (zeros < kPoints) return Verdict::Unknown;
  return numerator_degree(e) <= kMaxDegree ? Verdict::Zero : Verdict::ZeroPastDegree;
}

}  // namespace cgagen::symbolic
