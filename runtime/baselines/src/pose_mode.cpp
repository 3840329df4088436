// Names and conversions of the compared pose pipelines (see cga/baselines/pose_mode.hpp).
#include "cga/baselines/pose_mode.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace cga::baseline {

Interpolation to_interpolation(PoseMode m) {
  if (!uses_motors(m))
    throw std::invalid_argument(fmt::format("pose mode '{}' is a GLM baseline, not a motor mode", to_string(m)));
  return static_cast<Interpolation>(m);
}

std::string_view to_string(PoseMode mode) {
  switch (mode) {
    case PoseMode::paper:
    case PoseMode::nlerp:
    case PoseMode::screw: return cga::to_string(static_cast<Interpolation>(mode));
    case PoseMode::glm_matrix: return "glm-matrix";
    case PoseMode::glm_dualquat: return "glm-dualquat";
  }
  return "?";
}

PoseMode parse_pose_mode(std::string_view text) {
  for (PoseMode m : kAllPoseModes) {
    std::string alt(to_string(m));
    std::replace(alt.begin(), alt.end(), '-', '_');
    if (text == to_string(m) || text == alt) return m;
  }
  throw std::invalid_argument(
      fmt::format("unknown interpolation mode '{}' (choose paper, nlerp, screw, glm-matrix, glm-dualquat)", text));
}

}  // namespace cga::baseline
