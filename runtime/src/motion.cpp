// Motion extraction (see motion.hpp): the root track of translation and yaw, and the root's remaining motion.
#include "cga/runtime/motion.hpp"

#include <cmath>

#include "cga/runtime/motor.hpp"

namespace cga {
namespace {

// Index into the rotor part (c0 c1 c2 c4 = 1 e12 e13 e23) of the bivector whose plane is perpendicular to up.
int yaw_blade(MotionAxis up) {
  switch (up) {
    case MotionAxis::x: return blade::e23;
    case MotionAxis::y: return blade::e13;
    case MotionAxis::z: return blade::e12;
  }
  return blade::e13;
}

// The yaw (twist about up) as a unit rotor (scalar, bivector coefficient). The rotor of T·R·D is a + b
// normalized (a = 1 e12 e13 e23 blades, b = the ∞∧o-times blades, docs/runtime.md); the normalization
// drops out of the twist's own normalization. A rotor with no twist part (a half turn about a horizontal
// axis: the twist is undefined) gives the identity.
void yaw_of(const Motor& m, int b, float& s, float& y) {
  // rotor_g pairs each rotor blade with its ∞∧o partner: 0↔7, 1↔9, 2↔10, 4↔11.
  const int partner = b == blade::e12 ? blade::e12inf0 : b == blade::e13 ? blade::e13inf0 : blade::e23inf0;
  s = m.c[blade::s] + m.c[blade::einf0];
  y = m.c[b] + m.c[partner];
  const float n = std::sqrt(s * s + y * y);
  if (!(n > 1e-12f)) {
    s = 1.0f, y = 0.0f;
    return;
  }
  s /= n, y /= n;
}

bool finite_motor(const Motor& m) {
  for (float c : m.c)
    if (!std::isfinite(c)) return false;
  const float g0 = m.c[0] + m.c[7], g1 = m.c[1] + m.c[9], g2 = m.c[2] + m.c[10], g3 = m.c[4] + m.c[11];
  return g0 * g0 + g1 * g1 + g2 * g2 + g3 * g3 > 0.0f;
}

}  // namespace

bool MotionExtractionJob::Validate() const {
  if (root.empty() || track.size() != root.size() || remaining.size() != root.size()) return false;
  if (up != MotionAxis::x && up != MotionAxis::y && up != MotionAxis::z) return false;
  for (const Motor& m : root)
    if (!finite_motor(m)) return false;
  return true;
}

bool MotionExtractionJob::Run() const {
  if (!Validate()) return false;
  const int b = yaw_blade(up);
  const glm::vec3 origin(0.0f);
  const glm::vec3 keep(extract_x ? 1.0f : 0.0f, extract_y ? 1.0f : 0.0f, extract_z ? 1.0f : 0.0f);
  // The reference's translation and yaw (rotor s + y B; its inverse is s − y B).
  glm::vec3 t_ref(0.0f);
  float s_ref = 1.0f, y_ref = 0.0f;
  if (reference == MotionReference::first_frame) {
    t_ref = motor_transform_point(root[0], origin);
    yaw_of(root[0], b, s_ref, y_ref);
  }
  for (std::size_t k = 0; k < root.size(); ++k) {
    const Motor m = root[k];  // a copy: remaining may alias root
    const glm::vec3 t = (motor_transform_point(m, origin) - t_ref) * keep;
    float s = 1.0f, y = 0.0f;
    if (extract_yaw) {
      yaw_of(m, b, s, y);
      // Y_k · ~Y_ref: both rotations are in the same plane, so the product is (s s_r + y y_r) + (y s_r − s y_r) B.
      const float s2 = s * s_ref + y * y_ref, y2 = y * s_ref - s * y_ref;
      s = s2, y = y2;
    }
    // motor_from_trs takes the rotor through its quaternion; the yaw's bivector goes to its own blade.
    float r[4] = {s, 0.0f, 0.0f, 0.0f};  // rs r12 r13 r23
    r[b == blade::e12 ? 1 : b == blade::e13 ? 2 : 3] = y;
    Motor tr;
    kernels::motor_from_trs(t.x, t.y, t.z, r[0], r[1], r[2], r[3], 1.0f, tr.c.data());
    track[k] = tr;
    remaining[k] = motor_mul(motor_reverse(tr), m);
  }
  return true;
}

Motor apply_root_motion(const Motor& track, const Motor& remaining) { return motor_mul(track, remaining); }

Motor root_motion_delta(const Motor& previous, const Motor& current) {
  return motor_mul(motor_reverse(previous), current);
}

}  // namespace cga
