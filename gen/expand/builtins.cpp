// The built-in functions (builtins.hpp): the table, and the closed forms behind exp.
#include "expand/builtins.hpp"

#include <algorithm>
#include <map>

#include "algebra/algebra.hpp"
#include "front/diagnostics.hpp"

namespace cgagen::expand_builtins {

using front::CompileError;
using GiNaC::ex;

std::string blade_list(const Multivector& m) {
  std::string s;
  for (const auto& [b, c] : m.terms()) s += (s.empty() ? "" : ", ") + algebra::blade_name(b);
  return s;
}

std::string describe(const Multivector& m) { return "a multivector with blades " + blade_list(m); }

Multivector magnitude(const Multivector& m) { return Multivector(GiNaC::sqrt(GiNaC::abs((m * m.reverse()).scalar()))); }

ex Call::scalar(size_t i) const {
  args[i] = ctx.scalar_part_if_scalar(args[i]);
  if (!args[i].is_scalar()) {
    std::string which = args.size() == 1 ? "a scalar argument" : "scalar arguments";
    throw CompileError(expr.args[i]->loc, "'" + name + "' takes " + which + ", got " + describe(args[i]) +
                                              (args.size() == 1 ? "" : " as argument " + std::to_string(i + 1)));
  }
  return args[i].scalar();
}

std::vector<ex> Call::scalars() const {
  std::vector<ex> s;
  for (size_t i = 0; i < args.size(); ++i) s.push_back(scalar(i));
  return s;
}

namespace {

// floor of a real rational number, exactly.
GiNaC::numeric floor_numeric(const GiNaC::numeric& x) {
  GiNaC::numeric q = GiNaC::iquo(x.numer(), x.denom());  // truncates toward zero
  if (x.is_negative() && q * x.denom() != x.numer()) q -= 1;
  return q;
}

// A scalar function of one scalar.
Builtin scalar_function(const std::string& name, ex (*f)(const ex&)) {
  return {name, {1}, false, [f](const Call& c) { return Multivector(f(c.scalar(0))); }};
}

// floor, ceil and fact (Gaalop's MathFunction) are exact on constants. On a run-time value they would need a
// function some targets lack (a factorial of a real is tgamma(x+1), absent from GLSL) and one the optimizer
// cannot reason about (floor is not smooth), so a value that is not a number is a located error.
Builtin constant_function(const std::string& name, ex (*f)(const GiNaC::numeric&)) {
  return {name, {1}, false, [name, f](const Call& c) {
            const ex x = c.scalar(0);
            if (!GiNaC::is_a<GiNaC::numeric>(x) || !GiNaC::ex_to<GiNaC::numeric>(x).is_real())
              throw CompileError(c.expr.args[0]->loc, "'" + name + "' takes a constant argument in cgagen (a number, "
                                                      "not a value that depends on the inputs)");
            const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(x);
            if (name == "fact" && (!n.is_nonneg_integer() || n > 170))
              throw CompileError(c.expr.args[0]->loc, "'fact' takes an integer from 0 to 170");
            return Multivector(f(n));
          }};
}

// x e1 + y e2 + z e3 + (x^2 + y^2 + z^2 - r2)/2 einf + e0: a conformal point (r2 = 0), or a dual sphere.
Multivector up(const ex& x, const ex& y, const ex& z, const ex& r2) {
  return Multivector::blade(1, x) + Multivector::blade(2, y) + Multivector::blade(3, z) +
         Multivector::blade(4, (x * x + y * y + z * z - r2) / 2) + Multivector::e0();
}

// A binary product of the table below (lcont, rcont, ...).
Builtin binary(const std::string& name, Multivector (*f)(const Multivector&, const Multivector&)) {
  return {name, {2}, false, [f](const Call& c) { return f(c.args[0], c.args[1]); }};
}
Builtin unary(const std::string& name, Multivector (*f)(const Multivector&)) {
  return {name, {1}, false, [f](const Call& c) { return f(c.args[0]); }};
}

// <X ~X>_0, the squared reverse norm.
ex reverse_norm_squared(const Multivector& x) {
  return graded_product(Multivector::Graded::Scalar, x, x.reverse()).scalar();
}

// grade(X, k): k must be a constant integer from 0 to the algebra's dimension.
Multivector grade_select(const Call& c) {
  const Multivector k = c.ctx.scalar_part_if_scalar(c.args[1]);
  const int dim = algebra::current().dimension();
  const std::string range = "an integer constant from 0 to " + std::to_string(dim);
  if (!k.is_scalar() || !GiNaC::is_a<GiNaC::numeric>(k.scalar()))
    throw CompileError(c.expr.args[1]->loc, "'grade' takes as its second argument " + range +
                                                " (a number, not a value that depends on the inputs)");
  const GiNaC::numeric& n = GiNaC::ex_to<GiNaC::numeric>(k.scalar());
  if (!n.is_integer() || n.is_negative() || n > dim)
    throw CompileError(c.expr.args[1]->loc, "'grade' takes as its second argument " + range + " in the algebra '" +
                                                algebra::current().name() + "'");
  return c.args[0].grade(n.to_int());
}

// normalize(X) = X / sqrt(|<X ~X>_0|), in every algebra.
Multivector normalize(const Call& c) {
  const Multivector n2 = c.ctx.scalar_part_if_scalar(Multivector(reverse_norm_squared(c.args[0])));
  if (n2.is_zero())
    throw CompileError(c.expr.args[0]->loc, "'normalize' of a multivector whose squared norm <X ~X>_0 is 0");
  return c.args[0] / GiNaC::sqrt(GiNaC::abs(n2.scalar()));
}

// CLUCalc's DefVars*: they declare the basis names of a space for CLUCalc's interpreter; a script compiled
// for one algebra has them already, so they do nothing (and return 0, as a statement of their own).
Builtin no_op(const std::string& name) {
  return {name, {0}, false, [](const Call&) { return Multivector(); }};
}

const std::vector<Builtin>& table() {
  static const std::vector<Builtin> builtins = {
      // abs of a scalar is |x|; of a multivector, its magnitude (Gaalop).
      {"abs", {1}, false, [](const Call& c) {
         const Multivector s = c.ctx.scalar_part_if_scalar(c.args[0]);
         return s.is_scalar() ? Multivector(GiNaC::abs(s.scalar())) : magnitude(c.args[0]);
       }},
      scalar_function("sqrt", [](const ex& x) -> ex { return GiNaC::sqrt(x); }),
      scalar_function("sin", [](const ex& x) -> ex { return GiNaC::sin(x); }),
      scalar_function("cos", [](const ex& x) -> ex { return GiNaC::cos(x); }),
      scalar_function("tan", [](const ex& x) -> ex { return GiNaC::tan(x); }),
      scalar_function("asin", [](const ex& x) -> ex { return GiNaC::asin(x); }),
      scalar_function("acos", [](const ex& x) -> ex { return GiNaC::acos(x); }),
      scalar_function("atan", [](const ex& x) -> ex { return GiNaC::atan(x); }),
      // log of a positive scalar, or the logarithm of a rotor or motor (exponential.cpp).
      {"log", {1}, false, logarithm},
      constant_function("floor", [](const GiNaC::numeric& x) -> ex { return ex(floor_numeric(x)); }),
      constant_function("ceil", [](const GiNaC::numeric& x) -> ex { return ex(-floor_numeric(-x)); }),
      constant_function("fact", [](const GiNaC::numeric& x) -> ex { return GiNaC::factorial(x); }),
      {"atan2", {2}, false, [](const Call& c) {
         const auto s = c.scalars();
         return Multivector(GiNaC::atan2(s[0], s[1]));
       }},
      {"exp", {1}, false, exponential},
      // invert (Gaalop's MathFunction INVERT): the inverse of a multivector, 1/X as the division defines it.
      {"invert", {1}, false,
       [](const Call& c) { return c.ctx.divide(Multivector(ex(1)), c.args[0], *c.expr.args[0]); }},
      {"Dual", {1}, false, [](const Call& c) { return c.args[0].dual(); }},
      // The operator set of GATL, kingdon and ga-benchmark (docs/language.md, "Operators and functions").
      unary("undual", [](const Multivector& a) { return a.undual(); }),
      unary("involute", [](const Multivector& a) { return a.involute(); }),
      unary("conjugate", [](const Multivector& a) { return a.reverse().involute(); }),
      unary("rnorm_sqr", [](const Multivector& a) { return Multivector(reverse_norm_squared(a)); }),
      {"normalize", {1}, false, normalize},
      {"grade", {2}, false, grade_select},
      binary("lcont", [](const Multivector& a, const Multivector& b) {
        return graded_product(Multivector::Graded::LeftContraction, a, b);
      }),
      binary("rcont", [](const Multivector& a, const Multivector& b) {
        return graded_product(Multivector::Graded::RightContraction, a, b);
      }),
      binary("scp", [](const Multivector& a, const Multivector& b) {
        return graded_product(Multivector::Graded::Scalar, a, b);
      }),
      binary("dot", [](const Multivector& a, const Multivector& b) {
        return graded_product(Multivector::Graded::Dot, a, b);
      }),
      binary("hip", [](const Multivector& a, const Multivector& b) { return inner(a, b); }),
      binary("cp", [](const Multivector& a, const Multivector& b) {
        return GiNaC::numeric(1, 2) * (a * b - b * a);
      }),
      binary("rp", [](const Multivector& a, const Multivector& b) { return (a.dual() ^ b.dual()).undual(); }),
      // igp(A, B) = A * invert(B) = A / B.
      {"igp", {2}, false, [](const Call& c) { return c.ctx.divide(c.args[0], c.args[1], *c.expr.args[1]); }},
      // coefficient(mv, blade): the scalar c with which mv holds c * blade, for a blade given as one basis
      // blade (e1^e2, or e2^e1 = -e1^e2, or 1).
      {"coefficient", {2}, false, [](const Call& c) {
         const Multivector& blade = c.args[1];
         if (blade.terms().size() != 1 || !GiNaC::is_a<GiNaC::numeric>(blade.terms().begin()->second))
           throw CompileError(c.expr.args[1]->loc, "'coefficient' takes a basis blade as its second argument (such "
                                                   "as e1^e2 or 1), got " + describe(blade));
         const auto& [k, sign] = *blade.terms().begin();
         return Multivector(c.args[0].coeff(k) / sign);
       }},
      // Gaalop's CGA Normalize: -X / (X.einf), a point scaled to e0 weight 1 (not X / abs(X), which is what
      // the other algebras' Normalize and #pragma normalize do).
      {"Normalize", {1}, false, [](const Call& c) {
         return c.ctx.divide(-c.args[0], inner(c.args[0], Multivector::einf()), *c.expr.args[0]);
       }},
      {"VecN3", {3}, true, [](const Call& c) { const auto s = c.scalars(); return up(s[0], s[1], s[2], 0); }},
      {"createPoint", {3}, true, [](const Call& c) { const auto s = c.scalars(); return up(s[0], s[1], s[2], 0); }},
      // SphereN3(x, y, z, r) = *(VecN3(x, y, z) - r^2/2 einf); SphereN3(P, r) = *(P - r^2/2 einf): the dual of
      // the (inner product null space) sphere, a 4-vector; Gaalop's scripts write *SphereN3(...) for the vector.
      {"SphereN3", {2, 4}, true, [](const Call& c) {
         if (c.args.size() == 2) {
           const ex r = c.scalar(1);
           return (c.args[0] - Multivector::blade(4, r * r / 2)).dual();
         }
         const auto s = c.scalars();
         return up(s[0], s[1], s[2], s[3] * s[3]).dual();
       }},
      {"TranslatorN3", {3}, true, [](const Call& c) {
         const auto s = c.scalars();
         const Multivector t = Multivector::blade(1, s[0]) + Multivector::blade(2, s[1]) + Multivector::blade(3, s[2]);
         return Multivector(ex(1)) - GiNaC::numeric(1, 2) * (t * Multivector::einf());
       }},
      // RotorN3 (Gaalop): cos(a/2) + sin(a/2) * (-x e23 + y e13 - z e12) / |(x,y,z)|
      {"RotorN3", {4}, true, [](const Call& c) {
         const auto s = c.scalars();
         const ex len = GiNaC::sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
         const ex half = s[3] / 2;
         const Multivector plane =
             Multivector::blade(10, -s[0]) + Multivector::blade(7, s[1]) + Multivector::blade(6, -s[2]);
         return Multivector(GiNaC::cos(half)) + (GiNaC::sin(half) / len) * plane;
       }},
      // Gaalop's CGA ExtractFirstPoint / ExtractSecondPoint of X, the outer product of three dual spheres (the
      // form Gaalop's GPS example builds): with D = *X, the point pair, (D +- sqrt(|X.X|)) / (einf.D); first
      // with +, second with -. Not normalized (e0 weight != 1).
      {"ExtractFirstPoint", {1}, false, [](const Call& c) {
         const Multivector d = c.args[0].dual();
         const Multivector root(GiNaC::sqrt(GiNaC::abs(c.ctx.scalar_part_if_scalar(inner(c.args[0], c.args[0])).scalar())));
         return c.ctx.divide(d + root, inner(Multivector::einf(), d), *c.expr.args[0]);
       }},
      {"ExtractSecondPoint", {1}, false, [](const Call& c) {
         const Multivector d = c.args[0].dual();
         const Multivector root(GiNaC::sqrt(GiNaC::abs(c.ctx.scalar_part_if_scalar(inner(c.args[0], c.args[0])).scalar())));
         return c.ctx.divide(d - root, inner(Multivector::einf(), d), *c.expr.args[0]);
       }},
      no_op("DefVarsE3"),
      no_op("DefVarsP3"),
      no_op("DefVarsN3"),
  };
  return builtins;
}

}  // namespace

const Builtin* find(const std::string& name) {
  static const std::map<std::string, const Builtin*> by_name = [] {
    std::map<std::string, const Builtin*> m;
    for (const Builtin& b : table()) m.emplace(b.name, &b);
    return m;
  }();
  auto it = by_name.find(name);
  return it == by_name.end() ? nullptr : it->second;
}

std::vector<std::string> names() {
  std::vector<std::string> n;
  for (const Builtin& b : table()) n.push_back(b.name);
  std::sort(n.begin(), n.end());  // hints pick the first of equally close names: a fixed order
  return n;
}

}  // namespace cgagen::expand_builtins
