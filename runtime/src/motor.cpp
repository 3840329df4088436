// Motor decomposition (TRS from a motor's 12 coefficients) and the screw interpolation. The products go
// through the generated kernels (motor.hpp), the screw's logarithm and exponential through the generated
// library of runtime/scripts/cga_rigid.gal (cga_rigid.hpp).
#include "cga/runtime/motor.hpp"

#include <cmath>

#include <cga_rigid.hpp>

namespace cga {

Transform motor_to_transform(const Motor& m) {
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

namespace {

// cga_rigid::motor's blades (runtime/scripts/cga_rigid.gal: 1 e12 e13 e23 e1inf e2inf e3inf e123inf) in a
// Motor's coefficients (types.hpp).
constexpr int kRigidBlades[8] = {0, 1, 2, 4, 3, 5, 6, 8};

// The fraction alpha of a unit rigid motion along its screw, exp(alpha log(M)) (the generated library), the
// shorter way: M and -M are the same motion, and the one with a non-negative scalar turns by at most pi.
Motor screw_fraction(const Motor& m, double alpha) {
  cga_rigid::motor_t<double> x;
  const double sign = m.c[0] < 0.0f ? -1.0 : 1.0;
  for (int k = 0; k < 8; ++k) x[k] = sign * m.c[kRigidBlades[k]];
  const cga_rigid::motor_t<double> step = cga_rigid::exp(alpha * cga_rigid::log(x));
  Motor out;
  out.c.fill(0.0f);
  for (int k = 0; k < 8; ++k) out.c[kRigidBlades[k]] = static_cast<float>(step[k]);
  return out;
}

// The unit rigid part T*R and the scale of a motor, after the projection of motor_normalize_fast: with
// a' = R and b' = k R, 1 + k = 1 + a'.b', and the einf blades are (1 + k) times the rigid ones.
Motor rigid_part(const Motor& m, double& scale) {
  Motor n = motor_normalize_fast(m);
  const float k = n.c[0] * n.c[7] + n.c[1] * n.c[9] + n.c[2] * n.c[10] + n.c[4] * n.c[11];
  scale = (1.0 - double(k)) / (1.0 + double(k));
  const float inv = 1.0f / (1.0f + k);
  for (int c : {3, 5, 6, 8}) n.c[c] *= inv;
  for (int c : {7, 9, 10, 11}) n.c[c] = 0.0f;
  return n;
}

}  // namespace

Motor motor_screw(const Motor& m1, const Motor& m2, float alpha) {
  double s1, s2;
  const Motor r1 = rigid_part(m1, s1);
  const Motor r2 = rigid_part(m2, s2);
  // The relative rigid motion ~R1 * R2 (R1 is unit, so ~R1 is its inverse), a fraction of it along its screw,
  // then the dilator: a motor T*R*D has D rightmost.
  Motor rel;
  motor_mul_rigid_simd(motor_reverse(r1), r2, rel);
  Motor m = screw_fraction(rel, alpha);
  const double s = s1 == s2 ? s1 : std::pow(s1, 1.0 - alpha) * std::pow(s2, double(alpha));
  if (s != 1.0) {
    Transform dilation;
    dilation.scale = static_cast<float>(s);
    m = motor_mul(m, motor_from_transform(dilation));
  }
  if (!motor_is_rigid(m)) return motor_mul(r1, m);
  Motor out;
  motor_mul_rigid_simd(r1, m, out);
  return out;
}

Motor motor_screw(const Transform& x1, const Transform& x2, float alpha) {
  return motor_screw(motor_from_transform(x1), motor_from_transform(x2), alpha);
}

Transform transform_screw(const Transform& x1, const Transform& x2, float alpha) {
  return motor_to_transform(motor_screw(x1, x2, alpha));
}

}  // namespace cga
