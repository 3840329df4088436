// Tests of the naive oracle (tests/oracle/include/oracle/multivector.hpp): the blade sign rule against
// a vector-by-vector reduction, algebraic laws on random multivectors, the CGA facts of
// /work/shared/notes/cga-facts.md, and the translator / rotor / dilator against GLM on random inputs.
#include <oracle/multivector.hpp>

#include <catch2/catch.hpp>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace {

using MV = oracle::MV<double>;
using oracle::Rng;
using P3 = std::array<double, 3>;

constexpr double kRel = 1e-12;  // relative tolerance of the GLM comparisons (the brief's 1e-12)

MV S(double s) { return MV::scalar(s); }
MV e1() { return oracle::e1<double>(); }
MV e2() { return oracle::e2<double>(); }
MV e3() { return oracle::e3<double>(); }
MV ep() { return oracle::ep<double>(); }
MV em() { return oracle::em<double>(); }
MV ni() { return oracle::einf<double>(); }
MV no() { return oracle::e0<double>(); }
MV nb(std::string_view name) { return oracle::null_blade<double>(name); }

std::string str(const MV& m) {
  std::ostringstream os;
  os.precision(17);
  os << m;
  return os.str();
}

// |a - b| small next to the size of what was computed.
bool near(const MV& a, const MV& b, double scale = 1.0, double tol = 1e-12) {
  return oracle::max_abs_diff(a, b) <= tol * std::max(1.0, scale);
}

bool near3(const P3& a, const P3& b, double rel = kRel) {
  double scale = 1.0, diff = 0.0;
  for (std::size_t i = 0; i < 3; ++i) {
    scale = std::max(scale, std::abs(b[i]));
    diff = std::max(diff, std::abs(a[i] - b[i]));
  }
  return diff <= rel * scale;
}

std::string str3(const P3& p) {
  std::ostringstream os;
  os.precision(17);
  os << "(" << p[0] << ", " << p[1] << ", " << p[2] << ")";
  return os.str();
}

P3 from_glm(const glm::dvec3& v) { return {v.x, v.y, v.z}; }
glm::dvec3 to_glm(const P3& p) { return {p[0], p[1], p[2]}; }

// Reference for the blade sign: write both blades as lists of vector indices, bubble-sort the
// concatenation counting swaps, then cancel equal neighbours with their square (+1, or -1 for em).
std::pair<int, unsigned> reference_blade_product(unsigned a, unsigned b) {
  std::vector<unsigned> v;
  for (unsigned i = 0; i < 5; ++i)
    if (a & (1u << i)) v.push_back(i);
  for (unsigned i = 0; i < 5; ++i)
    if (b & (1u << i)) v.push_back(i);
  int sign = 1;
  for (std::size_t pass = 0; pass < v.size(); ++pass)
    for (std::size_t j = 0; j + 1 < v.size(); ++j)
      if (v[j] > v[j + 1]) {
        std::swap(v[j], v[j + 1]);
        sign = -sign;
      }
  unsigned result = 0;
  for (std::size_t j = 0; j < v.size();) {
    if (j + 1 < v.size() && v[j] == v[j + 1]) {
      if (v[j] == 4) sign = -sign;  // em^2 = -1
      j += 2;
    } else {
      result |= 1u << v[j];
      ++j;
    }
  }
  return {sign, result};
}

}  // namespace

TEST_CASE("blade product sign matches a vector-by-vector reduction for all 1024 pairs", "[oracle][blade]") {
  for (unsigned a = 0; a < 32; ++a)
    for (unsigned b = 0; b < 32; ++b) {
      const auto [sign, blade] = reference_blade_product(a, b);
      const MV prod = MV::blade(a) * MV::blade(b);
      INFO("a=" << a << " b=" << b << " product=" << str(prod));
      REQUIRE(blade == (a ^ b));
      for (unsigned k = 0; k < 32; ++k) REQUIRE(prod[k] == (k == blade ? double(sign) : 0.0));
    }
}

