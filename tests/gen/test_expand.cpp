// The expander: scripts under tests/gen/scripts expanded to Kernels, evaluated numerically (values
// substituted into each other in order) and compared with the independent oracle or with plain geometry;
// the Kernel's structure; and every expander diagnostic.
#include <catch2/catch.hpp>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <string>

#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "oracle/multivector.hpp"
#include "symbolic/node_cache.hpp"
#include "symbolic/probes.hpp"

using namespace cgagen;
using OMV = oracle::MV<double>;
using Coeffs = std::array<double, algebra::kBladeCount>;  // null-basis coefficients, Gaalop order
using Vec3 = std::array<double, 3>;

namespace {

Kernel expand_text(const std::string& text, const std::string& path = "t.clu") {
  front::SourceFile file(path, text);
  return expand(front::parse(file), "t");
}

Kernel expand_script(const std::string& name) {
  auto file = front::SourceFile::load(std::string(CGA_TEST_SCRIPTS) + "/" + name);
  return expand(front::parse(file), name.substr(0, name.find('.')));
}

// The formatted diagnostic of the first error in `text` ("" when it expands fine).
std::string diagnostic(const std::string& text) {
  front::SourceFile file("t.clu", text);
  try {
    expand(front::parse(file), "t");
  } catch (const front::CompileError& e) {
    return front::format_diagnostic(file, e.loc(), e.what());
  }
  return "";
}

double to_double(const GiNaC::ex& e) {
  GiNaC::ex v = GiNaC::evalf(e);
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real()) {
    std::ostringstream os;
    os << e;
    FAIL("not a real number after substitution: " << os.str());
  }
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

// Evaluates every value of the kernel in script order and returns each output's coefficients (blades
// not in the output are 0). Every input must be given.
std::map<std::string, Coeffs> evaluate(const Kernel& k, const std::map<std::string, double>& scalars,
                                       const std::map<std::string, Coeffs>& multivectors = {}) {
  GiNaC::exmap subs;
  for (const auto& in : k.inputs) {
    if (in.is_multivector) {
      INFO("multivector input " << in.name);
      REQUIRE(multivectors.count(in.name));
      for (size_t i = 0; i < in.blades.size(); ++i) subs[in.symbols[i]] = multivectors.at(in.name)[in.blades[i]];
    } else {
      INFO("scalar input " << in.name);
      REQUIRE(scalars.count(in.name));
      subs[in.symbols.at(0)] = scalars.at(in.name);
    }
  }
  std::vector<Coeffs> values;
  for (const auto& v : k.values) {
    Coeffs c{};
    for (size_t i = 0; i < v.blades.size(); ++i) {
      c[v.blades[i]] = to_double(v.coeffs[i].subs(subs));
      subs[v.symbols[i]] = c[v.blades[i]];
    }
    values.push_back(c);
  }
  std::map<std::string, Coeffs> out;
  for (const auto& o : k.outputs) {
    Coeffs c{};
    for (auto b : o.blades) c[b] = values.at(o.value)[b];
    out[o.name] = c;
  }
  return out;
}

Coeffs null_coeffs(const OMV& m) { return oracle::to_null_basis(m); }

// Running maximum that keeps a NaN (std::max(d, NaN) is d, and a NaN would pass every bound).
double nan_max(double a, double b) { return std::isnan(a) || std::isnan(b) ? std::nan("") : std::max(a, b); }

double max_diff(const Coeffs& a, const Coeffs& b) {
  double d = 0;
  for (int i = 0; i < algebra::kBladeCount; ++i) d = nan_max(d, std::abs(a[i] - b[i]));
  return d;
}

double max_abs(const Coeffs& a) {
  double d = 0;
  for (double x : a) d = nan_max(d, std::abs(x));
  return d;
}

Coeffs only(const Coeffs& c, std::initializer_list<int> blades) {
  Coeffs r{};
  for (int b : blades) r[b] = c[b];
  return r;
}

// Rotates p by angle about the unit axis n, right-handed (Rodrigues' formula, as GLM's rotate).
Vec3 rotate(const Vec3& p, const Vec3& n, double angle) {
  const double c = std::cos(angle), s = std::sin(angle);
  const double dot = n[0] * p[0] + n[1] * p[1] + n[2] * p[2];
  const Vec3 cross = {n[1] * p[2] - n[2] * p[1], n[2] * p[0] - n[0] * p[2], n[0] * p[1] - n[1] * p[0]};
  Vec3 r;
  for (int i = 0; i < 3; ++i) r[i] = p[i] * c + cross[i] * s + n[i] * dot * (1 - c);
  return r;
}

struct Rng {
  std::mt19937 gen{20240611};
  double operator()(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  Vec3 unit() {
    for (;;) {
      Vec3 v = {(*this)(-1, 1), (*this)(-1, 1), (*this)(-1, 1)};
      double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
      if (n > 0.2 && n < 1) return {v[0] / n, v[1] / n, v[2] / n};
    }
  }
};

OMV vec(const Vec3& v) { return v[0] * oracle::e1<double>() + v[1] * oracle::e2<double>() + v[2] * oracle::e3<double>(); }
OMV one() { return OMV::scalar(1.0); }

// The weight-normalized Euclidean point of coefficients on e1 e2 e3 and e0.
Vec3 point_of(const Coeffs& c) { return {c[1] / c[5], c[2] / c[5], c[3] / c[5]}; }

double dist(const Vec3& a, const Vec3& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

}  // namespace

// ---- scripts against the oracle and geometry --------------------------------------------------------

TEST_CASE("paper A.1: the expanded script equals the oracle doing the same steps") {
  const Kernel k = expand_script("paper_a1.clu");
  REQUIRE(k.outputs.size() == 1);
  CHECK(k.outputs[0].blades == std::vector<algebra::BladeIndex>{1, 2, 3, 5});
  Rng rng;
  for (int trial = 0; trial < 20; ++trial) {
    std::map<std::string, double> in;
    const Vec3 t1 = {rng(-2, 2), rng(-2, 2), rng(-2, 2)}, t2 = {rng(-2, 2), rng(-2, 2), rng(-2, 2)};
    const Vec3 a1 = rng.unit(), a2 = rng.unit(), p = {rng(-2, 2), rng(-2, 2), rng(-2, 2)};
    const double ang1 = rng(-1, 1), ang2 = rng(-1, 1), d1 = rng(0.5, 2), d2 = rng(0.5, 2), alpha = rng(0, 1);
    in = {{"transX", t1[0]}, {"transY", t1[1]}, {"transZ", t1[2]}, {"trans2X", t2[0]}, {"trans2Y", t2[1]},
          {"trans2Z", t2[2]}, {"axis1X", a1[0]}, {"axis1Y", a1[1]}, {"axis1Z", a1[2]}, {"axis2X", a2[0]},
          {"axis2Y", a2[1]}, {"axis2Z", a2[2]}, {"angle1", ang1}, {"angle2", ang2}, {"d1", d1}, {"d2", d2},
          {"alpha", alpha}, {"X", p[0]}, {"Y", p[1]}, {"Z", p[2]}};
    const auto out = evaluate(k, in);

    const OMV einf = oracle::einf<double>(), e0 = oracle::e0<double>();
    auto taylor = [](const OMV& b) { return one() + b + b * b / 2.0 + b * b * b / 6.0 + b * b * b * b / 24.0; };
    auto motor = [&](const Vec3& t, const Vec3& axis, double angle) {
      OMV T = one() - 0.5 * (vec(t) ^ einf);
      OMV plane = oracle::dual(oracle::up(axis[0], axis[1], axis[2]) ^ oracle::up(0.0, 0.0, 0.0) ^ einf);
      return T * taylor((-angle / 2) * plane);
    };
    auto dilator = [&](double d) { return one() + ((1 - d) / (1 + d)) * (einf ^ e0); };
    OMV tr = (1 - alpha) * motor(t1, a1, ang1) + alpha * motor(t2, a2, ang2);
    OMV dl = dilator(d1) + (dilator(d2) - dilator(d1)) * alpha;
    OMV f = tr * dl;
    OMV v = f * oracle::up(p[0], p[1], p[2]) * oracle::reverse(f);
    const Coeffs want = only(null_coeffs(v), {1, 2, 3, 5});
    CHECK(max_diff(out.at("vertexPos"), want) < 1e-9 * (1 + max_abs(want)));
  }
}

TEST_CASE("paper motor with the exact exp moves points like GLM translate * rotate * scale") {
  const Kernel k = expand_script("paper_motor.clu");
  Rng rng;
  for (int trial = 0; trial < 20; ++trial) {
    const Vec3 t = {rng(-3, 3), rng(-3, 3), rng(-3, 3)}, n = rng.unit(), p = {rng(-3, 3), rng(-3, 3), rng(-3, 3)};
    const double angle = rng(-3, 3), d = rng(0.3, 3);
    const auto out = evaluate(k, {{"tx", t[0]}, {"ty", t[1]}, {"tz", t[2]}, {"ax", n[0]}, {"ay", n[1]}, {"az", n[2]},
                                  {"angle", angle}, {"d", d}, {"X", p[0]}, {"Y", p[1]}, {"Z", p[2]}});
    Vec3 want = rotate({d * p[0], d * p[1], d * p[2]}, n, angle);
    for (int i = 0; i < 3; ++i) want[i] += t[i];
    CHECK(dist(point_of(out.at("P")), want) < 1e-9);
  }
}

TEST_CASE("translator inverse: (~T)/(T*~T) and 1/T both undo T") {
  const Kernel k = expand_script("translator_inverse.clu");
  Rng rng;
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3 t = {rng(-3, 3), rng(-3, 3), rng(-3, 3)}, p = {rng(-3, 3), rng(-3, 3), rng(-3, 3)};
    const auto out =
        evaluate(k, {{"tx", t[0]}, {"ty", t[1]}, {"tz", t[2]}, {"x", p[0]}, {"y", p[1]}, {"z", p[2]}});
    const Coeffs moved = null_coeffs(oracle::up(p[0] + t[0], p[1] + t[1], p[2] + t[2]));
    const Coeffs orig = null_coeffs(oracle::up(p[0], p[1], p[2]));
    CHECK(max_diff(out.at("moved"), moved) < 1e-9);
    CHECK(max_diff(out.at("back"), orig) < 1e-9);
    CHECK(max_diff(out.at("back2"), orig) < 1e-9);
    CHECK(max_diff(out.at("one"), null_coeffs(one())) < 1e-12);
    CHECK(max_diff(out.at("one2"), null_coeffs(one())) < 1e-12);
  }
}

TEST_CASE("circle through three points gives the circumcentre and radius") {
  const Kernel k = expand_script("circle3.clu");
  // mtmp = c*einf*c is a vector only because c is a 2-blade; the expander finds the grade-5 blade
  // identically zero through the value chain, so m carries just the point's blades.
  REQUIRE(k.outputs.size() == 2);
  CHECK(k.values.at(k.outputs[0].value).blades == std::vector<algebra::BladeIndex>{1, 2, 3, 4, 5});
  Rng rng;
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3 a = {rng(-2, 2), rng(-2, 2), rng(-2, 2)}, b = {rng(-2, 2), rng(-2, 2), rng(-2, 2)},
               c = {rng(-2, 2), rng(-2, 2), rng(-2, 2)};
    const auto out = evaluate(k, {{"x1", a[0]}, {"y1", a[1]}, {"z1", a[2]}, {"x2", b[0]}, {"y2", b[1]}, {"z2", b[2]},
                                  {"x3", c[0]}, {"y3", c[1]}, {"z3", c[2]}});
    // Circumcentre: a + (|u|^2 (v x w) + |v|^2 (w x u)) / (2 |w|^2), u = b - a, v = c - a, w = u x v.
    auto sub = [](Vec3 p, Vec3 q) { return Vec3{p[0] - q[0], p[1] - q[1], p[2] - q[2]}; };
    auto cross = [](Vec3 p, Vec3 q) {
      return Vec3{p[1] * q[2] - p[2] * q[1], p[2] * q[0] - p[0] * q[2], p[0] * q[1] - p[1] * q[0]};
    };
    auto dot = [](Vec3 p, Vec3 q) { return p[0] * q[0] + p[1] * q[1] + p[2] * q[2]; };
    const Vec3 u = sub(b, a), v = sub(c, a), w = cross(u, v);
    const Vec3 vw = cross(v, w), wu = cross(w, u);
    Vec3 centre;
    for (int i = 0; i < 3; ++i) centre[i] = a[i] + (dot(u, u) * vw[i] + dot(v, v) * wu[i]) / (2 * dot(w, w));
    const Coeffs& m = out.at("m");
    CHECK(m[5] == Approx(1.0).margin(1e-9));  // a normalized point
    CHECK(dist({m[1], m[2], m[3]}, centre) < 1e-7);
    CHECK(out.at("r")[0] == Approx(dist(centre, a)).epsilon(1e-9));
  }
}

