// Motion extraction (ozz-animation's MotionExtractor) in motor form: the root joint's translation and yaw
// are taken out of a clip's root keys into a root track, and re-applied at run time.
//   track_k     = T(sel(t_k − t_ref)) · Y_k · ~Y_ref    (rigid; Y = the yaw of the root's rotor)
//   remaining_k = ~track_k · M_k                        (the root's motion relative to the track)
// so that track_k · remaining_k = M_k (re-application is one motor product, apply_root_motion). The yaw is
// the twist of the swing-twist split about the up axis, in rotor form: of the rotor (1, e12, e13, e23) keep
// the scalar and the one bivector whose plane is perpendicular to `up` (y: e13, x: e23, z: e12), normalized;
// it equals the quaternion twist normalize(w, 0, y, 0) for y-up. sel() keeps the chosen translation axes.
// The translation is the image of the origin (generated transform_point), the rotor is the motor's rotor
// part a + b normalized (exact for T·R·D, see docs/runtime.md), the track is built by the generated
// motor_from_trs and the remaining part by the generated motor_mul and motor_reverse.
#pragma once

#include <span>

#include "cga/runtime/types.hpp"

namespace cga {

enum class MotionAxis { x = 0, y = 1, z = 2 };

enum class MotionReference {
  absolute,     // the track is the root's own translation and yaw (track_0 may be far from the identity)
  first_frame,  // relative to the first key: track_0 is the identity and remaining_0 = M_0
};

struct MotionExtractionJob {
  std::span<const Motor> root;       // the root joint's local motors, one per key/frame; size >= 1, unit motors
  bool extract_x = true;             // which translation axes go into the track (model space of the root)
  bool extract_y = false;            //   default: the ground plane of a y-up character
  bool extract_z = true;
  bool extract_yaw = true;           // the rotation about `up` goes into the track
  MotionAxis up = MotionAxis::y;
  MotionReference reference = MotionReference::first_frame;
  std::span<Motor> track;            // output: size == root.size(); rigid unit motors
  std::span<Motor> remaining;        // output: size == root.size(); may alias root

  bool Validate() const;  // sizes, finite root coefficients with a non-zero rotor part
  bool Run() const;       // false when invalid (outputs untouched)
};

// The root's motor with the track re-applied: track · remaining (generated motor_mul).
Motor apply_root_motion(const Motor& track, const Motor& remaining);

// The track's motion from one sample to the next, expressed in the previous sample's frame: ~prev · cur.
// A character's world motor advances by world = world · root_motion_delta(prev, cur) (ozz's accumulator);
// across a loop wrap, take delta(prev, last) · delta(first, cur).
Motor root_motion_delta(const Motor& previous, const Motor& current);

}  // namespace cga
