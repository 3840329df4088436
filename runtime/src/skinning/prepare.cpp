// prepare_palette (packed_palette.hpp): every palette entry through its method's generated bone kernel into
// the prepared entry the generated blends read, on the CPU loop's and the GPU backends' side alike.
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
                     std::span<const Motor> motors, float* out) {
  constexpr std::size_t kFloats = 4 * K::kVec4s;
  const auto seq = std::make_index_sequence<K::kVec4s>{};
  if constexpr (K::kPalette == PaletteKind::matrices) {  // the rows are the entry
    static_assert(kFloats == 12, "a matrix entry is its 3 rows");
    for (std::size_t e = 0; e < matrices.size(); ++e)
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) out[kFloats * e + 4 * r + c] = matrices[e][r][c];
  } else if constexpr (K::kPalette == PaletteKind::dual_quats) {
    for (std::size_t e = 0; e < dual_quats.size(); ++e) {
      std::fill(out + kFloats * e, out + kFloats * (e + 1), 0.0f);
      prepare_from_dual_quat<K>(dual_quats[e], out + kFloats * e, seq);
    }
  } else {
    for (std::size_t e = 0; e < motors.size(); ++e) {
      std::fill(out + kFloats * e, out + kFloats * (e + 1), 0.0f);
      prepare_from_motor<K>(motors[e].c.data(), out + kFloats * e, seq);
    }
  }
}

std::size_t kind_size(PaletteKind kind, std::size_t matrices, std::size_t dual_quats, std::size_t motors) {
  return kind == PaletteKind::matrices ? matrices : kind == PaletteKind::dual_quats ? dual_quats : motors;
}

}  // namespace

void prepare_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                     std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors, std::span<float> out) {
  const SkinningMethodInfo& info = skinning_method_info(method);
  const std::size_t need =
      prepared_entry_floats(method) * kind_size(info.palette, matrices.size(), dual_quats.size(), motors.size());
  if (out.size() < need)
    throw std::invalid_argument("prepare_palette: " + std::string(info.name) + " needs " + std::to_string(need) +
                                " floats, the output holds " + std::to_string(out.size()));
  switch (method) {
#define CGA_METHOD_PREPARE(id, ...) \
  case SkinningMethod::id: return prepare_entries<id##_kernels>(matrices, dual_quats, motors, out.data());
    CGA_SKINNING_METHODS(CGA_METHOD_PREPARE)
#undef CGA_METHOD_PREPARE
  }
}

}  // namespace cga
