// Blade products of the current algebra (algebra::current(), algebra.hpp; CGA by default) for the
// geometric, outer and Gaalop inner product, plus the per-blade signs of reverse and grade involution.
//
// Each product is computed on first use from the diagonal metric alone: both blades are written over the
// diagonal basis (in CGA the orthonormal {e1, e2, e3, e+, e-}, einf = e- + e+, e0 = (e- - e+)/2), multiplied
// there with bitmap products, and the result written back over the user blades; it is then cached per
// pair. Entries are exact rationals (0, +-1, +-2, +-1/2, ...).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "algebra/blade.hpp"

namespace cgagen::algebra {

// An exact rational with a positive denominator, always in lowest terms.
struct Rational {
  std::int64_t num = 0;
  std::int64_t den = 1;

  Rational() = default;
  Rational(std::int64_t n, std::int64_t d = 1);  // normalizes; throws std::invalid_argument on d == 0
  bool is_zero() const { return num == 0; }
  double to_double() const { return static_cast<double>(num) / static_cast<double>(den); }
  std::string str() const;  // "1", "-1/2"
  friend Rational operator+(Rational a, Rational b);
  friend Rational operator-(Rational a) { return Rational(-a.num, a.den); }
  friend Rational operator-(Rational a, Rational b) { return a + (-b); }
  friend Rational operator*(Rational a, Rational b);
  friend Rational operator/(Rational a, Rational b);
  friend bool operator==(Rational a, Rational b) { return a.num == b.num && a.den == b.den; }
};

// One term of a product of two blades: coeff * blade.
struct ProductTerm {
  BladeIndex blade;
  Rational coeff;
};

enum class ProductKind : int {
  Geometric,  // a * b
  Outer,      // a ^ b
  Inner,      // a . b (Gaalop): grade-|k-l| part of a*b for grades k, l >= 1; 0 if either is a scalar
};

// The nonzero terms of blade a (op) blade b, in increasing blade order.
const std::vector<ProductTerm>& product(ProductKind kind, BladeIndex a, BladeIndex b);

// ~blade = reverse_sign(i) * blade: (-1)^(k(k-1)/2) for grade k.
int reverse_sign(BladeIndex i);
// Grade involution: (-1)^k.
int involution_sign(BladeIndex i);

}  // namespace cgagen::algebra
