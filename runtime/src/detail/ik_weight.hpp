// The IK jobs' weighting of a correction (TwoBoneIKJob, AimIKJob, ChainIKJob): nlerp of its rotation from the
// identity by the job's weight, the short way, as a rotation motor.
#pragma once

#include <glm/gtc/quaternion.hpp>

#include "cga/runtime/motor.hpp"

namespace cga::ik_detail {

// nlerp from the identity toward the unit q by w (q's sign chosen for the short way).
inline glm::quat weighted(glm::quat q, float w) {
  if (w >= 1.0f) return q;
  if (q.w < 0.0f) q = -q;
  const glm::quat r = glm::quat(1.0f, 0.0f, 0.0f, 0.0f) * (1.0f - w) + q * w;
  return glm::normalize(r);
}

// The motor of the rotation q (its rotor blades 1, e12, e13, e23).
inline Motor rotation_motor(const glm::quat& q) {
  const auto r = rotor_from_quat(q);
  Motor m;
  m.c[0] = r[0], m.c[1] = r[1], m.c[2] = r[2], m.c[4] = r[3];
  return m;
}

}  // namespace cga::ik_detail
