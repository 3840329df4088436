// motor_to_transform and motor_screw's rigid part through the generated kernels motor_to_trs and
// motor_rigid_part, against the hand derivation they replace (copied here as the reference), on seeded
// random motors with scale, on their blends (not exact motors: the translation is a least-squares fit) and
// on blends scaled by a weight.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include <cga_rigid.hpp>

#include "cga/runtime/motor.hpp"
#include "random_motors.hpp"

using namespace cga;
using cga::test::random_blend;
using cga::test::random_transform;

namespace {

// The former hand derivation of motor_to_transform (runtime/src/motor.cpp before motor_to_trs.clu).
Transform reference_motor_to_transform(const Motor& m) {
  const auto& c = m.c;
  // g = a + b = (1+k) R and h = a - b = (1-k) R (coefficients 1, e12, e13, e23).
  const double g[4] = {double(c[0]) + c[7], double(c[1]) + c[9], double(c[2]) + c[10], double(c[4]) + c[11]};
  const double h[4] = {double(c[0]) - c[7], double(c[1]) - c[9], double(c[2]) - c[10], double(c[4]) - c[11]};
  const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3];
  const double hh = h[0] * h[0] + h[1] * h[1] + h[2] * h[2] + h[3] * h[3];
  if (!(gg > 1e-30)) throw std::domain_error("motor_to_transform: the motor has no rotor part");
  const double ng = std::sqrt(gg);
  Transform x;
  x.scale = static_cast<float>(std::sqrt(hh) / ng);
  x.rotation = quat_from_rotor(float(g[0] / ng), float(g[1] / ng), float(g[2] / ng), float(g[3] / ng));
  // The einf blades are -1/2 L(g) t with the 4x3 matrix L(g) of t*g (vector times even element), whose
  // columns are orthogonal with norm |g|: t = -2 L(g)^T e / |g|^2 (least squares for a blend).
  const double e[4] = {c[3], c[5], c[6], c[8]};  // e1inf, e2inf, e3inf, e123inf
  const double L[4][3] = {{g[0], -g[1], -g[2]}, {g[1], g[0], -g[3]}, {g[2], g[3], g[0]}, {g[3], -g[2], g[1]}};
  for (int j = 0; j < 3; ++j) {
    double s = 0.0;
    for (int i = 0; i < 4; ++i) s += L[i][j] * e[i];
    x.translation[j] = static_cast<float>(-2.0 * s / gg);
  }
  return x;
}

// The former hand derivation of motor_screw's rigid part: with a' = R and b' = k R after
// motor_normalize_fast, 1 + k = 1 + a'.b', and the einf blades are (1 + k) times the rigid ones.
Motor reference_rigid_part(const Motor& m, double& scale) {
  Motor n = motor_normalize_fast(m);
  const float k = n.c[0] * n.c[7] + n.c[1] * n.c[9] + n.c[2] * n.c[10] + n.c[4] * n.c[11];
  scale = (1.0 - double(k)) / (1.0 + double(k));
  const float inv = 1.0f / (1.0f + k);
  for (int c : {3, 5, 6, 8}) n.c[c] *= inv;
  for (int c : {7, 9, 10, 11}) n.c[c] = 0.0f;
  return n;
}

// motor_screw as runtime/src/motor.cpp writes it, on reference_rigid_part.
Motor reference_motor_screw(const Motor& m1, const Motor& m2, float alpha) {
  constexpr int kRigidBlades[8] = {0, 1, 2, 4, 3, 5, 6, 8};
  double s1, s2;
  const Motor r1 = reference_rigid_part(m1, s1);
  const Motor r2 = reference_rigid_part(m2, s2);
  Motor rel;
  motor_mul_rigid(motor_reverse(r1), r2, rel);
  cga_rigid::motor_t<double> x;
  const double sign = rel.c[0] < 0.0f ? -1.0 : 1.0;
  for (int k = 0; k < 8; ++k) x[k] = sign * rel.c[kRigidBlades[k]];
  const cga_rigid::motor_t<double> step = cga_rigid::exp(double(alpha) * cga_rigid::log(x));
  Motor m;
  m.c.fill(0.0f);
  for (int k = 0; k < 8; ++k) m.c[kRigidBlades[k]] = static_cast<float>(step[k]);
  const double s = s1 == s2 ? s1 : std::pow(s1, 1.0 - alpha) * std::pow(s2, double(alpha));
  if (s != 1.0) {
    Transform dilation;
    dilation.scale = static_cast<float>(s);
    m = motor_mul(m, motor_from_transform(dilation));
  }
  return motor_mul(r1, m);
}

