// Exact rationals, and the products of the current algebra (see products.hpp; algebra.cpp computes them).
#include "algebra/products.hpp"

#include "algebra/algebra.hpp"

#include <array>
#include <bit>
#include <numeric>
#include <stdexcept>

namespace cgagen::algebra {

Rational::Rational(std::int64_t n, std::int64_t d) {
  if (d == 0) throw std::invalid_argument("Rational: zero denominator");
  if (d < 0) n = -n, d = -d;
  std::int64_t g = std::gcd(n < 0 ? -n : n, d);
  if (g == 0) g = 1;
  num = n / g;
  den = d / g;
}

std::string Rational::str() const {
  return den == 1 ? std::to_string(num) : std::to_string(num) + "/" + std::to_string(den);
}

namespace {

// Exact int64 arithmetic, or std::overflow_error (a user algebra file with long decimals).
std::int64_t checked_mul(std::int64_t x, std::int64_t y) {
  std::int64_t r;
  if (__builtin_mul_overflow(x, y, &r)) throw std::overflow_error("Rational: overflow");
  return r;
}
std::int64_t checked_add(std::int64_t x, std::int64_t y) {
  std::int64_t r;
  if (__builtin_add_overflow(x, y, &r)) throw std::overflow_error("Rational: overflow");
  return r;
}

}  // namespace

Rational operator+(Rational a, Rational b) {
  return Rational(checked_add(checked_mul(a.num, b.den), checked_mul(b.num, a.den)), checked_mul(a.den, b.den));
}
Rational operator*(Rational a, Rational b) { return Rational(checked_mul(a.num, b.num), checked_mul(a.den, b.den)); }
Rational operator/(Rational a, Rational b) {
  if (b.is_zero()) throw std::invalid_argument("Rational: division by zero");
  return Rational(checked_mul(a.num, b.den), checked_mul(a.den, b.num));
}

const std::vector<ProductTerm>& product(ProductKind kind, BladeIndex a, BladeIndex b) {
  return current().product(kind, a, b);
}

int reverse_sign(BladeIndex i) {
  int k = blade_grade(i);
  return ((k * (k - 1) / 2) & 1) ? -1 : 1;
}

int involution_sign(BladeIndex i) { return (blade_grade(i) & 1) ? -1 : 1; }

}  // namespace cgagen::algebra
