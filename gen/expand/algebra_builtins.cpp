// Basis names and built-in macros per algebra (see algebra_builtins.hpp). The macros are our own, from the
// math of each model; docs/generator.md ("Algebras") lists them.
#include "expand/algebra_builtins.hpp"

#include <algorithm>
#include <set>

#include "algebra/algebra.hpp"

namespace cgagen::expand_algebra {

bool is_cga() {
  const auto& a = algebra::current();
  return a.name() == "cga" && a.spec().cga_idents;
}

bool is_basis_name(const std::string& n) {
  const auto& s = algebra::current().spec();
  return std::find(s.user.begin(), s.user.end(), n) != s.user.end() ||
         std::find(s.diagonal.begin(), s.diagonal.end(), n) != s.diagonal.end();
}

symbolic::Multivector basis(const std::string& n) {
  const auto& a = algebra::current();
  const auto& s = a.spec();
  if (int k = a.vector_index(n); k >= 0) return symbolic::Multivector::blade(a.index(1u << k));
  const auto d = static_cast<size_t>(std::find(s.diagonal.begin(), s.diagonal.end(), n) - s.diagonal.begin());
  symbolic::Multivector r;
  for (const auto& [u, c] : s.diagonal_in_user.at(d))
    r += symbolic::Multivector::blade(a.index(1u << u), GiNaC::numeric(c.num) / GiNaC::numeric(c.den));
  return r;
}

namespace {

// Every non-CGA algebra: the dual as a function, and normalization by the magnitude sqrt(|<A ~A>_0|).
const char* kCommon = R"(
Dual = { *_P(1) }
Normalize = { _P(1) / abs(_P(1)) }
)";

// PGA: the regressive product (join of points, meet of planes) through the complement dual.
const char* kPga = R"(
regProd = { *(*_P(1) ^ *_P(2)) }
)";

std::string specific(const std::string& name) {
  if (name == "2d") return "createPoint = { _P(1)*e1 + _P(2)*e2 }\n";
  if (name == "3d") return "createPoint = { _P(1)*e1 + _P(2)*e2 + _P(3)*e3 }\n";
  if (name == "sta") return "createPoint = { _P(1)*e0 + _P(2)*e1 + _P(3)*e2 + _P(4)*e3 }\n";
  // A PGA point is a (d)-vector: e1^e2^e3 at the origin, the coordinates on the blades with e0.
  if (name == "2dpga") return std::string(kPga) + "createPoint = { e1^e2 - _P(1)*(e0^e2) + _P(2)*(e0^e1) }\n";
  if (name == "3dpga")
    return std::string(kPga) +
           "createPoint = { e1^e2^e3 - _P(1)*(e0^e2^e3) + _P(2)*(e0^e1^e3) - _P(3)*(e0^e1^e2) }\n";
  // Conformal models: x + (x.x)/2 einf + e0, null (einf.e0 = -1).
  if (name == "cra") return "createPoint = { _P(1)*e1 + _P(2)*e2 + 0.5*(_P(1)*_P(1) + _P(2)*_P(2))*einf + e0 }\n";
  // Conics: the monomials x^2+y^2, x^2-y^2, xy on the three infinities; null through the e0p pairing.
  if (name == "gac")
    return "createPoint = { _P(1)*e1 + _P(2)*e2 + 0.5*(_P(1)*_P(1) + _P(2)*_P(2))*einfp + "
           "0.5*(_P(1)*_P(1) - _P(2)*_P(2))*einfm + _P(1)*_P(2)*einfc + e0p }\n";
  // Quadrics: each squared coordinate on its own infinity, the three origins summed.
  if (name == "qga")
    return "createPoint = { _P(1)*e1 + _P(2)*e2 + _P(3)*e3 + 0.5*(_P(1)*_P(1)*ei1 + _P(2)*_P(2)*ei2 + "
           "_P(3)*_P(3)*ei3) + eo1 + eo2 + eo3 }\n";
  // Double conformal: the outer product of the point in both CGA copies.
  if (name == "dcga")
    return "createPoint = {\n  s = 0.5*(_P(1)*_P(1) + _P(2)*_P(2) + _P(3)*_P(3));\n"
           "  (_P(1)*e1 + _P(2)*e2 + _P(3)*e3 + s*ei1 + eo1) ^ (_P(1)*e6 + _P(2)*e7 + _P(3)*e8 + s*ei2 + eo2)\n}\n";
  // Cubic plane curves: a null conformal point (pair 1) with the other cubic monomials on ei2..ei7, so that
  // a dual curve's inner product with it is any cubic polynomial in x, y.
  if (name == "ccga")
    return "createPoint = {\n  x = _P(1);\n  y = _P(2);\n"
           "  x*e1 + y*e2 + 0.5*(x*x + y*y)*ei1 + eo1 + x*x*ei2 + x*y*ei3 + x*x*x*ei4 + x*x*y*ei5 + "
           "x*y*y*ei6 + y*y*y*ei7\n}\n";
  return "";
}

}  // namespace

std::string prelude() {
  if (is_cga()) return "";
  return kCommon + specific(algebra::current().name());
}

}  // namespace cgagen::expand_algebra
