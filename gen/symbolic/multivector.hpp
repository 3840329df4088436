// A symbolic multivector of the current algebra (algebra::current(), CGA R(4,1) by default): a sparse map
// from user-basis blade (algebra/blade.hpp order) to a GiNaC expression; never 2^n slots, so ccga's 65,536
// blades cost only the blades a value has. A small value type with the algebra's operators; products look up the exact
// tables of algebra/products.hpp and expand their coefficients, and coefficients that expand to 0 are
// dropped, so two equal multivectors have the same blades.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <ostream>
#include <string>

#include "algebra/blade.hpp"
#include "algebra/products.hpp"

namespace cgagen::symbolic {

using algebra::BladeIndex;

class Multivector {
 public:
  Multivector() = default;                         // 0
  explicit Multivector(const GiNaC::ex& scalar);   // scalar * 1
  static Multivector blade(BladeIndex i, const GiNaC::ex& coeff = 1);
  // CGA's basis vectors and pseudoscalar e1^e2^e3^einf^e0 (the CGA built-ins use them).
  static Multivector e1() { return blade(1); }
  static Multivector e2() { return blade(2); }
  static Multivector e3() { return blade(3); }
  static Multivector einf() { return blade(4); }
  static Multivector e0() { return blade(5); }
  static Multivector pseudoscalar() { return blade(31); }

  // Blade -> coefficient, blades in Gaalop order; never holds an explicit 0.
  const std::map<BladeIndex, GiNaC::ex>& terms() const { return terms_; }
  GiNaC::ex coeff(BladeIndex i) const;
  // Sets blade i's coefficient (expanded; removed when it is identically zero).
  void set(BladeIndex i, const GiNaC::ex& c);

  bool is_zero() const { return terms_.empty(); }
  bool is_scalar() const { return terms_.empty() || (terms_.size() == 1 && terms_.begin()->first == 0); }
  GiNaC::ex scalar() const { return coeff(0); }
  // True when every blade has grade k (0 counts as any grade).
  bool is_homogeneous(int k) const;

  Multivector operator-() const;
  Multivector& operator+=(const Multivector& b);
  Multivector& operator-=(const Multivector& b);
  friend Multivector operator+(Multivector a, const Multivector& b) { return a += b; }
  friend Multivector operator-(Multivector a, const Multivector& b) { return a -= b; }
  friend Multivector operator*(const Multivector& a, const Multivector& b);  // geometric product
  friend Multivector operator^(const Multivector& a, const Multivector& b);  // outer product
  friend Multivector inner(const Multivector& a, const Multivector& b);      // Gaalop inner product
  // The products that keep one grade of each blade pair's geometric product (docs/language.md, "Products").
  enum class Graded {
    LeftContraction,   // grade s - r of A_r B_s, 0 when r > s
    RightContraction,  // grade r - s of A_r B_s, 0 when r < s
    Scalar,            // grade 0 of A B
    Dot,               // grade |r - s| of A_r B_s, scalars included (Gaalop's inner product drops them)
  };
  friend Multivector graded_product(Graded kind, const Multivector& a, const Multivector& b);
  // Scalar multiplication and division (coefficient-wise, expanded).
  friend Multivector operator*(const GiNaC::ex& s, const Multivector& a);
  friend Multivector operator*(const Multivector& a, const GiNaC::ex& s) { return s * a; }
  friend Multivector operator/(const Multivector& a, const GiNaC::ex& s);

  Multivector reverse() const;   // ~A
  Multivector involute() const;  // grade involution
  Multivector grade(int k) const;
  Multivector grade_above(int k) const;  // the blades of grade > k
  // Gaalop's *A: in CGA A * (-e1^e2^e3^einf^e0); in a nondegenerate algebra A * I^-1; in a degenerate one
  // (PGA) the complement map of Gaalop's 3dpga/2dpga (see multivector.cpp, docs/generator.md).
  Multivector dual() const;
  // The inverse of dual(): undual(dual(A)) = A. In a nondegenerate algebra A * (d)^-1 for dual's factor d; in
  // a degenerate one the complement map again (it is its own inverse).
  Multivector undual() const;
  // Re-expands every coefficient and, where a coefficient still has a denominator, normalizes it to find
  // identically-zero ones (normal() is only paid for rational coefficients).
  Multivector expanded() const;
  // Applies f to every coefficient (then expands and drops zeros).
  template <class F>
  Multivector map(F&& f) const {
    Multivector r;
    for (const auto& [b, c] : terms_) r.set(b, f(c));
    return r;
  }

  // Without the terms for which drop(blade, coefficient) holds (coefficients untouched, nothing expanded):
  // the expander's zero tests remove the blades whose coefficients vanish once earlier values are inlined.
  template <class Drop>
  Multivector without(Drop&& drop) const {
    Multivector r = *this;
    for (const auto& [b, c] : terms_)
      if (drop(b, c)) r.terms_.erase(b);
    return r;
  }

  // Stable text: "x*e1 + (1/2*x^2+...)*einf + e0"; "0" when empty. Blades in Gaalop order.
  std::string str() const;
  friend std::ostream& operator<<(std::ostream& os, const Multivector& a) { return os << a.str(); }
  friend bool operator==(const Multivector& a, const Multivector& b);  // (a - b) has no blades

 private:
  static Multivector product(algebra::ProductKind kind, const Multivector& a, const Multivector& b);
  std::map<BladeIndex, GiNaC::ex> terms_;
};

// True when e expands to 0, normalizing it first if it has a denominator. A float probe of the unexpanded
// e comes first: most coefficients asked about are plainly nonzero, and expanding large inlined values
// (a division by a multivector) used to take tens of seconds.
bool is_identically_zero(const GiNaC::ex& e);

// Whether x, a rational expression, is identically zero. Probes at two fixed irregular points (by symbol
// name, so the same in every process) first: a value clearly away from 0 in floats, or any nonzero exact
// value, decides "no" at once; only otherwise is x normalized (GiNaC's normal(), whose gcds take seconds
// on large quotients).
bool is_zero_rational(const GiNaC::ex& x);

}  // namespace cgagen::symbolic