TEST_CASE("plane through three points: plane . X is the oracle's value and a scaled signed distance") {
  const Kernel k = expand_script("plane_distance.clu");
  Rng rng;
  for (int trial = 0; trial < 10; ++trial) {
    std::array<Vec3, 4> p;
    for (auto& q : p) q = {rng(-2, 2), rng(-2, 2), rng(-2, 2)};
    const auto out = evaluate(k, {{"p1x", p[0][0]}, {"p1y", p[0][1]}, {"p1z", p[0][2]}, {"p2x", p[1][0]},
                                  {"p2y", p[1][1]}, {"p2z", p[1][2]}, {"p3x", p[2][0]}, {"p3y", p[2][1]},
                                  {"p3z", p[2][2]}, {"x", p[3][0]}, {"y", p[3][1]}, {"z", p[3][2]}});
    auto up = [](const Vec3& q) { return oracle::up(q[0], q[1], q[2]); };
    const OMV plane = oracle::dual(up(p[0]) ^ up(p[1]) ^ up(p[2]) ^ oracle::einf<double>());
    CHECK(max_diff(out.at("plane"), null_coeffs(plane)) < 1e-9);
    const double d = out.at("d")[0];
    CHECK(d == Approx(oracle::scalar_part(oracle::inner(plane, up(p[3])))).epsilon(1e-9));
    // |d| / |plane normal| is the Euclidean distance of X from the plane.
    const Coeffs& pl = out.at("plane");
    const double normal = std::sqrt(pl[1] * pl[1] + pl[2] * pl[2] + pl[3] * pl[3]);
    Vec3 u, v;
    for (int i = 0; i < 3; ++i) u[i] = p[1][i] - p[0][i], v[i] = p[2][i] - p[0][i];
    const Vec3 w = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    const double wn = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    double geo = 0;
    for (int i = 0; i < 3; ++i) geo += (p[3][i] - p[0][i]) * w[i] / wn;
    CHECK(std::abs(d) / normal == Approx(std::abs(geo)).epsilon(1e-9));
  }
}

