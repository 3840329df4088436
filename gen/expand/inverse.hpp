// The inverse of a multivector, as the language's division uses it (docs/language.md, "Division"): the
// cheapest closed form that applies, tried in order, each one proved symbolically before it is used.
//   1. X ~X is a scalar (versors and blades):        X^-1 = ~X / (X ~X)
//   2. X conj(X) is a scalar (every X in 1D and 2D):  X^-1 = conj(X) / (X conj(X))
//   3. any X: the adjugate of the characteristic-polynomial recursion (Shirokov, "On computing the
//      determinant, other characteristic polynomial coefficients, and inverse in Clifford algebras of
//      arbitrary dimension", 2021), X^-1 = adj(X) / (X adj(X)), where X adj(X) must come out a scalar.
// A value whose denominator is identically 0 has no inverse (a zero divisor) and is refused. So is an adjugate
// past the work budget (a general 5D even multivector): `#pragma versor NAME` then declares the versor form.
#pragma once

#include <functional>
#include <string>

#include "symbolic/multivector.hpp"

namespace cgagen::expand_inverse {

using symbolic::Multivector;

// X^-1 = numerator / denominator.
struct Inverse {
  Multivector numerator;
  GiNaC::ex denominator;
};

// Why X has no inverse; the caller adds the location.
struct NotInvertible {
  std::string message;
};

// The inverse of x, a non-scalar multivector; `vanishes` is the expander's zero test (is a coefficient 0 once
// earlier values are inlined?), which decides whether a product is a scalar and whether it is 0. Throws
// NotInvertible.
Inverse inverse(const Multivector& x, const std::function<bool(const GiNaC::ex&)>& vanishes);

// The versor form ~x / <x ~x>_0, for a value the script declares a versor (`#pragma versor`, `normalized`):
// x ~x is then a scalar for every input passed, though not symbolically. Throws NotInvertible when <x ~x>_0
// is identically 0.
Inverse versor_inverse(const Multivector& x, const std::function<bool(const GiNaC::ex&)>& vanishes);

}  // namespace cgagen::expand_inverse
