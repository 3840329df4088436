// A seeded random source whose numbers are the same with every standard library: mt19937's output is
// specified by the standard, the distributions are not, so they are converted by hand. For the test meshes
// and poses (skinning_test_meshes.cpp, crowd_meshes.cpp).
#pragma once

#include <cstdint>
#include <random>

namespace cga::testing {

struct SeededRandom {
  std::mt19937 engine;
  explicit SeededRandom(std::uint32_t seed) : engine(seed) {}
  float uniform(float lo, float hi) {
    return lo + (hi - lo) * static_cast<float>(engine() >> 8) * (1.0f / 16777216.0f);
  }
  std::uint32_t below(std::uint32_t n) { return static_cast<std::uint32_t>(engine() % n); }
};

}  // namespace cga::testing
