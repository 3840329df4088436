// Which pipeline poses a character when motor modes are compared with the GLM baselines: one of the
// runtime's motor interpolation modes (cga::Interpolation: paper, nlerp, screw) or one of the baselines'
// representations (glm_matrix, glm_dualquat). The runtime's jobs know only the motor modes; this choice, and
// the names the demo's and the benchmarks' command lines accept for it, belong to the comparison code.
#pragma once

#include <array>
#include <string_view>

#include "cga/runtime/animation.hpp"

namespace cga::baseline {

//   paper, nlerp, screw  the runtime's motor jobs in that Interpolation mode (animation.hpp).
//   glm_matrix           quaternion slerp + vector lerp + scale lerp (GLM), to matrices in the hierarchy.
//   glm_dualquat         dual-quaternion lerp (GLM dualquat, sign fix) normalized; scale lerped apart.
enum class PoseMode { paper, nlerp, screw, glm_matrix, glm_dualquat };
inline constexpr std::array<PoseMode, 5> kAllPoseModes{PoseMode::paper, PoseMode::nlerp, PoseMode::screw,
                                                       PoseMode::glm_matrix, PoseMode::glm_dualquat};

// The motor modes share Interpolation's values, so converting between the two is a cast.
static_assert(static_cast<int>(PoseMode::paper) == static_cast<int>(Interpolation::paper) &&
                  static_cast<int>(PoseMode::nlerp) == static_cast<int>(Interpolation::nlerp) &&
                  static_cast<int>(PoseMode::screw) == static_cast<int>(Interpolation::screw),
              "PoseMode's motor modes must mirror cga::Interpolation");

// Whether the mode poses with the runtime's motor jobs (paper, nlerp, screw).
constexpr bool uses_motors(PoseMode m) {
  return m == PoseMode::paper || m == PoseMode::nlerp || m == PoseMode::screw;
}
constexpr PoseMode to_pose_mode(Interpolation m) { return static_cast<PoseMode>(m); }
// The motor mode of a mode that uses_motors(); throws std::invalid_argument for a GLM baseline.
Interpolation to_interpolation(PoseMode m);

// "paper", "nlerp", "screw", "glm-matrix", "glm-dualquat".
std::string_view to_string(PoseMode mode);
// Accepts to_string()'s names and the enum spelling (glm_matrix); throws std::invalid_argument listing the
// choices.
PoseMode parse_pose_mode(std::string_view text);

}  // namespace cga::baseline