TEST_CASE("RotorN3, TranslatorN3, createPoint, multivector inputs and range pragmas") {
  const Kernel k = expand_script("rotor_n3.clu");
  REQUIRE(k.inputs.size() >= 2);
  CHECK(k.inputs[0].name == "M");
  CHECK(k.inputs[0].is_multivector);
  CHECK(k.inputs[0].blades == std::vector<algebra::BladeIndex>{0, 6, 7, 10});
  CHECK(k.inputs[0].symbols.at(1).get_name() == "M_e12");
  CHECK(k.inputs[1].name == "nx");
  REQUIRE(k.ranges.size() == 1);
  CHECK(k.ranges[0].name == "angle");
  CHECK(k.ranges[0].min == 0.0);
  CHECK(k.ranges[0].max == 6.3);
  Rng rng;
  for (int trial = 0; trial < 10; ++trial) {
    const Vec3 n = {rng(-2, 2), rng(-2, 2), rng(-2, 2)}, t = {rng(-2, 2), rng(-2, 2), rng(-2, 2)},
               p = {rng(-2, 2), rng(-2, 2), rng(-2, 2)};
    const double angle = rng(0, 6.3);
    Coeffs m{};
    for (int b : {0, 6, 7, 10}) m[b] = rng(-1, 1);
    const auto out = evaluate(k,
                              {{"nx", n[0]}, {"ny", n[1]}, {"nz", n[2]}, {"angle", angle}, {"tx", t[0]},
                               {"ty", t[1]}, {"tz", t[2]}, {"x", p[0]}, {"y", p[1]}, {"z", p[2]}},
                              {{"M", m}});
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    Vec3 want = rotate(p, {n[0] / len, n[1] / len, n[2] / len}, angle);
    for (int i = 0; i < 3; ++i) want[i] += t[i];
    CHECK(dist(point_of(out.at("P")), want) < 1e-9);
    // M*R against the oracle, with R = cos(a/2) - sin(a/2) (n1 e23 + n2 e31 + n3 e12)/|n|.
    const OMV e23 = oracle::e2<double>() * oracle::e3<double>(), e31 = oracle::e3<double>() * oracle::e1<double>(),
              e12 = oracle::e1<double>() * oracle::e2<double>();
    const OMV R = std::cos(angle / 2) * one() - (std::sin(angle / 2) / len) * (n[0] * e23 + n[1] * e31 + n[2] * e12);
    CHECK(max_diff(out.at("MR"), null_coeffs(oracle::from_null_basis(m) * R)) < 1e-9);
  }
}