TEST_CASE("basis vectors have signature (+,+,+,+,-) and anticommute", "[oracle][facts]") {
  const MV v[5] = {e1(), e2(), e3(), ep(), em()};
  const double sq[5] = {1, 1, 1, 1, -1};
  for (int i = 0; i < 5; ++i) {
    CHECK(near(v[i] * v[i], S(sq[i])));
    for (int j = 0; j < 5; ++j)
      if (i != j) {
        CHECK(near(v[i] * v[j], -(v[j] * v[i])));
        CHECK(near(v[i] * v[j], v[i] ^ v[j]));
        CHECK(scalar_part(inner(v[i], v[j])) == 0.0);
      }
  }
}

TEST_CASE("null vectors: einf^2 = e0^2 = 0, einf.e0 = -1, einf^e0 = ep^em", "[oracle][facts]") {
  CHECK(near(ni() * ni(), S(0)));
  CHECK(near(no() * no(), S(0)));
  CHECK(near(inner(ni(), no()), S(-1)));
  CHECK(near(inner(no(), ni()), S(-1)));
  CHECK(near(ni() ^ no(), ep() ^ em()));
  const MV E = ni() ^ no();
  CHECK(near(E * E, S(1)));              // the Minkowski plane squares to +1
  CHECK(near(ni() * no(), S(-1) + E));   // geometric = inner + outer
  CHECK(near(no() * ni(), S(-1) - E));
}

TEST_CASE("geometric product is associative and distributive on random multivectors", "[oracle][laws]") {
  Rng rng(1);
  for (int t = 0; t < 25; ++t) {
    const MV a = rng.multivector(), b = rng.multivector(), c = rng.multivector();
    INFO("trial " << t);
    CHECK(near((a * b) * c, a * (b * c), 1e3));
    CHECK(near(a * (b + c), a * b + a * c, 1e2));
    CHECK(near((a + b) * c, a * c + b * c, 1e2));
    CHECK(near((a ^ b) ^ c, a ^ (b ^ c), 1e3));
    CHECK(near(2.5 * (a * b), a * (2.5 * b), 1e2));
  }
  // A wrong sign anywhere would break associativity on basis blades too; check all triples exactly.
  for (unsigned i = 0; i < 32; ++i)
    for (unsigned j = 0; j < 32; ++j)
      for (unsigned k = 0; k < 32; k += 3) {
        const MV A = MV::blade(i), B = MV::blade(j), C = MV::blade(k);
        REQUIRE(oracle::max_abs_diff((A * B) * C, A * (B * C)) == 0.0);
      }
}

TEST_CASE("reverse is an anti-automorphism, involution an automorphism", "[oracle][laws]") {
  Rng rng(2);
  for (int t = 0; t < 25; ++t) {
    const MV a = rng.multivector(), b = rng.multivector();
    CHECK(near(reverse(a * b), reverse(b) * reverse(a), 1e2));
    CHECK(near(involute(a * b), involute(a) * involute(b), 1e2));
    CHECK(near(conjugate(a * b), conjugate(b) * conjugate(a), 1e2));
    CHECK(near(conjugate(a), reverse(involute(a))));
    CHECK(near(reverse(reverse(a)), a));
  }
  // Signs per grade 0..5 written out by hand: reverse + + - - + +, involute + - + - + -.
  const int rev[6] = {1, 1, -1, -1, 1, 1}, inv[6] = {1, -1, 1, -1, 1, -1};
  for (unsigned i = 0; i < 32; ++i) {
    const int g = oracle::grade_of(i);
    CHECK(reverse(MV::blade(i))[i] == rev[g]);
    CHECK(involute(MV::blade(i))[i] == inv[g]);
    CHECK(conjugate(MV::blade(i))[i] == rev[g] * inv[g]);
  }
}

