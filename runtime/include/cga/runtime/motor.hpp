// Motor operations of the runtime: thin wrappers over the kernels generated from runtime/scripts/*.clu
// (namespace cga::kernels), plus the few operations the script language cannot express because they need
// single coefficients, square roots of grade parts or trigonometry of them (decomposition back to TRS, the
// screw logarithm/exponential). Those work on the 12 coefficients of types.hpp's Motor and call the
// generated kernels for every geometric product.
//
// Coefficient groups of a motor M = T*R*D (D = 1 + k E, k = (1-s)/(1+s), E = einf^e0):
//   a = R        in c[0], c[1] (e12), c[2] (e13), c[4] (e23)
//   b = k R      in c[7] (E), c[9] (e12E), c[10] (e13E), c[11] (e23E)
//   c = -(1+k)/2 (t R) einf   in c[3] (e1inf), c[5] (e2inf), c[6] (e3inf), c[8] (e123inf)
// so a + b = (1+k) R and a - b = (1-k) R, whose norms give the scale s = |a-b| / |a+b|.
#pragma once

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string_view>

#include "cga/runtime/rotor_sign.hpp"
#include "cga/runtime/types.hpp"

#include <motor_from_trs.hpp>
#include <motor_lerp_paper.hpp>
#include <motor_mul.hpp>
#include <motor_mul_rigid.hpp>
#include <motor_normalize.hpp>
#include <motor_reverse.hpp>
#include <transform_point.hpp>
#include <transform_point_staged.hpp>