// ---- semantics and kernel structure ------------------------------------------------------------------

TEST_CASE("values refer to earlier values by their symbols, inputs in order of first use") {
  const Kernel k = expand_text("a = y*e1 + x*e2;\n?b = a*a;\n");
  REQUIRE(k.inputs.size() == 2);
  CHECK(k.inputs[0].name == "y");
  CHECK(k.inputs[1].name == "x");
  REQUIRE(k.values.size() == 2);
  CHECK(k.values[0].blades == std::vector<algebra::BladeIndex>{1, 2});
  CHECK(k.values[0].symbols[0].get_name() == "a_e1");
  REQUIRE(k.values[1].blades == std::vector<algebra::BladeIndex>{0});
  const GiNaC::ex b = k.values[1].coeffs[0];
  CHECK((b - (GiNaC::pow(k.values[0].symbols[0], 2) + GiNaC::pow(k.values[0].symbols[1], 2))).expand().is_zero());
  CHECK(!b.has(k.inputs[0].symbols[0]));
  REQUIRE(k.outputs.size() == 1);
  CHECK(k.outputs[0].value == 1);
  CHECK(k.outputs[0].blades == std::vector<algebra::BladeIndex>{0});
}

TEST_CASE("an output refers to the last assignment, '!' assignments are never outputs") {
  const Kernel k = expand_text("?x = 1;\nx = x + e1;\n!y = 2;\n?x;\n?z = e2;\n");
  REQUIRE(k.values.size() == 4);
  REQUIRE(k.outputs.size() == 2);
  CHECK(k.outputs[0].name == "x");
  CHECK(k.outputs[0].value == 1);
  CHECK(k.outputs[0].blades == std::vector<algebra::BladeIndex>{0, 1});
  CHECK(k.outputs[1].name == "z");
  CHECK(k.outputs[1].value == 3);
  CHECK(k.values[1].symbols[0].get_name() != k.values[0].symbols[0].get_name());
  const Kernel v = expand_text(":w = e3;\n");
  REQUIRE(v.outputs.size() == 1);
  CHECK(v.outputs[0].name == "w");
}

TEST_CASE("numbers are exact rationals, ep and em are the orthonormal vectors") {
  const Kernel k = expand_text("?n = 0.5 + 1e-3 + 2.5E2 + .25;\n?p = ep*ep;\n?m = em*em;\n?pm = ep.em;\n");
  const auto out = [&](int i) { return k.values.at(k.outputs.at(i).value); };
  REQUIRE(out(0).coeffs.size() == 1);
  CHECK(out(0).coeffs[0].is_equal(GiNaC::numeric(1, 2) + GiNaC::numeric(1, 1000) + 250 + GiNaC::numeric(1, 4)));
  CHECK(out(1).coeffs.at(0).is_equal(1));
  CHECK(out(2).coeffs.at(0).is_equal(-1));
  CHECK(out(3).coeffs.empty());  // ep and em are orthogonal
}

TEST_CASE("macros: arguments evaluated in the caller, locals stay local, nested calls") {
  const Kernel k = expand_text(
      "Sq = { t = _P(1)*_P(1); t };\nTwice = { u = Sq(_P(1)) + Sq(_P(2)); 2*u };\n?r = Twice(x*e1, y*e2);\n?s = t;\n");
  // t inside Sq was local, so the top-level t is a free scalar input.
  REQUIRE(k.inputs.size() == 3);
  CHECK(k.inputs[2].name == "t");
  const auto out = evaluate(k, {{"x", 3}, {"y", 5}, {"t", 7}});
  CHECK(out.at("r")[0] == Approx(2 * (9 + 25)));
  CHECK(out.at("s")[0] == Approx(7));
}

