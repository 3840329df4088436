// Exact evaluation at fixed points modulo a prime, for zero tests (see probes.hpp).
#include "symbolic/probes.hpp"

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

std::uint64_t inverse_mod(std::uint64_t a) {  // a^(p-2), a != 0 (Fermat)
  std::uint64_t r = 1, e = kPrime - 2;
  for (; e; e >>= 1, a = mul_mod(a, a))
    if (e & 1) r = mul_mod(r, a);
  return r;
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

// A rational number modulo p; nullopt when its denominator is a multiple of p.
std::optional<std::uint64_t> number_mod(const GiNaC::numeric& n) {
  if (n.is_integer()) return reduce(n);
  if (!n.is_rational()) return std::nullopt;
  const std::uint64_t den = reduce(n.denom());
  if (den == 0) return std::nullopt;
  return mul_mod(reduce(n.numer()), inverse_mod(den));
}

// e at one point, modulo p, computed directly on GiNaC's stored nodes (each shared node once); no value
// where e is not a rational function of known symbols and opaque nodes, or has a pole there. Exact: the same
// value as substituting the point's rationals and reducing, except where an intermediate denominator is a
// multiple of p (probability ~2^-61 per operation).
// A symbol without a value in `at` for which unknown(symbol) holds sets *unknown_met (the caller then gives
// it one and asks again); other symbols without a value make e's value none. An opaque node without a value
// gets opaque_value(node), which draws one and records it in `at`.
template <class Value, class Values, class Unknown, class Opaque>
Value value_at(const GiNaC::ex& e, const Values& at, Unknown&& unknown, Opaque&& opaque_value, bool* unknown_met) {
  std::unordered_map<const GiNaC::basic*, Value> memo;
  auto eval = [&](auto&& self, const GiNaC::ex& x) -> Value {
    if (symbolic::is_numeric(x)) return {number_mod(GiNaC::ex_to<GiNaC::numeric>(x)), false};
    if (auto it = memo.find(symbolic::node_of(x)); it != memo.end()) return it->second;  // symbols too
    Value v;
    const Kind kind = kind_of(x);
    const bool root = kind == Kind::Power && !(symbolic::is_numeric(x.op(1)) &&
                                               GiNaC::ex_to<GiNaC::numeric>(x.op(1)).is_integer());
    if (kind == Kind::Symbol) {
      if (auto it = at.find(x); it != at.end()) v = it->second;  // none where it did not evaluate
      else if (unknown(x)) *unknown_met = true;
    } else if (kind == Kind::Function || root) {
      if (auto it = at.find(x); it != at.end()) v = it->second;
      else v = opaque_value(x);
    } else if (kind == Kind::Add || kind == Kind::Mul) {
      const bool product = kind == Kind::Mul;
      const auto& pairs = symbolic::pairs_of(x);
      std::uint64_t acc = product ? 1 : 0;
      bool ok = true;
      for (const auto& p : pairs) {
        const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(p.coeff);
        if (product && !c.is_integer()) {  // a root among the factors, stored as (base, exponent): opaque
          const GiNaC::ex root = GiNaC::pow(p.rest, c);
          const auto it = at.find(root);
          const Value r = it != at.end() ? it->second : opaque_value(root);
          v.opaque = true;
          if (!r.v) { ok = false; break; }
          acc = mul_mod(acc, *r.v);
          continue;
        }
        const Value r = self(self, p.rest);
        v.opaque |= r.opaque;
        if (!r.v) { ok = false; break; }
        if (product) {
          std::uint64_t base = *r.v;
          if (c.is_negative()) {
            if (base == 0) { ok = false; break; }  // a pole
            base = inverse_mod(base);
          }
          acc = mul_mod(acc, pow_mod(base, static_cast<std::uint64_t>(GiNaC::abs(c).to_long())));
        } else {
          auto cm = number_mod(c);
          if (!cm) { ok = false; break; }
          acc = add_mod(acc, mul_mod(*cm, *r.v));
        }
      }
      if (ok && x.nops() > pairs.size()) {  // the numeric overall coefficient
        auto oc = number_mod(GiNaC::ex_to<GiNaC::numeric>(x.op(x.nops() - 1)));
        if (!oc) ok = false;
        else acc = product ? mul_mod(acc, *oc) : add_mod(acc, *oc);
      }
      if (ok) v.v = acc;
    } else if (kind == Kind::Power) {  // an integer power
      const Value r = self(self, x.op(0));
      const GiNaC::numeric& k = GiNaC::ex_to<GiNaC::numeric>(x.op(1));
      v.opaque = r.opaque;
      if (r.v && !(k.is_negative() && *r.v == 0))
        v.v = pow_mod(k.is_negative() ? inverse_mod(*r.v) : *r.v, static_cast<std::uint64_t>(GiNaC::abs(k).to_long()));
    }
    memo.emplace(symbolic::node_of(x), v);
    return v;
  };
  return eval(eval, e);
}

}  // namespace

std::uint64_t ProbePoints::draw() {
  state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
  return 1 + (state_ >> 3) % (kPrime - 1);
}

void ProbePoints::add_input(const GiNaC::symbol& s) {
  for (auto& at : at_) at[s] = {draw(), false};
}

void ProbePoints::define(const GiNaC::symbol& s, const GiNaC::ex& definition) { definitions_.emplace(s, definition); }

// e at point k. The defined symbols e depends on get their values there first, when e meets one without.
// The values drawn for opaque nodes depend only on the order in which nodes are first met, which is the
// order of the tests: the same in every run.
ProbePoints::Value ProbePoints::value_at_point(const GiNaC::ex& e, int k) {
  Values& at = at_[static_cast<std::size_t>(k)];
  auto pending = [&](const GiNaC::ex& s) { return !at.count(s) && definitions_.count(s); };
  auto opaque = [&](const GiNaC::ex& node) { return at[node] = Value{draw(), true}; };
  bool met_pending = false;
  Value v = value_at<Value>(e, at, pending, opaque, &met_pending);
  if (!met_pending) return v;
  symbolic::define_dependencies_first(
      e, pending, [&](const GiNaC::ex& s) -> const GiNaC::ex& { return definitions_.at(s); },
      [&](const GiNaC::ex& s) {
        bool unused = false;
        const Value sv = value_at<Value>(definitions_.at(s), at, pending, opaque, &unused);
        at[s] = sv;
      });
  bool unused = false;
  return value_at<Value>(e, at, pending, opaque, &unused);
}

ProbePoints::Verdict ProbePoints::test(const GiNaC::ex& e) {
  int zeros = 0;
  for (int k = 0; k < kPoints; ++k) {
    const Value v = value_at_point(e, k);
    if (!v.v) continue;
    if (*v.v != 0) return v.opaque ? Verdict::Unknown : Verdict::Nonzero;
    ++zeros;
  }
  return zeros == kPoints ? Verdict::Zero : Verdict::Unknown;
}

}  // namespace cgagen::symbolic
