// The skinning methods: one row each, and the only place that names a method. C++ (SkinningMethod and
// skinning_method_info()), CMake (runtime/cmake/SkinningMethods.cmake reads the rows below: the kernels to
// generate, the GPU programs, the page's method list) and through them GL, CUDA, the web page and the demo
// iterate this table. A method is two scripts under runtime/scripts/skin:
//   BONE   the per-bone prepare: the method's palette entry (a matrix, dual quaternion or motor) to the
//          entry the blend reads, once per bone and frame; `none` when the entry is the palette's own
//          (lbs: the matrix rows are the entry)
//   BLEND  the per-vertex blend: four entries, four weights, the rest position and normal to the skinned
//          position and (unnormalized) normal; its entry inputs are VEC4S multivectors of at most 4 blades
//          each, which is the entry's layout everywhere: VEC4S vec4s (4 VEC4S floats, a 3-blade input padded)
// Columns: ID, NAME (CLI, page), PALETTE (what SkinningJob and the GPU backends take: matrices, dual_quats or
// motors), BONE, BLEND, VEC4S, colour R G B (pictures, demo, page). A row's GPU code is its position.
// Keep each row on one line: CMake parses them.
#pragma once

#include <array>
#include <cstddef>
#include <string_view>

// clang-format off
#define CGA_SKINNING_METHODS(X) \
  X(lbs, "lbs", matrices, none, skin_matrices, 3, 0.85f, 0.55f, 0.35f) \
  X(dqs, "dqs", dual_quats, bone_dual_quat, skin_dual_quats, 2, 0.45f, 0.65f, 0.85f) \
  X(cga_points, "cga-points", motors, bone_motor_rows, skin_matrices, 3, 0.85f, 0.75f, 0.35f) \
  X(cga_motors, "cga-motors", motors, bone_motor_split, skin_motors, 3, 0.45f, 0.80f, 0.50f) \
  X(cga_log, "cga-log", motors, bone_motor_log, skin_motor_logs, 4, 0.70f, 0.50f, 0.85f)
// clang-format on

namespace cga {

enum class SkinningMethod {
#define CGA_METHOD_ID(id, ...) id,
  CGA_SKINNING_METHODS(CGA_METHOD_ID)
#undef CGA_METHOD_ID
};

// What a method's palette holds (SkinningJob's matrices, dual_quats or motors span).
enum class PaletteKind { matrices, dual_quats, motors };

struct SkinningMethodInfo {
  SkinningMethod method;
  std::string_view name;          // "cga-motors"
  PaletteKind palette;
  std::string_view bone_script;   // "none" or the script's stem
  std::string_view blend_script;
  std::size_t entry_vec4s;        // the prepared entry: this many vec4s
  std::array<float, 3> colour;
};

inline constexpr std::array kSkinningMethods{
#define CGA_METHOD_INFO(id, name, palette, bone, blend, vec4s, r, g, b) \
  SkinningMethodInfo{SkinningMethod::id, name, PaletteKind::palette, #bone, #blend, vec4s, {r, g, b}},
    CGA_SKINNING_METHODS(CGA_METHOD_INFO)
#undef CGA_METHOD_INFO
};

inline constexpr std::size_t kSkinningMethodCount = kSkinningMethods.size();

inline constexpr std::array<SkinningMethod, kSkinningMethodCount> kAllSkinningMethods = [] {
  std::array<SkinningMethod, kSkinningMethodCount> out{};
  for (std::size_t i = 0; i < out.size(); ++i) out[i] = kSkinningMethods[i].method;
  return out;
}();

constexpr const SkinningMethodInfo& skinning_method_info(SkinningMethod method) {
  return kSkinningMethods[static_cast<std::size_t>(method)];
}

// Floats of a prepared palette entry (what the GPU backends read per bone).
constexpr std::size_t prepared_entry_floats(SkinningMethod method) { return 4 * skinning_method_info(method).entry_vec4s; }

// The rows are in enum order, so a method's GPU code is its enum value.
static_assert([] {
  for (std::size_t i = 0; i < kSkinningMethods.size(); ++i)
    if (static_cast<std::size_t>(kSkinningMethods[i].method) != i) return false;
  return true;
}());

}  // namespace cga
