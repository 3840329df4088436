// Motor decomposition (TRS from a motor's 12 coefficients) and the screw interpolation. The decomposition
// goes through the generated kernels motor_to_trs and motor_rigid_part, the products through those of
// motor.hpp (the two rigid ones of motor_screw through detail/rigid_mul_simd.hpp), the screw's logarithm and exponential through the generated library of
// runtime/scripts/cga_rigid.gal (cga_rigid.hpp). Square roots and divisions are the C++ here.
#include "cga/runtime/motor.hpp"

#include <cmath>

#include <cga_rigid.hpp>
#include <motor_rigid_part.hpp>
#include <motor_to_trs.hpp>

#include "detail/rigid_mul_simd.hpp"

namespace cga {

Transform motor_to_transform(const Motor& m) {
  // The split form G, |G|^2, |H|^2 and the least-squares translation times |G|^2 (motor_to_trs.clu), in double.
  double c[12];
  for (int k = 0; k < 12; ++k) c[k] = m.c[k];
  double g[4], gg, hh, v[3];
  kernels::motor_to_trs(c, g, &gg, &hh, v);
  if (!(gg > 1e-30)) throw std::domain_error("motor_to_transform: the motor has no rotor part");
  const double ng = std::sqrt(gg);
  Transform x;
  x.scale = static_cast<float>(std::sqrt(hh) / ng);
  x.rotation = quat_from_rotor(float(g[0] / ng), float(g[1] / ng), float(g[2] / ng), float(g[3] / ng));
  for (int j = 0; j < 3; ++j) x.translation[j] = static_cast<float>(v[j] / gg);
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

}  // namespace

// motor_rigid: T*R and k from motor_rigid_part.clu, s = (1 - k)/(1 + k). A rigid motor has a scale of
// exactly 1: the test does not rely on motor_normalize_fast's b group staying 0, which the reassociation
// this file is built with (CMakeLists.txt) may break by an ulp; s != 1 would take motor_screw off the rigid
// products.
Motor motor_rigid(const Motor& m, double* scale) {
  const Motor n = motor_normalize_fast(m);
  float p[8], k;
  kernels::motor_rigid_part(n.c.data(), p, &k);
  if (scale) *scale = motor_is_rigid(m) ? 1.0 : (1.0 - double(k)) / (1.0 + double(k));
  // P's blades (motor_mul_rigid.clu's order) in a Motor's coefficients; the b group is 0.
  Motor out;
  out.c = {p[0], p[1], p[2], p[3], p[4], p[5], p[6], 0.0f, p[7], 0.0f, 0.0f, 0.0f};
  return out;
}

Motor motor_screw(const Motor& m1, const Motor& m2, float alpha) {
  double s1, s2;
  const Motor r1 = motor_rigid(m1, &s1);
  const Motor r2 = motor_rigid(m2, &s2);
  // The relative rigid motion ~R1 * R2 (R1 is unit, so ~R1 is its inverse), a fraction of it along its screw,
  // then the dilator: a motor T*R*D has D rightmost.
  Motor rel;
  detail::motor_mul_rigid_simd(motor_reverse(r1), r2, rel);
  Motor m = screw_fraction(rel, alpha);
  const double s = s1 == s2 ? s1 : std::pow(s1, 1.0 - alpha) * std::pow(s2, double(alpha));
  if (s != 1.0) {
    Transform dilation;
    dilation.scale = static_cast<float>(s);
    m = motor_mul(m, motor_from_transform(dilation));
  }
  if (!motor_is_rigid(m)) return motor_mul(r1, m);
  Motor out;
  detail::motor_mul_rigid_simd(r1, m, out);
  return out;
}

Motor motor_screw(const Transform& x1, const Transform& x2, float alpha) {
  return motor_screw(motor_from_transform(x1), motor_from_transform(x2), alpha);
}

Transform transform_screw(const Transform& x1, const Transform& x2, float alpha) {
  return motor_to_transform(motor_screw(x1, x2, alpha));
}

}  // namespace cga
