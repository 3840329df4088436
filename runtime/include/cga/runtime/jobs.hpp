// The pose jobs, ozz-animation style: each job has one concern and one data representation (motors), is a
// struct of non-owning spans, and has Validate() (sizes, pointers, modes; the size rule of every span is
// given next to it) and Run() (returns false when invalid; never allocates).
//
//   SamplingJob         clip, time -> local motors      (binary search per joint, time clamped to [0, duration])
//   BlendingJob         N weighted local poses -> one   (cross-fade = two layers with weights 1-a, a)
//   LocalToModelJob     local motors -> model motors    (parents first: model[j] = model[parent] * local[j])
//   SkinningPaletteJob  model motors -> a mesh's palette (model[remap[k]] * inverse_bind[k])
//
// A pose is an array of Motor, one per joint (types.hpp). The GLM matrix and dual-quaternion pipelines that
// the benchmarks and tests compare against are not part of cga::runtime: they live in cga::baselines
// (cga/baselines/pose_jobs.hpp). See docs/runtime.md for where a new job goes.
#pragma once

#include <span>
#include <vector>

#include "cga/runtime/animation.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

// The clip sampled at `time` in one of the motor modes (Interpolation: paper, nlerp, screw).
struct SamplingJob {
  const Clip* clip = nullptr;  // its keys built (build_joint_keys)
  // Seconds; clamped to [0, clip->duration] (before the first key: the first key; after the last: the last).
  // Must be finite.
  float time = 0.0f;
  Interpolation mode = Interpolation::paper;
  std::span<Motor> output;  // size >= the clip's joint count

  bool Validate() const;
  bool Run() const;
};

// One input pose of a blend and its weight (a weight <= 0 leaves the layer out; weights must be finite).
struct BlendLayer {
  float weight = 0.0f;
  std::span<const Motor> motors;  // size >= output.size() when weight > 0
  // Optional per-joint weights (partial blending, ozz's joint_weights): empty, or size >= output.size(),
  // each finite and >= 0; joint j then enters with weight * joint_weights[j].
  std::span<const float> joint_weights{};
};

// Weighted blend of N poses, weights normalized by their sum (which must be > 0):
//   paper   the weighted sum of the motors (eq. 25 with N terms), not normalized, no sign fix.
//   nlerp   weighted sum with each motor's sign matched to the first layer's (rotor_sign.hpp), normalized.
//   screw   screw interpolation folded over the layers: acc = screw(acc, layer k, w_k / (w_0+..+w_k));
//           exact for two layers, order-dependent (and approximate) for more.
// With per-joint weights every joint is normalized by its own weight sum; a joint whose sum is 0 takes
// rest_pose[j] (ozz's fallback), and without a rest pose such a joint makes the job invalid.
struct BlendingJob {
  Interpolation mode = Interpolation::paper;
  std::span<const BlendLayer> layers;  // at least one with weight > 0
  std::span<Motor> output;             // the joint count: every contributing layer holds at least this many
  std::span<const Motor> rest_pose{};  // optional: empty, or size >= output.size()

  bool Validate() const;
  bool Run() const;
};

// Model space from local space down the skeleton, by the generated motor product (the 8-blade rigid product
// when no local motor has a dilation; otherwise the split form, see src/jobs/common.hpp).
struct LocalToModelJob {
  const Skeleton* skeleton = nullptr;  // parents[j] < j
  std::span<const Motor> input;        // size >= joint count
  std::span<Motor> output;             // size >= joint count

  bool Validate() const;
  bool Run() const;
};

// The inverse bind motors of a mesh (one per palette entry), by the generated motor_from_trs kernel; a scale
// within float rounding of 1 is taken as 1, so rigid characters get exactly rigid inverse binds.
std::vector<Motor> make_inverse_bind_motors(const SkinnedMesh& mesh);

// palette[k] = model[joint_remap[k]] * inverse_bind[k] (the MotorPalette of the cga skinning methods).
struct SkinningPaletteJob {
  std::span<const int> joint_remap;     // each in [0, model.size())
  std::span<const Motor> inverse_bind;  // size >= joint_remap.size()
  std::span<const Motor> model;         // the model pose
  std::span<Motor> output;              // size >= joint_remap.size()

  bool Validate() const;
  bool Run() const;
};

}  // namespace cga