TEST_CASE("grades, contractions and Gaalop's inner product", "[oracle][laws]") {
  Rng rng(3);
  for (int t = 0; t < 20; ++t) {
    const MV A = rng.multivector();
    MV sum;
    for (int k = 0; k <= 5; ++k) sum += grade(A, k);
    CHECK(near(sum, A));
    CHECK(near(grade(A, 6), S(0)));

    // For a vector a and any B: aB = a_|B + a^B, and Ba = B|_a + B^a.
    const MV a = grade(rng.multivector(), 1);
    CHECK(near(a * A, lc(a, A) + (a ^ A), 10));
    CHECK(near(A * a, rc(A, a) + (A ^ a), 10));
    // Gaalop's '.' agrees with the left contraction when the left grade is smaller, is zero on scalars.
    CHECK(near(inner(a, A), lc(a, grade(A, 1) + grade(A, 2) + grade(A, 3) + grade(A, 4) + grade(A, 5)), 10));
    CHECK(near(inner(S(2.0), A), S(0)));
    CHECK(near(inner(A, S(2.0)), S(0)));
    // For a 3-blade . vector it is the right contraction (grade 2), unlike lc which gives 0.
    const MV B3 = grade(rng.multivector(), 3);
    CHECK(near(inner(B3, a), rc(B3, a), 10));
    CHECK(near(lc(B3, a), S(0)));
    // Symmetric scalar product of vectors.
    const MV b = grade(rng.multivector(), 1);
    CHECK(near(inner(a, b), S(0.5) * (a * b + b * a), 10));
  }
  CHECK_THROWS_AS(MV::blade(32), std::out_of_range);
}

TEST_CASE("up(x).up(y) = -1/2 |x - y|^2, points are null with weight 1, down inverts up", "[oracle][facts]") {
  Rng rng(4);
  for (int t = 0; t < 100; ++t) {
    const P3 x = rng.vec3(), y = rng.vec3();
    const MV X = oracle::up(x[0], x[1], x[2]), Y = oracle::up(y[0], y[1], y[2]);
    const double d2 = (x[0] - y[0]) * (x[0] - y[0]) + (x[1] - y[1]) * (x[1] - y[1]) + (x[2] - y[2]) * (x[2] - y[2]);
    CHECK(scalar_part(inner(X, Y)) == Approx(-0.5 * d2).epsilon(1e-12).margin(1e-10));
    CHECK(near(X * X, S(0), 100, 1e-13));
    CHECK(scalar_part(inner(X, ni())) == Approx(-1.0));
    CHECK(near3(oracle::down(X), x));
    CHECK(near3(oracle::down(3.5 * X), x));
  }
  CHECK_THROWS_AS(oracle::down(ni()), std::domain_error);
}

TEST_CASE("translator 1 - 1/2 t einf moves points as glm::translate does", "[oracle][glm]") {
  Rng rng(5);
  for (int t = 0; t < 200; ++t) {
    const P3 tr = rng.vec3(), x = rng.vec3();
    const glm::dvec4 g = glm::translate(glm::dmat4(1.0), to_glm(tr)) * glm::dvec4(to_glm(x), 1.0);
    const P3 got = oracle::apply_to_point(oracle::translator(tr[0], tr[1], tr[2]), x);
    INFO("t=" << str3(tr) << " x=" << str3(x) << " got " << str3(got));
    CHECK(near3(got, {g.x, g.y, g.z}));
  }
  // The facts file writes the translator as 1 - 1/2 t einf with t einf the geometric product.
  CHECK(near(oracle::translator(1.0, 2.0, 3.0), S(1) - 0.5 * ((e1() + 2.0 * e2() + 3.0 * e3()) * ni())));
}

TEST_CASE("rotor cos(phi/2) - sin(phi/2)(n1 e23 + n2 e31 + n3 e12) rotates as glm::angleAxis does", "[oracle][glm]") {
  Rng rng(6);
  for (int t = 0; t < 200; ++t) {
    const P3 n = rng.unit3(), x = rng.vec3();
    const double phi = rng.uniform(-2 * std::numbers::pi, 2 * std::numbers::pi);
    const glm::dvec3 g = glm::angleAxis(phi, to_glm(n)) * to_glm(x);
    const P3 got = oracle::apply_to_point(oracle::rotor(n[0], n[1], n[2], phi), x);
    INFO("n=" << str3(n) << " phi=" << phi << " x=" << str3(x) << " got " << str3(got));
    CHECK(near3(got, from_glm(g)));
  }
  // Right-handed: a quarter turn about e3 takes e1 to e2.
  CHECK(near3(oracle::apply_to_point(oracle::rotor(0.0, 0.0, 1.0, std::numbers::pi / 2), {1.0, 0.0, 0.0}), {0, 1, 0}));
}

