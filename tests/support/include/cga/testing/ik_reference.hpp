// Two-bone and aim IK with plain vectors and quaternions (law of cosines, glm::rotation), the reference the
// IK tests check the generated-kernel jobs against and the baseline of the IK benchmark. Same conventions as
// cga::TwoBoneIKJob / AimIKJob: model-space inputs, local-space rotation corrections; no softening, no
// degenerate-case handling (callers give well-formed chains).
#pragma once

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/quaternion.hpp>

namespace cga::testing {

struct TwoBoneReference {
  glm::vec3 elbow{0.0f};  // relative to the start joint
  glm::vec3 reach{0.0f};  // the clamped target, relative to the start joint
  glm::quat start_correction{1, 0, 0, 0}, mid_correction{1, 0, 0, 0};
};

// s, m, e: joint positions; qs, qm: the start and mid joints' model rotations.
inline TwoBoneReference two_bone_reference(const glm::vec3& s, const glm::vec3& m, const glm::vec3& e,
                                           const glm::quat& qs, const glm::quat& qm, const glm::vec3& target,
                                           const glm::vec3& pole) {
  TwoBoneReference r;
  const glm::vec3 v1 = m - s, v2 = e - m, t = target - s;
  const float l1 = glm::length(v1), l2 = glm::length(v2), d = glm::length(t);
  const glm::vec3 u = t / d;
  const float dc = std::clamp(d, std::abs(l1 - l2), l1 + l2);
  const float x = (dc * dc + l1 * l1 - l2 * l2) / (2.0f * dc);  // the elbow's distance along the axis
  const float h = std::sqrt(std::max(l1 * l1 - x * x, 0.0f));
  const glm::vec3 p = glm::normalize(pole - glm::dot(pole, u) * u);
  r.elbow = x * u + h * p;
  r.reach = dc * u;
  const glm::quat a = glm::rotation(v1 / l1, glm::normalize(r.elbow));
  const glm::quat b = glm::rotation(glm::normalize(a * v2), glm::normalize(r.reach - r.elbow)) * a;
  r.start_correction = glm::conjugate(qs) * a * qs;
  r.mid_correction = glm::conjugate(a * qm) * b * qm;
  return r;
}

// The aim correction: forward (joint-local) onto the target, then up (joint-local) toward the pole.
inline glm::quat aim_reference(const glm::vec3& position, const glm::quat& q, const glm::vec3& target,
                               const glm::vec3& forward, const glm::vec3& up, const glm::vec3& pole) {
  const glm::vec3 dir = glm::normalize(target - position);
  glm::quat a = glm::rotation(glm::normalize(q * forward), dir);
  const glm::vec3 u = a * (q * up);
  const glm::vec3 x = u - glm::dot(u, dir) * dir, y = pole - glm::dot(pole, dir) * dir;
  // The twist about dir: the signed angle from x to y (glm::rotation's own axis is ill-conditioned near pi).
  a = glm::angleAxis(std::atan2(glm::dot(glm::cross(x, y), dir), glm::dot(x, y)), dir) * a;
  return glm::conjugate(q) * a * q;
}

}  // namespace cga::testing