namespace cga {

// The rigid part T*R of a motor in motor_lerp_paper's 8-blade order:
// 1 e1^e2 e1^e3 e1^einf e2^e3 e2^einf e3^einf e1^e2^e3^einf.
using RigidMotor = std::array<float, 8>;

// Rotor coefficients (rs, r12, r13, r23) of a unit quaternion: R = w - x e23 - y e31 - z e12.
inline std::array<float, 4> rotor_from_quat(const glm::quat& q) { return {q.w, -q.z, q.y, -q.x}; }
inline glm::quat quat_from_rotor(float rs, float r12, float r13, float r23) {
  glm::quat q;
  q.w = rs;
  q.x = -r23;
  q.y = r13;
  q.z = -r12;
  return q;
}

// M = T*R*D of a transform (generated motor_from_trs).
inline Motor motor_from_transform(const Transform& x) {
  const auto r = rotor_from_quat(x.rotation);
  Motor m;
  kernels::motor_from_trs(x.translation.x, x.translation.y, x.translation.z, r[0], r[1], r[2], r[3], x.scale,
                          m.c.data());
  return m;
}

// C = A*B: apply B, then A (generated motor_mul).
inline Motor motor_mul(const Motor& a, const Motor& b) {
  Motor out;
  kernels::motor_mul(a.c.data(), b.c.data(), out.c.data());
  return out;
}

// ~A (generated motor_reverse).
inline Motor motor_reverse(const Motor& a) {
  Motor out;
  kernels::motor_reverse(a.c.data(), out.c.data());
  return out;
}

// The paper's eq. 25 + dilator lerp + eq. 27 (generated motor_lerp_paper).
inline Motor motor_lerp_paper(const RigidMotor& a, const RigidMotor& b, float d1, float d2, float alpha) {
  Motor out;
  kernels::motor_lerp_paper(a.data(), b.data(), d1, d2, alpha, out.c.data());
  return out;
}

// M X ~M of a Euclidean point, divided by its weight (generated transform_point).
inline glm::vec3 motor_transform_point(const Motor& m, const glm::vec3& p) {
  float out[4];
  kernels::transform_point(m.c.data(), p.x, p.y, p.z, out);
  return glm::vec3(out[0], out[1], out[2]) / out[3];
}

// The staged point transform: runtime/scripts/transform_point.clu generated once more with M
// uniform (generated/CMakeLists.txt, NAME transform_point_staged), so cgagen splits M X ~M into
// transform_point_staged_prepare(M) -> 13 values (the 3x4 matrix of P = (x', y', z') and the weight w, which
// does not depend on the point) and the per-point body (9 mul + 9 add). P is homogeneous and the body is
// linear in the prepared values, so dividing all 13 by the weight once per motor makes the body's output the
// Euclidean point (its w slot becomes 1): that is the whole normalization, 1 div + 12 mul per motor.
using PreparedPointTransform = std::array<float, kernels::transform_point_staged_prepare_prepared_blades.size()>;
namespace detail {
// The prepared slots' layout that motor_matrix and motor_prepare_points read, checked against the names the
// generator emits: a change in the split fails the build here rather than moving points silently.
constexpr bool prepared_point_layout() {
  constexpr std::string_view want[13] = {"P.e1[1]", "P.e1[x]", "P.e1[y]", "P.e1[z]", "P.e2[1]", "P.e2[x]", "P.e2[y]",
                                         "P.e2[z]", "P.e3[1]", "P.e3[x]", "P.e3[y]", "P.e3[z]", "P.e0"};
  const auto& got = kernels::transform_point_staged_prepare_prepared_blades;
  if (got.size() != 13) return false;
  for (std::size_t i = 0; i < 13; ++i)
    if (got[i] != want[i]) return false;
  return true;
}
static_assert(prepared_point_layout(), "transform_point_staged's prepared values are no longer the 3x4 rows + w");
}  // namespace detail

inline PreparedPointTransform motor_prepare_points(const Motor& m) {
  PreparedPointTransform p;
  kernels::transform_point_staged_prepare(m.c.data(), p.data());
  const float inv_w = 1.0f / p[12];
  for (float& v : p) v *= inv_w;
  p[12] = 1.0f;
  return p;
}

// One point through the prepared values (the generated per-element body).
inline glm::vec3 prepared_transform_point(const PreparedPointTransform& p, const glm::vec3& x) {
  float out[4];
  kernels::transform_point_staged(p.data(), x.x, x.y, x.z, out);
  return glm::vec3(out[0], out[1], out[2]);
}

// The weight-normalized point transform of a motor as a row-major 3x4 matrix: the generated prepare's
// values (slots P.e<r>[1], P.e<r>[x], P.e<r>[y], P.e<r>[z] for row r, detail::prepared_point_layout) as rows (x, y, z, translation).
inline glm::mat3x4 motor_matrix(const Motor& m) {
  const PreparedPointTransform p = motor_prepare_points(m);
  glm::mat3x4 out;
  for (int r = 0; r < 3; ++r) out[r] = glm::vec4(p[4 * r + 1], p[4 * r + 2], p[4 * r + 3], p[4 * r]);
  return out;
}

// The 8 rigid blades of a motor whose dilation is 1 (or the T*R factor as built by rigid_from_transform).
inline RigidMotor rigid_blades(const Motor& m) {
  return {m.c[0], m.c[1], m.c[2], m.c[3], m.c[4], m.c[5], m.c[6], m.c[8]};
}
inline Motor motor_from_rigid(const RigidMotor& r) {
  Motor m;
  m.c = {r[0], r[1], r[2], r[3], r[4], r[5], r[6], 0.0f, r[7], 0.0f, 0.0f, 0.0f};
  return m;
}

// Inner product of the rotor parts G = a + b of two motors: its sign decides the antipodal fix (rotor_sign.hpp).
inline float motor_rotor_dot(const Motor& x, const Motor& y) {
  float gx[4], gy[4];
  for (int i = 0; i < 4; ++i) gx[i] = rotor_sign::rotor_g(x.c.data(), i), gy[i] = rotor_sign::rotor_g(y.c.data(), i);
  return rotor_sign::dot(gx, gy);
}

// The similarity (t, R, s) nearest to a motor, read from its coefficients (see the header comment): exact for
// M = T*R*D; for a blend of motors it is the projection that nlerp's normalization uses (rotation from
// a + b normalized, scale |a - b| / |a + b|, translation by least squares on the einf blades).
// Throws std::domain_error when the rotor part vanishes.
Transform motor_to_transform(const Motor& m);

// nlerp's normalization: the exact motor of motor_to_transform(m).
inline Motor motor_normalize(const Motor& m) { return motor_from_transform(motor_to_transform(m)); }

// The same projection straight on the coefficients, in float and without branches (generated
// motor_normalize, runtime/scripts/motor_normalize.clu): with g = a + b, h = a - b and e the einf blades
// (header comment), a' = g/|g|, b' = k' a' with k' = (|g| - |h|)/(|g| + |h|), and c' = 2 P e / (|g| + |h|),
// where P removes from e its component along n = (-g3, g2, -g1, g0)/|g|, the normal of the 3-space that
// the einf blades of an exact motor T*R*D span. For b = 0 (no scale) g = h bit for bit, so b' = 0 exactly.
// No rotor part gives non-finite coefficients. The jobs call the kernel per lane of blocks of 8 motors
// (jobs/common.hpp), a loop GCC vectorizes. in and out may alias: the kernel reads every input before it
// writes.
inline void motor_normalize_fast(const float* in, float* out) { kernels::motor_normalize(in, out); }
inline Motor motor_normalize_fast(const Motor& m) {
  Motor out;
  kernels::motor_normalize(m.c.data(), out.c.data());
  return out;
}

// A motor without dilation: its einf^e0-times blades (the b group) are exactly zero. The jobs then use the
// 8-blade product motor_mul_rigid.
inline bool motor_is_rigid(const Motor& m) {
  // +0 or -0 in all four: OR their bits without the sign (no compares or branches per coefficient).
  const auto bits = [&](int c) { return std::bit_cast<std::uint32_t>(m.c[c]); };
  return ((bits(7) | bits(9) | bits(10) | bits(11)) << 1) == 0u;
}

// C = A*B for rigid motors (generated motor_mul_rigid on the 8 rigid blades; the b group of C is zero).
inline void motor_mul_rigid(const Motor& a, const Motor& b, Motor& out) {
  const float x[8] = {a.c[0], a.c[1], a.c[2], a.c[3], a.c[4], a.c[5], a.c[6], a.c[8]};
  const float y[8] = {b.c[0], b.c[1], b.c[2], b.c[3], b.c[4], b.c[5], b.c[6], b.c[8]};
  float z[8];
  kernels::motor_mul_rigid(x, y, z);
  out.c = {z[0], z[1], z[2], z[3], z[4], z[5], z[6], 0.0f, z[7], 0.0f, 0.0f, 0.0f};
}

// The unit rigid part T*R of a motor T*R*D after motor_normalize_fast's projection (generated
// motor_rigid_part), and its scale s when `scale` is given (exactly 1 for a rigid motor).
Motor motor_rigid(const Motor& m, double* scale = nullptr);

// Screw-linear interpolation between two similarities: the rigid parts by the motor logarithm/exponential
// (constant-speed helix about the screw axis of the relative motion ~M1*M2, shortest way), the scale
// geometrically (s1^(1-alpha) s2^alpha). alpha = 0 and 1 give the inputs exactly.
Motor motor_screw(const Transform& x1, const Transform& x2, float alpha);
// The same on two motors, straight from their coefficients (the jobs' form: no round trip through TRS).
// The inputs are first projected onto exact motors as motor_normalize_fast does.
Motor motor_screw(const Motor& m1, const Motor& m2, float alpha);
// The same interpolation on the TRS level (used by motor_screw; exposed for tests and the accuracy tool).
Transform transform_screw(const Transform& x1, const Transform& x2, float alpha);

}  // namespace cga
