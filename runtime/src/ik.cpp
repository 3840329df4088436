// TwoBoneIKJob and AimIKJob (see ik.hpp). The geometry is in the generated kernels (ik_two_bone: spheres,
// circle, pole plane, point pair; ik_aim: the shortest-arc rotor); this file does what a script cannot:
// the clamps, the soften split, the degenerate cases, and turning model-space rotations into local
// corrections with the weight.
#include "cga/runtime/ik.hpp"

#include <algorithm>
#include <cmath>

#include <ik_aim.hpp>
#include <ik_two_bone.hpp>

#include "cga/runtime/motor.hpp"
#include "detail/ik_weight.hpp"

namespace cga {

namespace {

// Relative size below which a length counts as zero (float rounding of unit-sized rigs is ~1e-7).
constexpr float kTiny = 1e-6f;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// The rotation part of a model-space motor (its rotor blades 1 e12 e13 e23, normalized: a scaled motor's
// rotor part is the rotor times a positive factor).
glm::quat joint_rotation(const Motor& m) {
  const glm::quat q = quat_from_rotor(m.c[0], m.c[1], m.c[2], m.c[4]);
  const float n = glm::length(q);
  return n > 0.0f ? q / n : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
}

// Where the motor puts the origin: the generated transform_point at x = y = z = 0, with the terms that carry
// x, y or z dropped (they are exact zeros there) and the remaining sums in the kernel's order, so the result
// is bit-identical to motor_transform_point(m, 0) (a caller's own positions match the job's; a target a few
// thousandths from the start turns the last bit of the start into a visible direction). Written out because
// a call with zero arguments does not fold (0 * x is not 0 for IEEE floats): 20 products instead of ~60
// operations (profile: the three point transforms were 27 % of a solve).
glm::vec3 joint_position(const Motor& m) {
  const float* M = m.c.data();
  const float g0 = M[7] + M[0], g1 = M[1] + M[9], g2 = M[2] + M[10], g3 = M[4] + M[11];
  const float t36 = M[1] * M[9] + M[2] * M[10] + M[4] * M[11] + M[7] * M[0];
  const float w = 2.0f * t36 + M[9] * M[9] + M[1] * M[1] + M[10] * M[10] + M[2] * M[2] + M[11] * M[11] +
                  M[4] * M[4] + M[7] * M[7] + M[0] * M[0];
  return glm::vec3(-2.0f * (M[8] * g3 + M[3] * g0 + M[5] * g1 + M[6] * g2),
                   2.0f * (M[8] * g2 + M[3] * g1 - M[5] * g0 - M[6] * g3),
                   -2.0f * (M[8] * g1 + M[6] * g0 - M[3] * g2 - M[5] * g3)) / w;
}

// A unit vector perpendicular to v (v non-zero): the cross product with the axis v is least aligned with.
glm::vec3 any_perpendicular(const glm::vec3& v) {
  const glm::vec3 a = std::abs(v.x) <= std::abs(v.y) && std::abs(v.x) <= std::abs(v.z) ? glm::vec3(1, 0, 0)
                      : std::abs(v.y) <= std::abs(v.z)                                  ? glm::vec3(0, 1, 0)
                                                                                         : glm::vec3(0, 0, 1);
  return glm::normalize(glm::cross(v, a));
}

// The unit quaternion turning f onto d by the shortest arc (generated ik_aim), f and d non-zero. Opposite
// directions have no shortest arc: a half turn about `half_turn_axis` when it is perpendicular to f, else
// about any perpendicular. `fd` is |f| |d| when the caller knows it (the bone lengths; it only scales the
// degenerate test), else negative (two square roots here).
glm::quat shortest_arc(const glm::vec3& f, const glm::vec3& d, const glm::vec3& half_turn_axis = glm::vec3(0.0f),
                       float fd = -1.0f) {
  float r[4];
  kernels::ik_aim(f.x, f.y, f.z, d.x, d.y, d.z, r);
  const glm::quat q = quat_from_rotor(r[0], r[1], r[2], r[3]);
  // |R|^2 = 2 |f||d| (|f||d| + f.d): zero (to rounding) for opposite directions.
  const float n2 = glm::dot(q, q);
  if (fd < 0.0f) fd = glm::length(f) * glm::length(d);
  if (n2 > 1e-10f * fd * fd) return q / std::sqrt(n2);
  const float a = glm::length(half_turn_axis);
  const glm::vec3 axis = a > 0.0f && std::abs(glm::dot(half_turn_axis, f)) <= kTiny * a * glm::length(f)
                             ? half_turn_axis / a
                             : any_perpendicular(f);
  return glm::quat(0.0f, axis.x, axis.y, axis.z);
}

// The turn about the unit `axis` taking x onto y, both perpendicular to it (to rounding), by its signed
// angle. Not the shortest-arc rotor: near a half turn its scalar part |x||y| + x.y cancels (and its own axis
// is ill-conditioned), while the angle about a given axis is well-conditioned there.
glm::quat turn_about(const glm::vec3& x, const glm::vec3& y, const glm::vec3& axis) {
  return glm::angleAxis(std::atan2(glm::dot(glm::cross(x, y), axis), glm::dot(x, y)), axis);
}

using ik_detail::rotation_motor;
using ik_detail::weighted;

}  // namespace

void apply_ik_correction(Motor& local, const Motor& correction) { local = motor_mul(local, correction); }

// ------------------------------------------------------------------------------------------------ two-bone

bool TwoBoneIKJob::Validate() const {
  if (!start_joint || !mid_joint || !end_joint || !start_joint_correction || !mid_joint_correction) return false;
  if (!finite(target) || !finite(pole_vector)) return false;
  if (!(weight >= 0.0f && weight <= 1.0f) || !(soften >= 0.0f && soften <= 1.0f) || !std::isfinite(twist_angle))
    return false;
  for (const Motor* m : {start_joint, mid_joint, end_joint})
    for (float c : m->c)
      if (!std::isfinite(c)) return false;
  if (positions && (!finite(positions[0]) || !finite(positions[1]) || !finite(positions[2]))) return false;
  return true;
}

bool TwoBoneIKJob::Run() const {
  if (!Validate()) return false;
  const glm::vec3 s = positions ? positions[0] : joint_position(*start_joint);
  const glm::vec3 m = positions ? positions[1] : joint_position(*mid_joint);
  const glm::vec3 e = positions ? positions[2] : joint_position(*end_joint);
  const glm::vec3 v1 = m - s, v2 = e - m, t = target - s;
  const float l1 = glm::length(v1), l2 = glm::length(v2), chain = l1 + l2, d = glm::length(t);
  const float tiny = kTiny * std::max(chain, d);
  // The direction to the target; a target on the start keeps the chain's current direction.
  glm::vec3 u = d > tiny ? t / d : e - s;
  if (!(d > tiny)) u = glm::length(u) > tiny ? glm::normalize(u) : l1 > tiny ? v1 / l1 : glm::vec3(1, 0, 0);

  glm::quat a(1.0f, 0.0f, 0.0f, 0.0f), b(1.0f, 0.0f, 0.0f, 0.0f);  // model-space turns of bone 1 and bone 2
  bool hit = false;
  if (!(chain > tiny)) {
    hit = d <= tiny;  // a chain of length 0 reaches only its start
  } else if (!(l1 > tiny) || !(l2 > tiny)) {
    // One bone of length 0: the other one aims at the target (from the start; the mid joint is there or the
    // end joint is at the mid joint).
    if (l1 > tiny) {
      a = b = shortest_arc(v1, u);
    } else {
      b = shortest_arc(v2, u);
    }
    hit = std::abs(d - chain) <= kTiny * chain;
  } else {
    // Clamp into the reachable range, then split the soften range for the kernel (ik_two_bone.clu).
    const float dc = std::clamp(d, std::abs(l1 - l2), chain);
    const float da = chain * soften, ds = chain - da;
    const bool soft = ds > tiny && dc > da;
    // The pole direction off the chain axis; on the axis (or zero): the current bend, else any perpendicular.
    glm::vec3 p = pole_vector - glm::dot(pole_vector, u) * u;
    if (!(glm::length(p) > kTiny * glm::length(pole_vector)) || !(glm::length(p) > 0.0f)) {
      p = v1 - glm::dot(v1, u) * u;
      if (!(glm::length(p) > kTiny * l1)) p = any_perpendicular(u);
    }
    p = glm::normalize(p);
    float tt[3], x[4];
    kernels::ik_two_bone(soft ? da : dc, soft ? ds : 1.0f, soft ? dc - da : 0.0f, u.x, u.y, u.z, l1, l2, p.x, p.y,
                         p.z, tt, x);
    const glm::vec3 reach(tt[0], tt[1], tt[2]), elbow = glm::vec3(x[0], x[1], x[2]) / x[3];
    a = shortest_arc(v1, elbow, p, l1 * l1);
    // Bone 2 aims from where bone 1 actually put the mid joint (a v1, of length l1 exactly), not from the
    // kernel's elbow: near full extension or folded flat the elbow's rounding (sqrt of a cancelling B.B) would
    // otherwise tilt bone 2 to first order.
    b = shortest_arc(a * v2, reach - a * v1, p, l2 * l2) * a;
    hit = glm::length(reach - t) <= 1e-5f * chain;
  }
  if (twist_angle != 0.0f) {
    const glm::quat twist = glm::angleAxis(twist_angle, u);
    a = twist * a, b = twist * b;
  }
  // Local corrections: the start's model rotation Qs becomes a Qs, the mid's Qm becomes b Qm.
  const glm::quat qs = joint_rotation(*start_joint), qm = joint_rotation(*mid_joint);
  const glm::quat c1 = glm::conjugate(qs) * a * qs;
  const glm::quat c2 = glm::conjugate(a * qm) * b * qm;
  *start_joint_correction = rotation_motor(weighted(c1, weight));
  *mid_joint_correction = rotation_motor(weighted(c2, weight));
  if (reached) *reached = hit && weight >= 1.0f;
  return true;
}

// ------------------------------------------------------------------------------------------------- aim

bool AimIKJob::Validate() const {
  if (!joint || !joint_correction) return false;
  if (!finite(target) || !finite(forward) || !finite(up) || !finite(pole_vector)) return false;
  if (!(glm::length(forward) > 0.0f)) return false;
  if (!(weight >= 0.0f && weight <= 1.0f) || !std::isfinite(twist_angle)) return false;
  for (float c : joint->c)
    if (!std::isfinite(c)) return false;
  return true;
}

bool AimIKJob::Run() const {
  if (!Validate()) return false;
  const glm::quat q = joint_rotation(*joint);
  const glm::vec3 to_target = target - joint_position(*joint);
  const float d = glm::length(to_target);
  glm::quat a(1.0f, 0.0f, 0.0f, 0.0f);
  const bool aimed = d > kTiny * std::max(1.0f, glm::length(target));
  if (aimed) {
    const glm::vec3 dir = to_target / d;
    a = shortest_arc(q * forward, dir);
    // Twist about the aim direction: the carried up axis onto the pole vector, both projected off it.
    const glm::vec3 up_now = a * (q * up);
    const glm::vec3 x = up_now - glm::dot(up_now, dir) * dir, y = pole_vector - glm::dot(pole_vector, dir) * dir;
    if (glm::length(x) > kTiny * glm::length(up) && glm::length(y) > kTiny * glm::length(pole_vector))
      a = turn_about(x, y, dir) * a;
    if (twist_angle != 0.0f) a = glm::angleAxis(twist_angle, dir) * a;
  }
  *joint_correction = rotation_motor(weighted(glm::conjugate(q) * a * q, weight));
  if (reached) *reached = aimed && weight >= 1.0f;
  return true;
}

}  // namespace cga
