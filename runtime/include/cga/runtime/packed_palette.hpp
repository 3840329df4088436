// Skinning palettes as flat float arrays, the layout both GPU backends read (cga::gpu's shaders and
// cga::cuda's kernels): lbs 12 floats per entry (the 3x4 matrix row by row), dqs 8 (real x y z w, dual
// x y z w), cga_points / cga_motors 12 (the motor's blades in order, which as std430 is the paper's mat3x4
// with blade k at column k/4, row k%4).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

inline std::size_t packed_palette_floats(SkinningMethod method) { return method == SkinningMethod::dqs ? 8 : 12; }

// Appends the method's palette (matrices for lbs, dual_quats for dqs, motors for the cga methods; the others
// are ignored) to `out`. Call once per instance to build a crowd's palettes.
inline void append_packed_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                                  std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                                  std::vector<float>& out) {
  switch (method) {
    case SkinningMethod::lbs:
      for (const glm::mat3x4& m : matrices)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 4; ++c) out.push_back(m[r][c]);
      break;
    case SkinningMethod::dqs: {
      const std::size_t at = out.size();
      out.resize(at + 8 * dual_quats.size());
      pack_dual_quats(dual_quats, std::span<float>(out).subspan(at));
      break;
    }
    case SkinningMethod::cga_points:
    case SkinningMethod::cga_motors:
      for (const Motor& m : motors) out.insert(out.end(), m.c.begin(), m.c.end());
      break;
  }
}

// The packed palettes of `instances` instances, instance i posed by palette i % count of the `count`
// palettes given per method (the crowd benchmarks' layout: few distinct poses, many instances).
inline std::vector<float> cycled_packed_palettes(SkinningMethod method, std::span<const MatrixPalette> matrices,
                                                 std::span<const DualQuatPalette> dual_quats,
                                                 std::span<const MotorPalette> motors, std::size_t instances) {
  const std::size_t count = std::max({matrices.size(), dual_quats.size(), motors.size()});
  std::vector<std::vector<float>> packed(count);
  for (std::size_t p = 0; p < count; ++p)
    append_packed_palette(method, p < matrices.size() ? matrices[p] : MatrixPalette{},
                          p < dual_quats.size() ? dual_quats[p] : DualQuatPalette{},
                          p < motors.size() ? motors[p] : MotorPalette{}, packed[p]);
  std::vector<float> out;
  if (count == 0) return out;
  out.reserve(packed[0].size() * instances);
  for (std::size_t i = 0; i < instances; ++i) out.insert(out.end(), packed[i % count].begin(), packed[i % count].end());
  return out;
}

}  // namespace cga
