// Inverse kinematics jobs in ozz-animation's form, on kernels generated from CGA scripts:
//   TwoBoneIKJob  runtime/scripts/ik_two_bone.clu: the elbow where the spheres around the start (radius l1)
//                 and the target (radius l2) meet the pole plane, on the pole side, with softening;
//   AimIKJob      runtime/scripts/ik_aim.clu: the shortest-arc rotor between two directions, applied to the
//                 forward axis (onto the target) and then to the up axis (onto the pole vector).
// Inputs are model-space motors (LocalToModelJob's output); outputs are local-space rotation corrections, one
// per joint, applied to the local pose with apply_ik_correction (local[j] = local[j] * correction) before the
// model pose is recomputed. Joints may carry a uniform scale; only their rotation is corrected.
//
// Degenerate input gives a defined result, never NaN: zero-length bones (the other bone aims at the target),
// a target on the start joint (the current chain direction is kept), a pole vector along the chain axis or
// zero (the current bend direction, else any perpendicular), a target on the aiming joint (no rotation).
#pragma once

#include <span>

#include "cga/runtime/types.hpp"

namespace cga {

struct TwoBoneIKJob {
  // Model-space motors of the chain's three joints: start (e.g. shoulder), mid (elbow), end (hand). Required.
  const Motor* start_joint = nullptr;
  const Motor* mid_joint = nullptr;
  const Motor* end_joint = nullptr;
  // Optional: the model-space positions of start, mid and end (3 entries, finite) when the caller has them
  // (its own hierarchy, a previous job); the job then does not read them out of the motors. They must be
  // where the motors put the joints (motor_transform_point(*start_joint, 0) ...): the rotations still come
  // from the motors. nullptr: read off the motors (bit-identical to motor_transform_point).
  const glm::vec3* positions = nullptr;
  glm::vec3 target{0.0f};            // model space; must be finite
  glm::vec3 pole_vector{0.0f, 1.0f, 0.0f};  // model-space direction the mid joint bends toward; finite
  float weight = 1.0f;               // [0, 1]: 0 leaves the pose, 1 solves fully (corrections are nlerped)
  float soften = 1.0f;               // [0, 1]: above soften * chain length the reach approaches full
                                     // extension smoothly (1: no softening, the chain may straighten)
  float twist_angle = 0.0f;          // radians: the solved chain turned about the start -> target axis
  Motor* start_joint_correction = nullptr;  // outputs (required): local-space rotations
  Motor* mid_joint_correction = nullptr;
  bool* reached = nullptr;           // optional: the end joint reaches the target (weight 1, no clamp/soften)

  bool Validate() const;  // pointers, finite inputs (positions too when given), weight and soften in [0, 1]
  bool Run() const;       // false when invalid (outputs untouched)
};

struct AimIKJob {
  const Motor* joint = nullptr;      // model-space motor of the aiming joint (required)
  glm::vec3 target{0.0f};            // model space
  glm::vec3 forward{1.0f, 0.0f, 0.0f};  // joint-local axis to point at the target (non-zero)
  glm::vec3 up{0.0f, 1.0f, 0.0f};    // joint-local axis to turn toward the pole vector (zero: no twist)
  glm::vec3 pole_vector{0.0f, 1.0f, 0.0f};  // model space (zero: no twist)
  float twist_angle = 0.0f;          // radians about the aim direction, after the up alignment
  float weight = 1.0f;               // [0, 1]
  Motor* joint_correction = nullptr; // output (required): local-space rotation
  bool* reached = nullptr;           // optional: forward points at the target (weight 1, target off the joint)

  bool Validate() const;
  bool Run() const;
};

// local = local * correction (the correction's rotation applied in the joint's own frame, before its children).
void apply_ik_correction(Motor& local, const Motor& correction);

}  // namespace cga