TEST_CASE("dilator 1 + (1-s)/(1+s) einf^e0 scales as glm::scale does", "[oracle][glm]") {
  // The unnormalized dilator loses precision as s grows: the weight (1+k)^2 shrinks like 4/s^2 while
  // rounding from the |x|^2/2 einf term of X stays, so the relative error grows like eps |x|^2 s^2.
  // Scales 0.22 .. 4.5 meet 1e-12; larger ones (to 12) are checked at 1e-11.
  Rng rng(7);
  for (int t = 0; t < 300; ++t) {
    const bool wide = t >= 200;
    const double s = std::exp(wide ? rng.uniform(-2.5, 2.5) : rng.uniform(-1.5, 1.5));
    const P3 x = rng.vec3();
    const glm::dvec4 g = glm::scale(glm::dmat4(1.0), glm::dvec3(s)) * glm::dvec4(to_glm(x), 1.0);
    const MV D = oracle::dilator(s);
    const P3 got = oracle::apply_to_point(D, x);
    INFO("s=" << s << " x=" << str3(x) << " got " << str3(got));
    CHECK(near3(got, {g.x, g.y, g.z}, wide ? 1e-11 : kRel));
    // Not normalized: D~D = 1 - ((1-s)/(1+s))^2.
    const double k = (1 - s) / (1 + s);
    CHECK(near(D * reverse(D), S(1 - k * k)));
  }
}

TEST_CASE("motor T R D moves points as glm translate * rotate * scale", "[oracle][glm]") {
  Rng rng(8);
  for (int t = 0; t < 100; ++t) {
    const P3 tr = rng.vec3(), n = rng.unit3(), x = rng.vec3();
    const double phi = rng.uniform(-std::numbers::pi, std::numbers::pi), s = std::exp(rng.uniform(-1.5, 1.5));
    const MV M = oracle::translator(tr[0], tr[1], tr[2]) * oracle::rotor(n[0], n[1], n[2], phi) * oracle::dilator(s);
    const glm::dmat4 G = glm::translate(glm::dmat4(1.0), to_glm(tr)) * glm::mat4_cast(glm::angleAxis(phi, to_glm(n))) *
                         glm::scale(glm::dmat4(1.0), glm::dvec3(s));
    const glm::dvec4 g = G * glm::dvec4(to_glm(x), 1.0);
    const P3 got = oracle::apply_to_point(M, x);
    INFO("t=" << str3(tr) << " n=" << str3(n) << " phi=" << phi << " s=" << s << " x=" << str3(x));
    CHECK(near3(got, {g.x, g.y, g.z}));
  }
}

TEST_CASE("the rotation plane *(n ^ up(0) ^ einf) is n1 e23 + n2 e31 + n3 e12", "[oracle][facts]") {
  Rng rng(9);
  for (int t = 0; t < 20; ++t) {
    const P3 n = rng.unit3();
    const MV nv = n[0] * e1() + n[1] * e2() + n[2] * e3();
    const MV plane = oracle::dual(nv ^ oracle::up(0.0, 0.0, 0.0) ^ ni());
    CHECK(near(plane, n[0] * (e2() * e3()) + n[1] * (e3() * e1()) + n[2] * (e1() * e2())));
  }
}

TEST_CASE("versor times its inverse is 1", "[oracle][versor]") {
  Rng rng(10);
  for (int t = 0; t < 50; ++t) {
    const P3 tr = rng.vec3(), n = rng.unit3();
    const double phi = rng.uniform(-3, 3), s = std::exp(rng.uniform(-1.5, 1.5));
    const MV M = oracle::translator(tr[0], tr[1], tr[2]) * oracle::rotor(n[0], n[1], n[2], phi) * oracle::dilator(s);
    CHECK(near(M * oracle::versor_inverse(M), S(1), 1e2));
    CHECK(near(oracle::versor_inverse(M) * M, S(1), 1e2));
    // A product of three random (non-null) vectors is a versor too.
    const MV V = grade(rng.multivector(), 1) * grade(rng.multivector(), 1) * grade(rng.multivector(), 1);
    const MV Vi = oracle::versor_inverse(V);
    const double scale = oracle::norm1(V) * oracle::norm1(Vi);
    INFO("V=" << str(V));
    CHECK(near(V * Vi, S(1), scale));
  }
  // Not versors: V~V has a non-scalar part, or vanishes.
  CHECK_THROWS_AS(oracle::versor_inverse(S(1) + e1() + (e1() ^ e2())), std::domain_error);
  CHECK_THROWS_AS(oracle::versor_inverse(ni()), std::domain_error);
  CHECK_THROWS_AS(oracle::versor_inverse(MV{}), std::domain_error);
}