TEST_CASE("exp closed forms match the oracle's series for rotation, translation and boost bivectors") {
  const Kernel k = expand_text("?r = exp(a*(e1^e2) + b*(e2^e3));\n?t = exp(c*(e1^einf));\n?h = exp(c*(einf^e0));\n?s = exp(a);\n");
  Rng rng;
  for (int trial = 0; trial < 10; ++trial) {
    const double a = rng(-2, 2), b = rng(-2, 2), c = rng(-2, 2);
    const auto out = evaluate(k, {{"a", a}, {"b", b}, {"c", c}});
    const OMV e1 = oracle::e1<double>(), e2 = oracle::e2<double>(), e3 = oracle::e3<double>();
    const OMV einf = oracle::einf<double>(), e0 = oracle::e0<double>();
    CHECK(max_diff(out.at("r"), null_coeffs(oracle::exp(a * (e1 ^ e2) + b * (e2 ^ e3)))) < 1e-9);
    CHECK(max_diff(out.at("t"), null_coeffs(oracle::exp(c * (e1 ^ einf)))) < 1e-9);
    CHECK(max_diff(out.at("h"), null_coeffs(oracle::exp(c * (einf ^ e0)))) < 1e-9);
    CHECK(out.at("s")[0] == Approx(std::exp(a)));
  }
}

TEST_CASE("scalar functions and division by a scalar") {
  const Kernel k = expand_text(
      "?f = abs(x) + sqrt(y) + sin(x) + cos(x) + tan(x) + asin(z) + acos(z) + atan(x) + atan2(x, y) + log(y);\n"
      "?g = (x*e1 + e2)/y;\n");
  const double x = -0.7, y = 1.9, z = 0.3;
  const auto out = evaluate(k, {{"x", x}, {"y", y}, {"z", z}});
  const double f = std::abs(x) + std::sqrt(y) + std::sin(x) + std::cos(x) + std::tan(x) + std::asin(z) +
                   std::acos(z) + std::atan(x) + std::atan2(x, y) + std::log(y);
  CHECK(out.at("f")[0] == Approx(f));
  CHECK(out.at("g")[1] == Approx(x / y));
  CHECK(out.at("g")[2] == Approx(1 / y));
}

// ---- diagnostics ---------------------------------------------------------------------------------------

TEST_CASE("expander diagnostics") {
  CHECK(diagnostic("?x = foo(1);\n") == "t.clu:1:6: error: unknown function 'foo'\n?x = foo(1);\n     ^\n");
  CHECK(diagnostic("?x = atan2(1);\n") == "t.clu:1:6: error: 'atan2' takes 2 arguments, got 1\n?x = atan2(1);\n     ^\n");
  CHECK(diagnostic("?x = VecN3(1, 2);\n") ==
        "t.clu:1:6: error: 'VecN3' takes 3 arguments, got 2\n?x = VecN3(1, 2);\n     ^\n");
  CHECK(diagnostic("A = { B(_P(1)) };\nB = { A(_P(1)) };\n?x = A(1);\n") ==
        "t.clu:2:7: error: recursive macro call 'A' -> 'B' -> 'A'\nB = { A(_P(1)) };\n      ^\n");
  CHECK(diagnostic("A = { A(1) };\n?x = A(1);\n") ==
        "t.clu:1:7: error: recursive macro call 'A' -> 'A'\nA = { A(1) };\n      ^\n");
  CHECK(diagnostic("A = { _P(2) };\n?x = A(1);\n") ==
        "t.clu:1:7: error: _P(2) out of range: macro 'A' was called with 1 argument\nA = { _P(2) };\n      ^\n");
  CHECK(diagnostic("?x = _P(1);\n") == "t.clu:1:6: error: _P(1) used outside a macro\n?x = _P(1);\n     ^\n");
  CHECK(diagnostic("x = 1;\n") == "t.clu:1:1: error: script has no outputs (mark one with ?name)\nx = 1;\n^\n");
  CHECK(diagnostic("?e1 = 1;\n") == "t.clu:1:2: error: cannot assign to basis vector 'e1'\n?e1 = 1;\n ^\n");
  CHECK(diagnostic("?x = sqrt(e1 + e2);\n") ==
        "t.clu:1:14: error: 'sqrt' takes a scalar argument, got a multivector with blades e1, e2\n"
        "?x = sqrt(e1 + e2);\n             ^\n");
  CHECK(diagnostic("?x = VecN3(1, e1, 2);\n") ==
        "t.clu:1:15: error: 'VecN3' takes scalar arguments, got a multivector with blades e1 as argument 2\n"
        "?x = VecN3(1, e1, 2);\n              ^\n");
  CHECK(diagnostic("?x = exp(e1);\n") ==
        "t.clu:1:10: error: 'exp' takes a scalar or a bivector, got a multivector with blades e1\n?x = exp(e1);\n"
        "         ^\n");
  // A screw (a rotation with a translation) and a rotation with a dilation have closed forms; two commuting
  // rotation planes (e1^e2 and e3^e+, e+ = e0 - einf/2) do not.
  CHECK(diagnostic("?x = exp(e1^e2 + e3^einf);\n").empty());
  CHECK(diagnostic("?x = exp(e1^e2 + einf^e0);\n").empty());
  CHECK(diagnostic("?x = exp(e1^e2 + e3^e0 - 0.5*(e3^einf));\n") ==
        "t.clu:1:24: error: 'exp' of a bivector B of two commuting planes is supported where one is a rotation and "
        "the other a boost (<B*B>_4 squared visibly <= 0, as a rotation with a dilation); write the product of the "
        "exps of its commuting parts\n?x = exp(e1^e2 + e3^e0 - 0.5*(e3^einf));\n                       ^\n");
  // A script that names another algebra than the one it is expanded in (a caller that did not select it).
  CHECK(diagnostic("#pragma algebra 3dpga\n?x = e1;\n") ==
        "t.clu:1:17: error: '#pragma algebra 3dpga': the script is being compiled in 'cga' (a conflicting --algebra "
        "or ALGEBRA?)\n#pragma algebra 3dpga\n                ^\n");
  CHECK(diagnostic("#pragma algebra cga\n?x = e1;\n").empty());
  // A square of no visible sign: rotation or boost is chosen at run time (test_exp_log).
  CHECK(diagnostic("?x = exp(a*(e1^e2) + b*(e1^em));\n").empty());
  CHECK(diagnostic("?x = e1/(1 + e1);\n") ==
        "t.clu:1:12: error: cannot divide by this multivector: it has no inverse (d*conjugate(d) = 0)\n"
        "?x = e1/(1 + e1);\n           ^\n");
  // A divisor whose extra blades vanish only once earlier values are inlined is still a scalar.
  CHECK(diagnostic("v = a*e1 + b*e2;\nw = v*v;\n?x = e1/w;\n").empty());
  CHECK(diagnostic("?x = e1/einf;\n") ==
        "t.clu:1:9: error: cannot divide by a null multivector (d*~d = 0)\n?x = e1/einf;\n        ^\n");
  CHECK(diagnostic("?x = e1/(y - y);\n") == "t.clu:1:12: error: division by zero\n?x = e1/(y - y);\n           ^\n");
  CHECK(diagnostic("?x = RotorN3(0, 0, 0, 1);\n").rfind("t.clu:1:6: error: cannot evaluate: ", 0) == 0);
  CHECK(diagnostic("A = { 1 };\n?x = A + 1;\n") ==
        "t.clu:2:6: error: 'A' is a macro; call it as A(...)\n?x = A + 1;\n     ^\n");
  CHECK(diagnostic("A = { 1 };\n?A = 2;\n") == "t.clu:2:2: error: cannot assign to 'A': it is a macro\n?A = 2;\n ^\n");
  CHECK(diagnostic("einf = { 1 };\n?x = 1;\n") ==
        "t.clu:1:1: error: cannot define a macro named 'einf'\neinf = { 1 };\n^\n");
  CHECK(diagnostic("?y;\n") == "t.clu:1:2: error: output 'y' is never assigned\n?y;\n ^\n");
  CHECK(diagnostic("?x = y;\n?y;\n") == "t.clu:2:2: error: output 'y' is never assigned\n?y;\n ^\n");
}

