// Motor decomposition and the screw logarithm/exponential, on a motor's 12 coefficients. The geometric
// products go through the generated kernels (motor.hpp); what is here needs single coefficients, square
// roots and trigonometry of grade parts, which the script language cannot express (it has no grade
// projection and its functions take scalars only).
#include "cga/runtime/motor.hpp"

#include <cmath>

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

// Screw parameters of a rigid motion (rotation q, translation t), interpolated to the fraction alpha:
// log gives the axis u, angle theta, pitch d = t.u and a point p on the axis; exp of alpha*log is the
// rotation by alpha*theta about that axis followed by the slide alpha*d along it.
Transform screw_fraction(glm::dquat q, const glm::dvec3& t, double alpha) {
  if (q.w < 0.0) q = -q;  // the shortest way: theta in [0, pi]
  const glm::dvec3 v(q.x, q.y, q.z);
  const double sin_half = glm::length(v);
  const double theta = 2.0 * std::atan2(sin_half, q.w);
  Transform out;
  if (theta < 1e-6) {
    // No rotation to speak of: the screw is a straight slide (the limit of the general case).
    out.translation = glm::vec3(alpha * t);
    out.rotation = glm::quat(glm::normalize(glm::dquat(1.0, alpha * v.x, alpha * v.y, alpha * v.z)));
    return out;
  }
  const glm::dvec3 u = v / sin_half;
  const double d = glm::dot(t, u);
  const glm::dvec3 t_perp = t - d * u;
  // 1/tan(theta/2) = q.w / sin_half (theta/2 = atan2(sin_half, q.w)); 0 at theta = pi, as it should be.
  const glm::dvec3 p = 0.5 * (t_perp + glm::cross(u, t_perp) * (q.w / sin_half));
  const double half = 0.5 * alpha * theta;
  const glm::dquat qa(std::cos(half), std::sin(half) * u.x, std::sin(half) * u.y, std::sin(half) * u.z);
  out.rotation = glm::quat(qa);
  out.translation = glm::vec3(p - qa * p + alpha * d * u);
  return out;
}

}  // namespace

Motor motor_screw(const Transform& x1, const Transform& x2, float alpha) {
  Transform r1 = x1, r2 = x2;
  r1.scale = r2.scale = 1.0f;
  const Motor m1 = motor_from_transform(r1);
  // The relative rigid motion ~M1 * M2 (M1 is a unit rigid motor, so ~M1 is its inverse).
  const Motor rel = motor_mul(motor_reverse(m1), motor_from_transform(r2));
  const Transform rel_x = motor_to_transform(rel);
  Transform step = screw_fraction(glm::dquat(rel_x.rotation), glm::dvec3(rel_x.translation), alpha);
  step.scale = static_cast<float>(std::pow(double(x1.scale), 1.0 - alpha) * std::pow(double(x2.scale), double(alpha)));
  // M1 * exp(alpha log(~M1 M2)) * D(s): the dilator is the rightmost factor of a motor T*R*D.
  return motor_mul(m1, motor_from_transform(step));
}

namespace {

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
  // The relative rigid motion ~R1 * R2: its rotor and, from the einf blades, its translation
  // (t = -2 L(a)^T e for a unit rotor a, see motor_to_transform).
  Motor rel;
  motor_mul_rigid_simd(motor_reverse(r1), r2, rel);
  const auto& c = rel.c;
  const glm::dquat q = glm::normalize(glm::dquat(quat_from_rotor(c[0], c[1], c[2], c[4])));
  const double g[4] = {c[0], c[1], c[2], c[4]}, e[4] = {c[3], c[5], c[6], c[8]};
  const double gg = g[0] * g[0] + g[1] * g[1] + g[2] * g[2] + g[3] * g[3];
  const glm::dvec3 t = (-2.0 / gg) * glm::dvec3((g[0] * e[0] + g[1] * e[1] + g[2] * e[2] + g[3] * e[3]),
                                                (-g[1] * e[0] + g[0] * e[1] + g[3] * e[2] - g[2] * e[3]),
                                                (-g[2] * e[0] - g[3] * e[1] + g[0] * e[2] + g[1] * e[3]));
  Transform step = screw_fraction(q, t, alpha);
  step.scale = s1 == s2 ? static_cast<float>(s1) : static_cast<float>(std::pow(s1, 1.0 - alpha) * std::pow(s2, double(alpha)));
  const Motor m = motor_from_transform(step);
  if (!motor_is_rigid(m)) return motor_mul(r1, m);
  Motor out;
  motor_mul_rigid_simd(r1, m, out);
  return out;
}

Transform transform_screw(const Transform& x1, const Transform& x2, float alpha) {
  return motor_to_transform(motor_screw(x1, x2, alpha));
}

}  // namespace cga