TEST_CASE("exp by series matches closed forms", "[oracle][exp]") {
  Rng rng(11);
  for (int t = 0; t < 50; ++t) {
    // Euclidean bivector B = theta * unit plane, plane^2 = -1: exp(B) = cos(theta) + sin(theta) plane.
    const P3 n = rng.unit3();
    const double theta = rng.uniform(-2 * std::numbers::pi, 2 * std::numbers::pi);
    const MV plane = n[0] * (e2() * e3()) + n[1] * (e3() * e1()) + n[2] * (e1() * e2());
    REQUIRE(near(plane * plane, S(-1)));
    CHECK(near(oracle::exp(theta * plane), S(std::cos(theta)) + std::sin(theta) * plane, 1, 1e-13));
    // The facts' rotor is exp(-phi/2 plane).
    CHECK(near(oracle::exp((-theta / 2) * plane), oracle::rotor(n[0], n[1], n[2], theta), 1, 1e-13));
    // Nilpotent: exp(-1/2 t einf) = 1 - 1/2 t einf exactly.
    const P3 tr = rng.vec3();
    const MV tinf = (tr[0] * e1() + tr[1] * e2() + tr[2] * e3()) * ni();
    CHECK(near(oracle::exp(-0.5 * tinf), oracle::translator(tr[0], tr[1], tr[2]), 10));
    // Hyperbolic: E^2 = +1 so exp(a E) = cosh a + sinh a E.
    const double a = rng.uniform(-2, 2);
    const MV E = ni() ^ no();
    CHECK(near(oracle::exp(a * E), S(std::cosh(a)) + std::sinh(a) * E, 1, 1e-13));
  }
  // exp(A) exp(-A) = 1 for a general multivector (A commutes with -A).
  const MV A = rng.multivector(-0.5, 0.5);
  CHECK(near(oracle::exp(A) * oracle::exp(-A), S(1), 1, 1e-12));
  CHECK(near(oracle::exp(MV{}), S(1)));
}

TEST_CASE("scalars of other arithmetic types mix with MV<double>", "[oracle][types]") {
  CHECK(near(2 * e1(), e1() + e1()));
  CHECK(near(e1() * 0.5f, e1() / 2));
  CHECK(near(oracle::up(std::array<double, 3>{1, 2, 3}), oracle::up(1.0, 2.0, 3.0)));
}

TEST_CASE("pseudoscalar and dual", "[oracle][facts]") {
  const MV I = oracle::pseudoscalar<double>();
  CHECK(near(I, MV::blade(0b11111)));  // e1 e2 e3 ep em is the bitmap-31 blade with coefficient +1
  CHECK(near(I, e1() ^ e2() ^ e3() ^ ni() ^ no()));
  CHECK(near(I, nb("e1^e2^e3^einf^e0")));
  CHECK(near(I * I, S(-1)));
  // Hand computation: *e1 = e1 (-e1 e2 e3 ep em) = -e2 e3 ep em = -(e2^e3^einf^e0).
  const MV d = oracle::dual(e1());
  CHECK(near(d, -MV::blade(0b11110)));
  CHECK(near(d, -nb("e2^e3^einf^e0")));
  // Dualizing twice multiplies by I^2 = -1.
  Rng rng(12);
  const MV A = rng.multivector();
  CHECK(near(oracle::dual(oracle::dual(A)), -A));
}

TEST_CASE("null_blade builds named blades and rejects bad names", "[oracle][null]") {
  CHECK(near(nb("1"), S(1)));
  CHECK(near(nb("einf"), em() + ep()));
  CHECK(near(nb("e0"), 0.5 * (em() - ep())));
  CHECK(near(nb("e0^einf"), -nb("einf^e0")));
  CHECK(near(nb("einf^e0"), ep() ^ em()));
  CHECK(near(nb("e2^e1"), -(e1() * e2())));
  CHECK(near(nb(" e1 ^ einf "), e1() ^ ni()));
  for (const char* bad : {"", "e4", "e1^e1", "e1^", "^e1", "einf^^e0", "E1", "e12", "einf^e0^einf", "0"}) {
    INFO("name '" << bad << "'");
    CHECK_THROWS_AS(nb(bad), std::invalid_argument);
  }
}