TEST_CASE("pragma diagnostics") {
  CHECK(diagnostic("#pragma foo x\n?x = 1;\n") ==
        "t.clu:1:9: error: unknown pragma 'foo' (expected output, input, range, uniform, normalized, versor, jacobian, algebra, onlyEvaluate, in2out, normalize, segments or triangles)\n#pragma foo x\n        ^\n");
  CHECK(diagnostic("#pragma output x e1 e5\n?x = 1;\n") ==
        "t.clu:1:21: error: unknown blade 'e5' in '#pragma output'\n#pragma output x e1 e5\n                    ^\n");
  CHECK(diagnostic("#pragma output x e0^einf\n?x = 1;\n") ==
        "t.clu:1:18: error: blade 'e0^einf' in '#pragma output' is not in canonical order; write 'einf^e0'\n"
        "#pragma output x e0^einf\n                 ^\n");
  CHECK(diagnostic("#pragma output x e1 e1\n?x = 1;\n") ==
        "t.clu:1:21: error: blade 'e1' is listed twice in '#pragma output'\n#pragma output x e1 e1\n"
        "                    ^\n");
  CHECK(diagnostic("#pragma output x\n?x = 1;\n") ==
        "t.clu:1:1: error: '#pragma output' needs a name and at least one blade\n#pragma output x\n^\n");
  CHECK(diagnostic("#pragma output\n?x = 1;\n") ==
        "t.clu:1:1: error: '#pragma output' needs a name and at least one blade\n#pragma output\n^\n");
  for (const char* p : {"#pragma\n?x = 1;\n", "#pragma input\n?x = 1;\n", "#pragma range\n?x = 1;\n",
                        "#pragma in2out\n?x = 1;\n", "#pragma onlyEvaluate\n?x = 1;\n"})
    CHECK(diagnostic(p).find("t.clu:1:1: error: ") == 0);
  CHECK(diagnostic("#pragma output y e1\n?x = 1;\n") ==
        "t.clu:1:16: error: '#pragma output' names 'y', which is not an output\n#pragma output y e1\n"
        "               ^\n");
  CHECK(diagnostic("#pragma range 0 <= x\n?x = 1;\n") ==
        "t.clu:1:1: error: '#pragma range' expects MIN <= NAME <= MAX\n#pragma range 0 <= x\n^\n");
  CHECK(diagnostic("#pragma range 2 <= x <= 1\n?y = x;\n") ==
        "t.clu:1:1: error: '#pragma range' for 'x' has MIN > MAX\n#pragma range 2 <= x <= 1\n^\n");
  CHECK(diagnostic("?y = M;\n#pragma input M e1\n") ==
        "t.clu:2:15: error: 'M' is already used before its '#pragma input'\n#pragma input M e1\n              ^\n");
  CHECK(diagnostic("#pragma input e1 e1\n?y = 1;\n") ==
        "t.clu:1:15: error: cannot declare basis vector 'e1' as an input\n#pragma input e1 e1\n              ^\n");
  // Pragmas that are fine: output blades in the pragma's order, with blades the value lacks.
  const Kernel k = expand_text("#pragma output x e3 1 e1\n#pragma range -1 <= t <= 1\n?x = t*e1 + 2;\n");
  REQUIRE(k.outputs.size() == 1);
  CHECK(k.outputs[0].blades == std::vector<algebra::BladeIndex>{3, 0, 1});
  REQUIRE(k.ranges.size() == 1);
  CHECK(k.ranges[0].min == -1.0);
}

