// The generated skinning path: every method of the table (skinning_methods.hpp) as its two generated kernels
// (runtime/scripts/skin -> cga::kernels): the per-bone prepare fills the run's converted palette with
// prepared entries (entry_vec4s vec4s each, one kEntry-float line per entry: prepare_palette_strided), and the
// portable block loop calls the per-vertex blend on four of them. This is the loop every method runs on with
// use_simd = false; the batch path (batch.cpp) is checked against it (test_skinning_simd).
// Private to runtime/src/skinning/.
#pragma once

#include <cstddef>
#include <span>
#include <utility>

#include <skinning_kernels.hpp>

#include "cga/runtime/skinning_methods.hpp"

#include "streams.hpp"

namespace cga::skinning_detail {

// The method's kernels as function objects (the generated functions are overloaded for float and double).
// A bone script of `none` (the entry is the palette's own) names no kernel.
template <class... A>
CGA_ALWAYS_INLINE void none(A...) {}

#define CGA_METHOD_KERNELS(id, name, palette, bone, blend, vec4s, r, g, b)                  \
  struct id##_kernels {                                                                    \
    static constexpr std::size_t kVec4s = vec4s;                                           \
    static constexpr PaletteKind kPalette = PaletteKind::palette;                          \
    template <class... A>                                                                  \
    static CGA_ALWAYS_INLINE void bone_fn(A... a) {                                        \
      using namespace ::cga::kernels;                                                      \
      bone(a...);                                                                          \
    }                                                                                      \
    template <class... A>                                                                  \
    static CGA_ALWAYS_INLINE void blend_fn(A... a) {                                       \
      ::cga::kernels::blend(a...);                                                         \
    }                                                                                      \
  };
CGA_SKINNING_METHODS(CGA_METHOD_KERNELS)
#undef CGA_METHOD_KERNELS

// One palette entry prepared: the bone kernel's inputs from the method's palette kind, its outputs the
// entry's vec4s (a 3-blade output leaves its fourth float 0).
template <class K, std::size_t... I>
CGA_ALWAYS_INLINE void prepare_from_motor(const float m[12], float* entry, std::index_sequence<I...>) {
  K::bone_fn(m, (entry + 4 * I)...);
}
template <class K, std::size_t... I>
CGA_ALWAYS_INLINE void prepare_from_dual_quat(const glm::dualquat& q, float* entry, std::index_sequence<I...>) {
  K::bone_fn(q.real.x, q.real.y, q.real.z, q.real.w, q.dual.x, q.dual.y, q.dual.z, q.dual.w, (entry + 4 * I)...);
}

// The method's palette prepared into `out` at `stride` floats per entry (prepare.cpp; prepare_palette packs
// them at prepared_entry_floats). The CPU loops read entries of kEntry floats: one 64-byte line each, and an
// entry's offset is a shift of its joint index.
void prepare_palette_strided(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                             std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                             std::span<float> out, std::size_t stride);

// The blend of one vertex on the entries e[0..3].
template <class K, std::size_t... I>
CGA_ALWAYS_INLINE void blend_vertex(const float* const e[4], const float w[4], float x, float y, float z,
                                    float nx, float ny, float nz, float p[3], float n[3],
                                    std::index_sequence<I...>) {
  K::blend_fn((e[I / K::kVec4s] + 4 * (I % K::kVec4s))..., w[0], w[1], w[2], w[3], x, y, z, nx, ny, nz, p, n);
}

template <class K, bool kNormals>
CGA_ALWAYS_INLINE void generated_block(const float* __restrict pal, const Streams& s, std::size_t begin,
                                       std::size_t end) {
  constexpr std::size_t kFloats = kEntry;
  // One vertex per iteration: GCC 12 vectorizes neither the four entry gathers nor (in cga-log) the libm
  // calls, so this loop stays scalar (docs/bench.md has the A/B against the batch path).
  const std::uint16_t* __restrict joints = s.joints[0].data();
  const float* __restrict weights = s.weights[0].data();
#pragma GCC ivdep
  for (std::size_t i = begin; i < end; ++i) {
    const float* const e[4] = {pal + kFloats * joints[4 * i], pal + kFloats * joints[4 * i + 1],
                               pal + kFloats * joints[4 * i + 2], pal + kFloats * joints[4 * i + 3]};
    const float w[4] = {weights[4 * i], weights[4 * i + 1], weights[4 * i + 2], weights[4 * i + 3]};
    float p[3], n[3];
    if constexpr (kNormals)
      blend_vertex<K>(e, w, s.px[i], s.py[i], s.pz[i], s.nx[i], s.ny[i], s.nz[i], p, n,
                      std::make_index_sequence<4 * K::kVec4s>{});
    else
      blend_vertex<K>(e, w, s.px[i], s.py[i], s.pz[i], 0.0f, 0.0f, 0.0f, p, n,
                      std::make_index_sequence<4 * K::kVec4s>{});
    s.ox[i] = p[0];
    s.oy[i] = p[1];
    s.oz[i] = p[2];
    if constexpr (kNormals) {
      s.onx[i] = n[0];
      s.ony[i] = n[1];
      s.onz[i] = n[2];
    }
  }
  if constexpr (kNormals) renormalize(s, begin, end);
}

// The generated block functions, [method][normals] (portable.cpp).
using GeneratedBlocks = std::array<std::array<BlockFn, 2>, kSkinningMethodCount>;
const GeneratedBlocks& generated_blocks();

}  // namespace cga::skinning_detail
