// Skinning palettes as flat float arrays, the layout the GPU backends read (cga::gpu's shaders, cga::cuda's
// kernels, the page): each entry prepared by its method's bone kernel (skinning_methods.hpp), 4 x entry_vec4s
// floats, the layout of the inputs of the method's generated blend. The CPU loop prepares the same entries
// (SkinningJob::Run on the generated path).
#pragma once

#include <algorithm>
#include <cstddef>
#include <span>
#include <vector>

#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

inline std::size_t packed_palette_floats(SkinningMethod method) { return prepared_entry_floats(method); }

// Prepares the entries of the method's palette (its table row's PALETTE: matrices, dual_quats or motors; the
// other spans are ignored) into out, prepared_entry_floats(method) floats each. Throws std::invalid_argument
// when out is too small. Runs the generated bone kernels (runtime/src/skinning/prepare.cpp).
void prepare_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                     std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors, std::span<float> out);

// Appends the method's prepared palette to `out`. Call once per instance to build a crowd's palettes.
inline void append_packed_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                                  std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                                  std::vector<float>& out) {
  const SkinningMethodInfo& info = skinning_method_info(method);
  const std::size_t entries = info.palette == PaletteKind::matrices     ? matrices.size()
                              : info.palette == PaletteKind::dual_quats ? dual_quats.size()
                                                                         : motors.size();
  const std::size_t at = out.size();
  out.resize(at + packed_palette_floats(method) * entries);
  prepare_palette(method, matrices, dual_quats, motors, std::span<float>(out).subspan(at));
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