TEST_CASE("outputs record whether their blades come from a pragma", "[expand]") {
  Kernel k = expand_text("#pragma output P e1 e2\n?P = x*e1 + y*e2;\n?Q = x*e1;\n");
  REQUIRE(k.outputs.size() == 2);
  CHECK(k.outputs[0].name == "P");
  CHECK(k.outputs[0].from_pragma);
  CHECK(k.outputs[0].blades == std::vector<algebra::BladeIndex>{1, 2});
  CHECK(k.outputs[1].name == "Q");
  CHECK_FALSE(k.outputs[1].from_pragma);
}

TEST_CASE("typo warnings: a free name one edit from a known name", "[expand]") {
  auto warnings = [](const std::string& text) {
    std::vector<std::string> out;
    for (const auto& w : expand_text(text).warnings)
      out.push_back(std::to_string(w.loc.line) + ":" + std::to_string(w.loc.col) + " " + w.message);
    return out;
  };
  // Basis vectors, assigned names (also those assigned later), macros and built-ins are all candidates.
  CHECK(warnings("?p = Einf + x*e1;") ==
        std::vector<std::string>{"1:6 'Einf' is used before it is assigned and becomes an input; did you mean 'einf'?"});
  CHECK(warnings("a = motro*e1;\nmotor = 1;\n?b = a;") ==
        std::vector<std::string>{
            "1:5 'motro' is used before it is assigned and becomes an input; did you mean 'motor'?"});
  CHECK(warnings("Square = { _P(1)*_P(1) };\n?b = Squre + Square(x);") ==
        std::vector<std::string>{
            "2:6 'Squre' is used before it is assigned and becomes an input; did you mean 'Square'?"});
  CHECK(warnings("?b = sqr*e1;") ==
        std::vector<std::string>{"1:6 'sqr' is used before it is assigned and becomes an input; did you mean 'sqrt'?"});
  // Short names (x1 against e1, p2 against p1) and ordinary inputs are no typos; one warning per name.
  CHECK(warnings("p1 = VecN3(x1,y1,z1);\n?q = p1 + p2 + e0*x1 + radius + radius;").empty());
  CHECK(warnings("?q = eiof + eiof;").size() == 1);
  // An unknown function suggests the nearest built-in or macro.
  CHECK(diagnostic("?v = VecN4(1,2,3);").find("unknown function 'VecN4'; did you mean 'VecN3'?") != std::string::npos);
  CHECK(diagnostic("?v = frobnicate(1);").find("unknown function 'frobnicate'\n") != std::string::npos);
}

TEST_CASE("zero tests through the value chain: exact probes, no inlining", "[expand]") {
  // b - a*a - 2a - 1 vanishes only once a and b are inlined: the blade is dropped.
  Kernel k = expand_text("a = x + 1;\nb = a*a;\n?c = (b - x*x - 2*x - 1)*e1 + e2;");
  REQUIRE(k.values.back().blades.size() == 1);
  CHECK(k.values.back().blades[0] == 2);
  // abs is no rational function: abs(y) - y vanishes for y > 0 only, and must not be taken for zero.
  k = expand_text("a = abs(y);\n?c = (a - y)*e1;");
  CHECK(k.values.back().blades.size() == 1);
  // A chain of 30 squarings: degree 2^30, no expansion ever made, values kept modulo a prime.
  std::string chain = "v0 = x + 1;\n";
  for (int i = 1; i <= 30; ++i) chain += "v" + std::to_string(i) + " = v" + std::to_string(i - 1) + "*v" + std::to_string(i - 1) + ";\n";
  chain += "?r = (v30 - v29*v29)*e1 + v30*e2;";
  k = expand_text(chain);
  REQUIRE(k.values.back().blades.size() == 1);
  CHECK(k.values.back().blades[0] == 2);
}

TEST_CASE("zero tests give no verdict past the degree a prime can vouch for", "[expand]") {
  // 128 squarings of x - y e12 + t e1^einf: degree 2^128 in x, y, t. Modulo p = 2^61 - 1 the e12 part
  // of (x - y i)^(2^128) vanishes at every point (odd-order elements of F_p^2 lie in F_p), so probes
  // alone would drop it; the degree bound keeps them from saying "zero", and all three blades stay.
  std::string script = "M = x - y*e1^e2 + t*e1^einf;\n";
  for (int i = 0; i < 128; ++i) script += "M = M*M;\n";
  script += "?M;";
  Kernel k = expand_text(script);
  CHECK(k.values.back().blades.size() == 3);
}

TEST_CASE("zero tests reach values whose probe values and samples were never needed before", "[expand]") {
  // Values proved nonzero at the first exact probe point get their other probe values, float samples and
  // signed samples only when a later test needs them: here all 3000 at once, at the last statement
  // (iteratively: no recursion as deep as the chain).
  std::string chain = "v0 = x + 1;\n";
  for (int i = 1; i <= 3000; ++i) chain += "v" + std::to_string(i) + " = v" + std::to_string(i - 1) + " + x;\n";
  chain += "?r = (v3000 - v2999 - x)*e1 + v3000*e2;";
  Kernel k = expand_text(chain);
  REQUIRE(k.values.back().blades.size() == 1);
  CHECK(k.values.back().blades[0] == 2);
  // Through abs (no exact probe values): the float and signed samples, then the exact test.
  chain = "v0 = abs(x) + 1;\n";
  for (int i = 1; i <= 300; ++i) chain += "v" + std::to_string(i) + " = v" + std::to_string(i - 1) + " + abs(x);\n";
  chain += "?r = (v300 - v299 - abs(x))*e1 + v300*e2;";
  k = expand_text(chain);
  REQUIRE(k.values.back().blades.size() == 1);
  CHECK(k.values.back().blades[0] == 2);
}

