// Animation data: a clip's per-joint key tracks as loaded (translation / rotation / scale keys at their own
// times) and, per joint, the merged keys the sampler reads: every key time of the joint's three tracks,
// with the full TRS at each and its precomputed representations (motor T*R*D, rigid T*R for the paper's
// lerp, dual quaternion for the GLM baseline). Also the interpolation modes.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "cga/runtime/motor.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

// How the sampler interpolates between two keys (and the blender between two poses): the motor modes.
//   paper   the paper's eq. 25/27: linear lerp of the rigid motors T*R, linear lerp of the dilators, their
//           product (generated motor_lerp_paper). Not a unit motor; points divide by the weight.
//   nlerp   lerp of the 12 motor coefficients with the antipodal sign fix, then normalized (projected back
//           onto T*R*D, see motor_to_transform).
//   screw   motor log/exp: constant-speed screw motion for the rigid part, geometric scale.
// The GLM matrix and dual-quaternion pipelines the motor modes are compared against are no Interpolation:
// cga::baselines names them (cga::baseline::PoseMode, cga/baselines/pose_mode.hpp).
enum class Interpolation { paper, nlerp, screw };
inline constexpr std::array<Interpolation, 3> kAllInterpolations{Interpolation::paper, Interpolation::nlerp,
                                                                 Interpolation::screw};
// "paper", "nlerp", "screw".
std::string_view to_string(Interpolation mode);
// Accepts to_string()'s names; throws std::invalid_argument listing the choices.
Interpolation parse_interpolation(std::string_view text);

struct VectorKey {
  float time;  // seconds
  glm::vec3 value;
};
// A rotation key: the file's quaternion and its rotor coefficients (rs, r12, r13, r23), converted once at
// load. Consecutive keys are made sign-continuous (q and -q are the same rotation) so that a lerp between
// neighbours never takes the long way.
struct RotationKey {
  float time;
  glm::quat value;
  std::array<float, 4> rotor;
};
struct ScaleKey {
  float time;
  float value;  // uniform; a non-uniform key was reported and replaced by the geometric mean
};

// One joint's keys as the file has them (each track at least one key; a joint the clip does not animate
// holds its rest transform as a single key).
struct JointTrack {
  std::vector<VectorKey> translations;
  std::vector<RotationKey> rotations;
  std::vector<ScaleKey> scales;
};

// One joint's merged keys (structure of arrays, same length, times strictly increasing, at least one).
struct JointKeys {
  std::vector<float> times;
  std::vector<Transform> transforms;
  std::vector<Motor> motors;            // T*R*D
  std::vector<RigidMotor> rigid;        // T*R (motor_lerp_paper's input)
  std::vector<glm::dualquat> dual_quats;  // rigid part, for the baseline
  std::size_t size() const { return times.size(); }
};

// The sampler's view of a clip's keys, built once by build_joint_keys: the union of all joints' key times
// cuts the clip into intervals inside which no joint has a key, so one binary search per sample finds, for
// every joint at once, its pair of keys (i, i+1). Per interval the pairs of all joints are stored as
// structure of arrays (joint index fastest, `stride` = joints rounded up to kLanes, padding lanes hold the
// identity), so the sampling loops read contiguous memory and vectorize across joints. It trades memory for
// speed: about (2 + 18 + 24) floats + one index per joint per interval (16 MB for a 31-joint, 2752-frame BVH).
struct ClipIntervals {
  static constexpr std::size_t kLanes = 16;  // one AVX-512 register of floats
  static constexpr std::size_t kRigid = 8, kMotor = 12;
  std::vector<float> times;       // interval u covers [times[u], times[u+1]) (the last one: the last key on)
  std::size_t joints = 0;
  std::size_t stride = 0;
  std::vector<std::uint32_t> key;  // [u*stride + j]: joint j's key i
  // alpha = (t - t0) * inv_span, in [0, 1); inv_span = 0 where the joint holds a key (before its first key,
  // after its last one, or a joint with one key).
  std::vector<float> t0, inv_span;             // [u*stride + j]
  std::vector<float> rigid0, rigid1;           // [(u*kRigid + c)*stride + j]: T*R of keys i and i+1
  std::vector<float> scale0, scale1;           // [u*stride + j]
  std::vector<float> motor0, motor_delta;      // [(u*kMotor + c)*stride + j]: T*R*D of key i, and the
                                               // sign-matched T*R*D of key i+1 minus it (nlerp)
  // Interval of time t (clamped to the first/last one).
  std::size_t find(float t) const;
  bool has_motors() const { return !rigid0.empty(); }
};

struct Clip {
  std::string name;
  float duration = 0.0f;  // seconds
  float ticks_per_second = 0.0f;
  std::vector<JointTrack> tracks;  // one per skeleton joint
  std::vector<JointKeys> keys;     // one per skeleton joint, built from tracks by build_joint_keys
  ClipIntervals intervals;         // the sampler's copy of `keys`, built with them
};

// Fills clip.keys from clip.tracks: the union of each joint's key times, each component interpolated at the
// times it has no key of its own (lerp; slerp for rotations), and the motor forms (generated kernels); then
// clip.intervals from clip.keys.
void build_joint_keys(Clip& clip);
// Rebuilds clip.intervals from clip.keys (after editing keys by hand).
void build_clip_intervals(Clip& clip);

}  // namespace cga
