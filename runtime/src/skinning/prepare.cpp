// prepare_palette (packed_palette.hpp): every palette entry through its method's generated bone kernel into
// the prepared entry the generated blends read, on the CPU loop's and the GPU backends' side alike: packed
// (4 x entry_vec4s floats each) for the GPU buffers, one kEntry-float line each for the CPU loops
// (prepare_palette_lines, generated.hpp).
#include <algorithm>
#include <stdexcept>
#include <string>

#include "cga/runtime/packed_palette.hpp"
#include "generated.hpp"

namespace cga {
namespace {

using namespace skinning_detail;

template <class K>
void prepare_entries(std::span<const glm::mat3x4> matrices, std::span<const glm::dualquat> dual_quats,
                     std::span<const Motor> motors, float* out, std::size_t stride) {
  static_assert(K::kPalette != PaletteKind::matrices || K::kVec4s == 3, "a matrix entry is its 3 rows");
  const auto seq = std::make_index_sequence<K::kVec4s>{};
  const std::size_t entries = K::kPalette == PaletteKind::matrices     ? matrices.size()
                              : K::kPalette == PaletteKind::dual_quats ? dual_quats.size()
                                                                        : motors.size();
  for (std::size_t e = 0; e < entries; ++e) {
    float* entry = out + stride * e;
    std::fill(entry, entry + stride, 0.0f);
    if constexpr (K::kPalette == PaletteKind::matrices)  // the rows are the entry
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) entry[4 * r + c] = matrices[e][r][c];
    else if constexpr (K::kPalette == PaletteKind::dual_quats)
      prepare_from_dual_quat<K>(dual_quats[e], entry, seq);
    else
      prepare_from_motor<K>(motors[e].c.data(), entry, seq);
  }
}

std::size_t kind_size(PaletteKind kind, std::size_t matrices, std::size_t dual_quats, std::size_t motors) {
  return kind == PaletteKind::matrices ? matrices : kind == PaletteKind::dual_quats ? dual_quats : motors;
}

}  // namespace

namespace skinning_detail {

// The entries at `stride` floats each (stride >= prepared_entry_floats(method)), the floats after an entry's
// own zero.
void prepare_palette_strided(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                             std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                             std::span<float> out, std::size_t stride) {
  const SkinningMethodInfo& info = skinning_method_info(method);
  const std::size_t need = stride * kind_size(info.palette, matrices.size(), dual_quats.size(), motors.size());
  if (out.size() < need)
    throw std::invalid_argument("prepare_palette: " + std::string(info.name) + " needs " + std::to_string(need) +
                                " floats, the output holds " + std::to_string(out.size()));
  switch (method) {
#define CGA_METHOD_PREPARE(id, ...) \
  case SkinningMethod::id: return prepare_entries<id##_kernels>(matrices, dual_quats, motors, out.data(), stride);
    CGA_SKINNING_METHODS(CGA_METHOD_PREPARE)
#undef CGA_METHOD_PREPARE
  }
}

}  // namespace skinning_detail

void prepare_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                     std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors, std::span<float> out) {
  prepare_palette_strided(method, matrices, dual_quats, motors, out, prepared_entry_floats(method));
}

}  // namespace cga