TEST_CASE("null basis: Gaalop order and round trip", "[oracle][null]") {
  const auto& names = oracle::null_blade_names();
  // The order stated in the facts file: 1; vectors; 2-blades lexicographic in e1 < e2 < e3 < einf < e0; ...
  const std::vector<std::string> head = {"1",      "e1",     "e2",     "e3",      "einf",   "e0",
                                         "e1^e2",  "e1^e3",  "e1^einf", "e1^e0",  "e2^e3",  "e2^einf",
                                         "e2^e0",  "e3^einf", "e3^e0", "einf^e0", "e1^e2^e3"};
  for (std::size_t i = 0; i < head.size(); ++i) CHECK(names[i] == head[i]);
  CHECK(names[25] == "e3^einf^e0");
  CHECK(names[26] == "e1^e2^e3^einf");
  CHECK(names[30] == "e2^e3^einf^e0");
  CHECK(names[31] == "e1^e2^e3^einf^e0");
  CHECK(std::set<std::string>(names.begin(), names.end()).size() == 32);

  for (unsigned k = 0; k < 32; ++k) {
    const auto c = oracle::to_null_basis(nb(names[k]));
    for (unsigned j = 0; j < 32; ++j) CHECK(std::abs(c[j] - (j == k ? 1.0 : 0.0)) < 1e-14);
  }
  Rng rng(13);
  for (int t = 0; t < 10; ++t) {
    const MV A = rng.multivector();
    CHECK(near(oracle::from_null_basis(oracle::to_null_basis(A)), A, 1, 1e-13));
  }
}

TEST_CASE("motor T R D has exactly the 12 null-basis blades of the facts file", "[oracle][facts]") {
  const std::set<std::string> expected = {"1",       "e1^e2",   "e1^e3",   "e2^e3",
                                          "e1^einf", "e2^einf", "e3^einf", "einf^e0",
                                          "e1^e2^einf^e0", "e1^e3^einf^e0", "e2^e3^einf^e0", "e1^e2^e3^einf"};
  Rng rng(14);
  for (int t = 0; t < 30; ++t) {
    const P3 tr = rng.vec3(), n = rng.unit3();
    const double phi = rng.uniform(0.1, 3.0), s = std::exp(rng.uniform(-1.5, 1.5));
    const MV M = oracle::translator(tr[0], tr[1], tr[2]) * oracle::rotor(n[0], n[1], n[2], phi) * oracle::dilator(s);
    const auto c = oracle::to_null_basis(M);
    const double scale = *std::max_element(c.begin(), c.end(), [](double a, double b) { return std::abs(a) < std::abs(b); });
    std::set<std::string> nonzero;
    for (unsigned k = 0; k < 32; ++k)
      if (std::abs(c[k]) > 1e-12 * std::abs(scale)) nonzero.insert(oracle::null_blade_names()[k]);
    INFO("M=" << str(M));
    CHECK(nonzero == expected);
  }
}

TEST_CASE("the oracle works for other scalar types", "[oracle][types]") {
  using MF = oracle::MV<float>;
  const MF X = oracle::up(1.0f, 2.0f, 3.0f), Y = oracle::up(4.0f, 6.0f, 3.0f);
  CHECK(scalar_part(inner(X, Y)) == Approx(-12.5f));
  const P3 x{0.3, -0.7, 1.9};
  using ML = oracle::MV<long double>;
  const ML R = oracle::rotor<long double>(0.0L, 0.0L, 1.0L, std::numbers::pi_v<long double> / 2);
  const auto p = oracle::apply_to_point(R, std::array<long double, 3>{(long double)x[0], (long double)x[1], (long double)x[2]});
  CHECK(std::abs(p[0] - (long double)(-x[1])) < 1e-17L);
  CHECK(std::abs(p[1] - (long double)x[0]) < 1e-17L);
  CHECK(std::abs(p[2] - (long double)x[2]) < 1e-17L);
}
