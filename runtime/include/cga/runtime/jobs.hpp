// ozz-style animation jobs: each is a struct of non-owning spans plus the mode, with Validate() (sizes and
// pointers) and Run() (returns false when invalid; never allocates). One pose is a set of per-joint arrays in
// the representation of its interpolation mode:
//   paper / nlerp / screw   Motor per joint
//   glm_matrix              Transform (TRS) per joint locally, glm::mat4 in model space
//   glm_dualquat            glm::dualquat (rigid part) + float scale per joint
//
//   SamplingJob         clip, time -> local pose       (binary search per joint, time clamped to [0, duration])
//   BlendingJob         N weighted local poses -> one  (cross-fade = two layers with weights 1-a, a)
//   LocalToModelJob     local pose -> model pose       (parents first: model[j] = model[parent] * local[j])
//   SkinningPaletteJob  model pose -> a mesh's palette (model[remap[k]] * inverse_bind[k])
#pragma once

#include <span>
#include <vector>

#include "cga/runtime/animation.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

// Owning storage of one pose in every representation (only the mode's arrays are used); for convenience.
struct PoseBuffer {
  std::vector<Motor> motors;
  std::vector<Transform> transforms;
  std::vector<glm::mat4> matrices;
  std::vector<glm::dualquat> dual_quats;
  std::vector<float> scales;
  PoseBuffer() = default;
  explicit PoseBuffer(std::size_t joints)
      : motors(joints), transforms(joints), matrices(joints), dual_quats(joints), scales(joints, 1.0f) {}
};

struct SamplingJob {
  const Clip* clip = nullptr;
  // Seconds; clamped to [0, clip->duration] (before the first key: the first key; after the last: the last).
  float time = 0.0f;
  Interpolation mode = Interpolation::paper;
  // Output of the mode, one per joint: motors (paper, nlerp, screw), transforms (glm_matrix),
  // dual_quats + scales (glm_dualquat).
  std::span<Motor> out_motors;
  std::span<Transform> out_transforms;
  std::span<glm::dualquat> out_dual_quats;
  std::span<float> out_scales;

  bool Validate() const;
  bool Run() const;
};

// One input pose of a blend and its weight (a weight <= 0 leaves the layer out).
struct BlendLayer {
  float weight = 0.0f;
  std::span<const Motor> motors;
  std::span<const Transform> transforms;
  std::span<const glm::dualquat> dual_quats;
  std::span<const float> scales;
};

// Weighted blend of N poses, weights normalized by their sum (which must be > 0):
//   paper         the weighted sum of the motors (eq. 25 with N terms), not normalized, no sign fix.
//   nlerp         weighted sum with each motor's sign matched to the first layer's, then normalized.
//   screw         screw interpolation folded over the layers: acc = screw(acc, layer k, w_k / (w_0+..+w_k));
//                 exact for two layers, order-dependent (and approximate) for more.
//   glm_matrix    quaternions summed with the sign fix and normalized (as ozz does), translations and
//                 scales averaged.
//   glm_dualquat  dual quaternions summed with the sign fix and normalized, scales averaged.
struct BlendingJob {
  Interpolation mode = Interpolation::paper;
  std::span<const BlendLayer> layers;
  std::span<Motor> out_motors;
  std::span<Transform> out_transforms;
  std::span<glm::dualquat> out_dual_quats;
  std::span<float> out_scales;

  bool Validate() const;
  bool Run() const;
};

// Model space from local space down the skeleton. Motors compose by the generated motor product; matrices
// by GLM; dual quaternions by GLM with the parent's scale folded into the child's translation (a dual
// quaternion holds no scale, model_scales carries the accumulated uniform scale).
struct LocalToModelJob {
  const Skeleton* skeleton = nullptr;
  Interpolation mode = Interpolation::paper;
  std::span<const Motor> local_motors;
  std::span<const Transform> local_transforms;
  std::span<const glm::dualquat> local_dual_quats;
  std::span<const float> local_scales;
  std::span<Motor> model_motors;
  std::span<glm::mat4> model_matrices;
  std::span<glm::dualquat> model_dual_quats;
  std::span<float> model_scales;

  bool Validate() const;
  bool Run() const;
};

// Inverse bind data of a mesh in each representation, computed once (the motors by the generated kernel).
struct InverseBind {
  std::vector<Motor> motors;
  std::vector<glm::mat4> matrices;
  std::vector<glm::dualquat> dual_quats;  // rigid part
  std::vector<float> scales;
};
InverseBind make_inverse_bind(const SkinnedMesh& mesh);

// palette[k] = model[joint_remap[k]] * inverse_bind[k], in the mode's skinning palette type. The dual
// quaternion palette is the rigid part only: dual quaternion skinning cannot apply a scale.
struct SkinningPaletteJob {
  Interpolation mode = Interpolation::paper;
  std::span<const int> joint_remap;
  const InverseBind* inverse_bind = nullptr;
  std::span<const Motor> model_motors;
  std::span<const glm::mat4> model_matrices;
  std::span<const glm::dualquat> model_dual_quats;
  std::span<const float> model_scales;
  std::span<Motor> out_motors;          // MotorPalette (paper, nlerp, screw)
  std::span<glm::mat3x4> out_matrices;  // MatrixPalette (glm_matrix)
  std::span<glm::dualquat> out_dual_quats;  // DualQuatPalette (glm_dualquat)

  bool Validate() const;
  bool Run() const;
};

// Helpers for tests and tools: the TRS of a transform as a row-major 3x4 palette matrix, and the rigid
// translation of a unit dual quaternion.
glm::mat3x4 to_palette_matrix(const glm::mat4& m);
glm::vec3 dual_quat_translation(const glm::dualquat& q);

}  // namespace cga