TEST_CASE("node caches live only while a scope is open, nested scopes share the outer one", "[expand]") {
  // A long-lived process (the fuzzer) must get back all that one generation allocated: no cache may
  // outlive the expander's or the optimizer's own scope.
  REQUIRE(symbolic::NodeCaches::current() == nullptr);
  (void)expand_script("paper_motor.clu");
  CHECK(symbolic::NodeCaches::current() == nullptr);
  {
    symbolic::NodeCacheScope outer;
    symbolic::NodeCaches* shared = symbolic::NodeCaches::current();
    REQUIRE(shared != nullptr);
    {
      symbolic::NodeCacheScope inner;
      CHECK(symbolic::NodeCaches::current() == shared);
    }
    CHECK(symbolic::NodeCaches::current() == shared);
    (void)expand_script("paper_motor.clu");
    CHECK(symbolic::NodeCaches::current() == shared);
  }
  CHECK(symbolic::NodeCaches::current() == nullptr);
}

TEST_CASE("built-ins: CLUCalc's DefVars calls do nothing, exp in a basis that is not orthonormal", "[expand]") {
  // DefVarsN3() (Gaalop's hist_Horizon.clu) declares CLUCalc's basis names: here a no-op statement.
  Kernel k = expand_text("DefVarsN3();\nDefVarsE3();\n?p = createPoint(1, 2, 3);\n");
  REQUIRE(k.outputs.size() == 1);
  CHECK(k.values.back().blades.size() == 5);
  CHECK_THROWS_WITH(expand_text("?p = DefVarsN3(1);\n"), Catch::Contains("'DefVarsN3' takes 0 arguments, got 1"));
  // A user basis a = 2 d1, b = d2 over orthonormal d1, d2: (a^b)^2 = -4, so exp(t a^b) = cos(2t) +
  // sin(2t)/2 a^b (t = 0.5: cos 1 + sin(1)/2 a^b), not cos(t) + sin(t) a^b.
  const std::string csv = (std::filesystem::temp_directory_path() / "cgagen_scaled2d.csv").string();
  {
    std::ofstream f(csv);
    f << "1,a,b\nd1=0.5*a,d2=b\n1,d1,d2\nd1=1,d2=1\na=2*d1,b=d2\n";
  }
  front::SourceFile file("t.clu", "?o = exp(0.5*(a^b));\n");
  Kernel e = expand(front::parse(file), "t", algebra::load(csv));
  REQUIRE(e.values.back().blades.size() == 2);
  const double c = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e.values.back().coeffs[0])).to_double();
  const double s = GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e.values.back().coeffs[1])).to_double();
  CHECK(c == Approx(std::cos(1.0)));
  CHECK(s == Approx(std::sin(1.0) / 2));
}

TEST_CASE("exact probes: opaque nodes as inputs, and a degree bound on zero verdicts", "[expand]") {
  using V = symbolic::ProbePoints::Verdict;
  symbolic::ProbePoints probes;
  const GiNaC::symbol x("x"), y("y"), a("a"), r("r");
  probes.add_input(x);
  probes.add_input(y);
  probes.define(a, GiNaC::cos(x));
  probes.define(r, GiNaC::sqrt(x));
  // A function application is one more input: what vanishes with it free vanishes whatever its value.
  CHECK(probes.test(a * a - GiNaC::pow(GiNaC::cos(x), 2)) == V::Zero);
  CHECK(probes.test(r - GiNaC::sqrt(x)) == V::Zero);
  // ... but its values are related: a nonzero with opaque inputs proves nothing.
  CHECK(probes.test(GiNaC::pow(GiNaC::sin(x), 2) + a * a - 1) == V::Unknown);
  CHECK(probes.test(r * r - x) == V::Unknown);
  CHECK(probes.test(GiNaC::abs(y) - y) == V::Unknown);
  CHECK(probes.test(x - y) == V::Nonzero);
  // Zero at every point, but only up to numerator degree 2^40 does that prove anything.
  std::vector<GiNaC::symbol> v;
  v.emplace_back("v0");
  probes.define(v[0], x + 1);
  for (int i = 1; i <= 45; ++i) {
    v.emplace_back("v" + std::to_string(i));
    probes.define(v[i], v[i - 1] * v[i - 1]);
  }
  CHECK(probes.test(v[30] - v[29] * v[29]) == V::Zero);
  CHECK(probes.test(v[45] - v[44] * v[44]) == V::ZeroPastDegree);
  // A common denominator counts once: w_i = w_(i-1)/d + y w_(i-1)/d has degree i over d^i, where a bound
  // adding the terms' denominators would double with every step and pass 2^40.
  const GiNaC::symbol d("d");
  probes.define(d, x + y);
  std::vector<GiNaC::symbol> w;
  w.emplace_back("w0");
  probes.define(w[0], x);
  for (int i = 1; i <= 45; ++i) {
    w.emplace_back("w" + std::to_string(i));
    probes.define(w[i], w[i - 1] / d + y * w[i - 1] / d);
  }
  CHECK(probes.test(w[45] * d - w[44] * (1 + y)) == V::Zero);
}