float ulps_apart_scaled(float a, float b, float magnitude) { return std::abs(a - b) / (magnitude * 1.1920929e-7f); }

void check_same_transform(const Transform& x, const Transform& y, float ulps) {
  const float tmag = std::max({1.0f, glm::length(y.translation)});
  for (int j = 0; j < 3; ++j) CHECK(ulps_apart_scaled(x.translation[j], y.translation[j], tmag) <= ulps);
  for (int j = 0; j < 4; ++j) CHECK(ulps_apart_scaled(x.rotation[j], y.rotation[j], 1.0f) <= ulps);
  CHECK(ulps_apart_scaled(x.scale, y.scale, std::max(1.0f, y.scale)) <= ulps);
}

}  // namespace

TEST_CASE("motor_to_transform equals the former hand derivation on exact motors with scale", "[motor]") {
  std::mt19937 rng(11);
  for (int n = 0; n < 1000; ++n) {
    const Motor m = motor_from_transform(random_transform(rng));
    INFO("motor " << n);
    check_same_transform(motor_to_transform(m), reference_motor_to_transform(m), 1.0f);
  }
}

TEST_CASE("motor_to_transform equals the former hand derivation on blends (least-squares translation)",
          "[motor]") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> weight(0.3f, 3.0f);
  int not_exact = 0;
  for (int n = 0; n < 1000; ++n) {
    const Motor m = random_blend(rng, 2 + n % 3, n % 2 ? weight(rng) : 1.0f);
    INFO("blend " << n);
    const Transform ref = reference_motor_to_transform(m);
    check_same_transform(motor_to_transform(m), ref, 1.0f);
    // The blend is no exact motor: its translation is a fit, and the exact motor of the result differs.
    const Motor back = motor_from_transform(ref);
    float w = 0.0f;
    for (int c : {0, 1, 2, 4}) w += back.c[c] * m.c[c];
    float off = 0.0f;
    for (int c : {3, 5, 6, 8}) off = std::max(off, std::abs(m.c[c] - w * back.c[c]));
    if (off > 1e-3f) ++not_exact;
  }
  CHECK(not_exact > 100);
}

TEST_CASE("motor_to_transform still refuses a motor without rotor part", "[motor]") {
  Motor m;
  m.c.fill(0.0f);
  m.c[3] = 1.0f;
  CHECK_THROWS_AS(motor_to_transform(m), std::domain_error);
}

TEST_CASE("motor_screw equals the screw on the former hand-derived rigid part", "[motor]") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> alpha(0.0f, 1.0f);
  for (int n = 0; n < 500; ++n) {
    // Exact motors and blends, with and without scale.
    Motor a = n % 2 ? random_blend(rng, 2, 1.0f) : motor_from_transform(random_transform(rng));
    Motor b = n % 3 ? random_blend(rng, 3, 1.0f) : motor_from_transform(random_transform(rng));
    if (n % 5 == 0) {
      Transform x = motor_to_transform(a);
      x.scale = 1.0f;
      a = motor_from_transform(x);
    }
    const float t = n % 7 == 0 ? 0.0f : n % 7 == 1 ? 1.0f : alpha(rng);
    INFO("pair " << n << " alpha " << t);
    const Transform got = motor_to_transform(motor_screw(a, b, t));
    const Transform ref = motor_to_transform(reference_motor_screw(a, b, t));
    // A few float roundings apart (5 ulps at most here): k and 1/(1+k) are summed in another order.
    check_same_transform(got, ref, 16.0f);
  }
}

TEST_CASE("motor_screw of rigid motors stays rigid (scale exactly 1)", "[motor]") {
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> alpha(0.0f, 1.0f);
  for (int n = 0; n < 1000; ++n) {
    Transform x = random_transform(rng), y = random_transform(rng);
    x.scale = y.scale = 1.0f;
    const Motor m = motor_screw(motor_from_transform(x), motor_from_transform(y), alpha(rng));
    INFO("pair " << n);
    CHECK(motor_is_rigid(m));
  }
}
