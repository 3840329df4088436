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

// e at one point, modulo p, computed directly on GiNaC's stored nodes (each shared node once); nullopt when
// e is not a rational function of known symbols or has a pole there. Exact: the same value as
// substituting the point's rationals and reducing, except where an intermediate denominator is a multiple
// of p (probability ~2^-61 per operation).
// A symbol without a value in `at` for which unknown(symbol) holds sets *unknown_met (the caller then gives
// it one and asks again); other symbols without a value make e's value nullopt.
template <class Values, class Unknown>
std::optional<std::uint64_t> value_at(const GiNaC::ex& e, const Values& at, Unknown&& unknown, bool* unknown_met) {
  std::unordered_map<const GiNaC::basic*, std::optional<std::uint64_t>> memo;
  auto eval = [&](auto&& self, const GiNaC::ex& x) -> std::optional<std::uint64_t> {
    if (symbolic::is_numeric(x)) return number_mod(GiNaC::ex_to<GiNaC::numeric>(x));
    if (auto it = memo.find(symbolic::node_of(x)); it != memo.end()) return it->second;  // symbols too
    std::optional<std::uint64_t> v;
    if (symbolic::is_symbol(x)) {
      if (auto it = at.find(x); it != at.end()) v = it->second;  // none where it did not evaluate
      else if (unknown(x)) *unknown_met = true;
    } else if (symbolic::is_add(x) || symbolic::is_mul(x)) {
      const bool product = symbolic::is_mul(x);
      const auto& pairs = symbolic::pairs_of(x);
      std::uint64_t acc = product ? 1 : 0;
      bool ok = true;
      for (const auto& p : pairs) {
        auto r = self(self, p.rest);
        if (!r) { ok = false; break; }
        const GiNaC::numeric& c = GiNaC::ex_to<GiNaC::numeric>(p.coeff);
        if (product) {
          if (!c.is_integer()) { ok = false; break; }
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

}  // namespace

void ProbePoints::add_input(const GiNaC::symbol& s) {
  for (auto& at : at_) {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    at[s] = 1 + (state_ >> 3) % (kPrime - 1);
  }
}

void ProbePoints::define(const GiNaC::symbol& s, const GiNaC::ex& definition) { definitions_.emplace(s, definition); }

// e at point k. The defined symbols e depends on get their values there first, when e meets one without.
std::optional<std::uint64_t> ProbePoints::value_at_point(const GiNaC::ex& e, int k) {
  Values& at = at_[static_cast<std::size_t>(k)];
  auto pending = [&](const GiNaC::ex& s) { return !at.count(s) && definitions_.count(s); };
  bool met_pending = false;
  std::optional<std::uint64_t> v = value_at(e, at, pending, &met_pending);
  if (!met_pending) return v;
  symbolic::define_dependencies_first(
      e, pending, [&](const GiNaC::ex& s) -> const GiNaC::ex& { return definitions_.at(s); },
      [&](const GiNaC::ex& s) {
        bool unused = false;
        const std::optional<std::uint64_t> sv = value_at(definitions_.at(s), at, pending, &unused);
        at[s] = sv;
      });
  bool unused = false;
  return value_at(e, at, pending, &unused);
}

ProbePoints::Verdict ProbePoints::test(const GiNaC::ex& e) {
  int zeros = 0;
  for (int k = 0; k < kPoints; ++k) {
    auto v = value_at_point(e, k);
    if (!v) continue;
    if (*v != 0) return Verdict::Nonzero;
    ++zeros;
  }
  return zeros == kPoints ? Verdict::Zero : Verdict::Unknown;
}

}  // namespace cgagen::symbolic
