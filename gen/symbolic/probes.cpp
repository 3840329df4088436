// Exact evaluation at fixed points modulo a prime, for zero tests (see probes.hpp).
#include "symbolic/probes.hpp"

#include <exception>
#include <optional>

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
  GiNaC::numeric m = GiNaC::mod(integer, GiNaC::numeric(static_cast<long>(kPrime)));
  return static_cast<std::uint64_t>(m.to_long());
}

// Sums, products, integer powers, symbols and rational numbers only.
bool is_rational_function(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return true;
  if (GiNaC::is_a<GiNaC::numeric>(e)) return GiNaC::ex_to<GiNaC::numeric>(e).is_rational();
  if (GiNaC::is_a<GiNaC::power>(e)) {
    const GiNaC::ex& k = e.op(1);
    return GiNaC::is_a<GiNaC::numeric>(k) && GiNaC::ex_to<GiNaC::numeric>(k).is_integer() &&
           is_rational_function(e.op(0));
  }
  if (!GiNaC::is_a<GiNaC::add>(e) && !GiNaC::is_a<GiNaC::mul>(e)) return false;
  for (size_t i = 0; i < e.nops(); ++i)
    if (!is_rational_function(e.op(i))) return false;
  return true;
}

// e at one point, modulo p; nullopt when e is not a rational function of known symbols or has a pole there.
std::optional<std::uint64_t> value_at(const GiNaC::ex& e, const GiNaC::exmap& at) {
  if (!is_rational_function(e)) return std::nullopt;
  try {
    const GiNaC::ex v = e.subs(at, GiNaC::subs_options::no_pattern | GiNaC::subs_options::pattern_is_not_product);
    if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_rational()) return std::nullopt;
    const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(v);
    const std::uint64_t den = reduce(n.denom());
    if (den == 0) return std::nullopt;  // a pole modulo p
    return mul_mod(reduce(n.numer()), inverse_mod(den));
  } catch (const std::exception&) {
    return std::nullopt;  // a pole of the rational expression itself
  }
}

}  // namespace

void ProbePoints::add_input(const GiNaC::symbol& s) {
  for (GiNaC::exmap& at : at_) {
    state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;
    at[s] = GiNaC::numeric(static_cast<long>(1 + (state_ >> 3) % (kPrime - 1)));
  }
}

void ProbePoints::define(const GiNaC::symbol& s, const GiNaC::ex& definition) {
  for (GiNaC::exmap& at : at_)
    if (auto v = value_at(definition, at)) at[s] = GiNaC::numeric(static_cast<long>(*v));
}

ProbePoints::Verdict ProbePoints::test(const GiNaC::ex& e) const {
  int zeros = 0;
  for (const GiNaC::exmap& at : at_) {
    auto v = value_at(e, at);
    if (!v) continue;
    if (*v != 0) return Verdict::Nonzero;
    ++zeros;
  }
  return zeros == kPoints ? Verdict::Zero : Verdict::Unknown;
}

}  // namespace cgagen::symbolic
