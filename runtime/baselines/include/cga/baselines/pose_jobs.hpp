// The GLM baselines the benchmarks, tests, demo and GPU comparisons measure the motor pipeline against: the
// same four pose jobs as cga::runtime's (jobs.hpp), one representation each, in plain GLM.
//   Transform   quaternion slerp + vector lerp + scale lerp locally, glm::mat4 in model space, mat3x4 palettes
//   DualQuat    glm::dualquat (rigid part) + float uniform scale per joint, dual-quaternion palettes
// Not part of cga::runtime's API (they exist only for comparison). At the bottom: an any-mode pose pipeline
// (PoseBuffer, sample/blend/local_to_model/palette over every PoseMode, pose_mode.hpp) for code that compares
// the motor modes with the baselines.
#pragma once

#include <span>
#include <vector>

#include "cga/baselines/pose_mode.hpp"
#include "cga/runtime/animation.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/types.hpp"

namespace cga::baseline {

// ------------------------------------------------------------------------------------------ Transform / mat4

// Per joint: slerp of the rotation (normalized), lerp of translation and scale, between the clip's keys.
struct TransformSamplingJob {
  const Clip* clip = nullptr;
  float time = 0.0f;                // finite; clamped as SamplingJob's
  std::span<Transform> output;      // size >= joint count

  bool Validate() const;
  bool Run() const;
};

struct TransformLayer {
  float weight = 0.0f;
  std::span<const Transform> transforms;  // size >= output.size() when weight > 0
};
// Quaternions summed with the sign fix and normalized (as ozz does), translations and scales averaged.
struct TransformBlendingJob {
  std::span<const TransformLayer> layers;
  std::span<Transform> output;

  bool Validate() const;
  bool Run() const;
};

// model[j] = model[parent] * TRS(local[j]) with GLM 4x4 matrices.
struct MatrixLocalToModelJob {
  const Skeleton* skeleton = nullptr;
  std::span<const Transform> input;  // size >= joint count
  std::span<glm::mat4> output;       // size >= joint count

  bool Validate() const;
  bool Run() const;
};

// palette[k] = row-major 3x4 of model[joint_remap[k]] * inverse_bind[k].
struct MatrixPaletteJob {
  std::span<const int> joint_remap;
  std::span<const glm::mat4> inverse_bind;  // size >= joint_remap.size()
  std::span<const glm::mat4> model;
  std::span<glm::mat3x4> output;            // size >= joint_remap.size()

  bool Validate() const;
  bool Run() const;
};

// ------------------------------------------------------------------------------- dual quaternion + scale

// Per joint: the dual quaternions' lerp with the sign fix, normalized; the scale lerped apart.
struct DualQuatSamplingJob {
  const Clip* clip = nullptr;
  float time = 0.0f;
  std::span<glm::dualquat> output;  // size >= joint count
  std::span<float> output_scales;   // size >= joint count

  bool Validate() const;
  bool Run() const;
};

struct DualQuatLayer {
  float weight = 0.0f;
  std::span<const glm::dualquat> dual_quats;
  std::span<const float> scales;
};
// Dual quaternions summed with the sign fix and normalized, scales averaged.
struct DualQuatBlendingJob {
  std::span<const DualQuatLayer> layers;
  std::span<glm::dualquat> output;
  std::span<float> output_scales;

  bool Validate() const;
  bool Run() const;
};

// Dual quaternions by GLM with the parent's scale folded into the child's translation (a dual quaternion holds
// no scale; output_scales carries the accumulated uniform scale).
struct DualQuatLocalToModelJob {
  const Skeleton* skeleton = nullptr;
  std::span<const glm::dualquat> input;
  std::span<const float> input_scales;
  std::span<glm::dualquat> output;
  std::span<float> output_scales;

  bool Validate() const;
  bool Run() const;
};

// The rigid part only: dual quaternion skinning cannot apply a scale.
struct DualQuatPaletteJob {
  std::span<const int> joint_remap;
  std::span<const glm::dualquat> inverse_bind;  // rigid part
  std::span<const glm::dualquat> model;
  std::span<const float> model_scales;
  std::span<glm::dualquat> output;

  bool Validate() const;
  bool Run() const;
};

// Helpers: the TRS of a transform as a row-major 3x4 palette matrix, and the rigid translation of a unit
// dual quaternion.
glm::mat3x4 to_palette_matrix(const glm::mat4& m);
glm::vec3 dual_quat_translation(const glm::dualquat& q);

// ------------------------------------------------------------------------------------ any-mode pipeline

// Owning storage of one pose in every representation (only the mode's arrays are used).
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

// Inverse bind data of a mesh in each representation, computed once (the motors by the generated kernel).
struct InverseBind {
  std::vector<Motor> motors;
  std::vector<glm::mat4> matrices;
  std::vector<glm::dualquat> dual_quats;  // rigid part
  std::vector<float> scales;
};
InverseBind make_inverse_bind(const SkinnedMesh& mesh);

// Palettes of one mesh in every representation (only the mode's is written).
struct PaletteBuffer {
  std::vector<Motor> motors;
  std::vector<glm::mat3x4> matrices;
  std::vector<glm::dualquat> dual_quats;
  PaletteBuffer() = default;
  explicit PaletteBuffer(std::size_t entries) : motors(entries), matrices(entries), dual_quats(entries) {}
};

struct PoseLayer {
  float weight = 0.0f;
  const PoseBuffer* pose = nullptr;
};

// Each runs the job of the mode's representation (motor modes: cga::runtime's jobs in that Interpolation)
// and returns its Run().
bool sample(PoseMode mode, const Clip& clip, float time, PoseBuffer& out);
bool blend(PoseMode mode, std::span<const PoseLayer> layers, PoseBuffer& out);
bool local_to_model(PoseMode mode, const Skeleton& skeleton, const PoseBuffer& local, PoseBuffer& model);
bool palette(PoseMode mode, std::span<const int> joint_remap, const InverseBind& inverse_bind,
             const PoseBuffer& model, PaletteBuffer& out);
// The model-space position of joint j of a model pose.
glm::vec3 joint_position(PoseMode mode, const PoseBuffer& model, int j);

}  // namespace cga::baseline
