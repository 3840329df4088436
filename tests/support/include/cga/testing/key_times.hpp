// A clip's key times: every joint's key times merged, sorted, without repeats. At these times every sampling
// mode returns keys, not interpolations, so tests compare methods there.
#pragma once

#include <algorithm>
#include <vector>

#include "cga/runtime/animation.hpp"

namespace cga::testing {

inline std::vector<float> key_times(const Clip& clip) {
  std::vector<float> times;
  for (const JointKeys& k : clip.keys) times.insert(times.end(), k.times.begin(), k.times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

}  // namespace cga::testing
