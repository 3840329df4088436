// ChainIKJob: inverse kinematics of a joint chain of any length by damped least squares (Levenberg-Marquardt
// steps) on a Jacobian from generated kernels, in ozz-animation's form (Validate()/Run(), model-space motors
// in, local-space corrections out, applied with apply_ik_correction as for TwoBoneIKJob).
//   runtime/scripts/ik_chain_joint.clu: one joint's Jacobian column (the end effector's point and two frame
//                                       directions turned about the joint's axis, derivatives by the angle;
//                                       without an orientation target the effector's derivative alone,
//                                       generated as ik_chain_joint_position);
//   runtime/scripts/ik_chain_rotor.clu: the rotor of a turn about an axis (the corrections).
// The forward kinematics of the iterations are motor_mul_rigid products; the C++ does the small solve
// (J J^T + lambda^2 I) y = r, dq = J^T y, the limits and the step control.
// ChainIKBatchJob solves many chains of one rig (a crowd) in lockstep, their Jacobian columns filled together
// by the same kernels as SIMD batch kernels (NAME.simd.hpp, Highway run-time dispatch).
#pragma once

#include <cstdint>
#include <span>

#include "cga/runtime/types.hpp"

namespace cga {

struct ChainIKJob {
  // Model-space motors of the chain, root first: joints[i] is the parent of joints[i + 1] (LocalToModelJob's
  // output for the chain's joints). At least one joint; joints may carry a uniform scale (only their
  // rotations are corrected).
  std::span<const Motor> joints;
  // Per joint: its hinge axis in its own (joint-local) frame, any non-zero length; a zero vector makes the
  // joint free (3 rotational degrees of freedom). Empty: every joint is free.
  std::span<const glm::vec3> axes;
  // Optional hinge limits, radians, per joint (both empty or both of the chain's size): the correction's angle
  // about the hinge axis stays in [min_angles[i], max_angles[i]]. The angle is relative to the input pose
  // (0 = the animated pose), so min <= 0 <= max is required. Ignored for free joints.
  std::span<const float> min_angles;
  std::span<const float> max_angles;
  glm::vec3 effector_offset{0.0f};   // the end effector in the tip joint's (last joint's) frame
  glm::vec3 target{0.0f};            // model space; finite
  // Optional: the model-space orientation the tip joint's frame should take (its rotation part; its
  // translation is ignored), weighted against the position by orientation_weight (>= 0; the orientation
  // residual is the difference of the frames' x and y axes times orientation_weight times the chain length).
  const Motor* target_orientation = nullptr;
  float orientation_weight = 1.0f;
  float weight = 1.0f;               // [0, 1]: 0 leaves the pose, 1 solves fully (corrections are nlerped)
  int max_iterations = 64;           // >= 1; Levenberg-Marquardt trials (rejected steps count)
  float tolerance = 1e-4f;           // > 0: reached when the effector is within tolerance * chain length
  float orientation_tolerance = 1e-3f;  // > 0, radians (about): the frame axes' difference, when oriented
  float damping = 0.05f;             // > 0: the least lambda, relative to the chain length
  std::span<Motor> corrections;      // output (required, the chain's size): local-space rotations
  bool* reached = nullptr;           // optional: the target (and orientation) is reached, weight 1
  int* iterations = nullptr;         // optional: the trials the solve took

  bool Validate() const;  // sizes, finite inputs, weight in [0, 1], limits around 0, positive parameters
  bool Run() const;       // false when invalid (outputs untouched)
};

// ChainIKJob for many chains of the same rig at once: every iteration fills the columns of all chains still
// iterating with one call of the SIMD batch kernel, then takes each chain's trial as ChainIKJob does (the
// same solve; results agree with ChainIKJob's to float rounding, not bit for bit: the batch kernel's lanes
// contract products into FMAs).
struct ChainIKBatchJob {
  int chain_joints = 0;                    // joints per chain (>= 1)
  std::span<const Motor> joints;           // chain c's model motors at [c chain_joints, (c + 1) chain_joints)
  std::span<const glm::vec3> axes;         // per joint of the rig, shared by every chain (empty: all free)
  std::span<const float> min_angles;       // per joint of the rig, shared (both empty: no limits)
  std::span<const float> max_angles;
  glm::vec3 effector_offset{0.0f};         // in the tip joint's frame, shared
  std::span<const glm::vec3> targets;      // one per chain
  std::span<const Motor> target_orientations;  // empty, or one per chain
  float orientation_weight = 1.0f;
  float weight = 1.0f;
  int max_iterations = 64;
  float tolerance = 1e-4f;
  float orientation_tolerance = 1e-3f;
  float damping = 0.05f;
  std::span<Motor> corrections;            // output: one per joint of every chain
  std::span<std::uint8_t> reached;         // optional: empty, or one per chain (1: reached)
  std::span<int> iterations;               // optional: empty, or one per chain

  bool Validate() const;  // sizes as above, and every chain valid as a ChainIKJob
  bool Run() const;       // false when invalid (outputs untouched)
};

}  // namespace cga
