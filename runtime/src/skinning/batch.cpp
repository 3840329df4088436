// The batch path of SkinningJob: every method of the table (skinning_methods.hpp) on its blend's generated
// SIMD batch kernels (the simd target over runtime/scripts/skin: NAME_batch, and NAME_positions_batch when
// there are no normals), which Highway dispatches to the best instruction set of the CPU. What is written here
// is method-blind: the block check, the joints as 32-bit index streams (the kernels gather the prepared
// entries through them) and the stream descriptors. The entries are the method's prepared palette
// (prepare_palette: 4 * VEC4S floats each), the blend's entry inputs read at 4 * v within an entry.
#define CGAGEN_SIMD_DISPATCH
// Before Highway's first header: the generated kernels take arrays of vectors, which sizeless vectors (SVE,
// RVV) cannot be elements of.
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skinning_batch_kernels.hpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <skinning_batch_kernels.hpp>

#include "batch.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_BATCH_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define CGA_BATCH_CLONES
#endif

namespace cga::skinning_detail {
namespace {

namespace ks = ::cga::kernels::simd;

// A method's two batch kernels as function objects (one per blend script of the table).
#define CGA_METHOD_BATCH(id, name, palette, bone, blend, vec4s, r, g, b)   \
  struct id##_batch {                                                    \
    static constexpr std::size_t kVec4s = vec4s;                         \
    template <class... A>                                                \
    static void both(A... a) {                                           \
      ks::blend##_batch(a...);                                           \
    }                                                                    \
    template <class... A>                                                \
    static void positions(A... a) {                                      \
      ks::blend##_positions_batch(a...);                                 \
    }                                                                    \
  };
CGA_SKINNING_METHODS(CGA_METHOD_BATCH)
#undef CGA_METHOD_BATCH

// The input lines of vertices [begin, end) + kAhead, for a large mesh: its loop is bound by the misses one
// core keeps in flight, which the hardware prefetchers alone leave too few of. Addresses past the arrays are
// formed as integers (a prefetch never faults).
constexpr std::size_t kAhead = 1024;
inline void prefetch(const void* base, std::size_t bytes) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(base) + bytes));
}
template <bool kNormals>
inline void prefetch_block(const Streams& s, std::size_t begin, std::size_t end) {
  for (std::size_t v = begin + kAhead; v < end + kAhead; v += 16) {
    for (const float* p : {s.px, s.py, s.pz}) prefetch(p, 4 * v);
    if constexpr (kNormals)
      for (const float* p : {s.nx, s.ny, s.nz}) prefetch(p, 4 * v);
    for (std::size_t b = 0; b < 128; b += 64) prefetch(s.joints, 8 * v + b);
    for (std::size_t b = 0; b < 256; b += 64) prefetch(s.weights, 16 * v + b);
  }
}

// The blend's arguments: 4 x VEC4S entry streams, 4 weights, the position, the normal (positions only: the
// position's streams again, which the kernel does not read), then the outputs.
template <class K, bool kNormals, std::size_t... I>
void call(std::size_t n, const ks::In* e, const ks::In* w, const ks::In* p, const ks::In* nrm, const ks::Out& op,
          const ks::Out& on, std::index_sequence<I...>) {
  if constexpr (kNormals)
    K::both(n, e[I]..., w[0], w[1], w[2], w[3], p[0], p[1], p[2], nrm[0], nrm[1], nrm[2], op, on);
  else
    K::positions(n, e[I]..., w[0], w[1], w[2], w[3], p[0], p[1], p[2], p[0], p[1], p[2], op);
}

// Vertices [begin, end) of packed streams (strided runs are staged into packed blocks by the caller).
template <class K, bool kNormals>
CGA_BATCH_CLONES bool batch_block(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
                                  std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  prefetch_block<kNormals>(s, begin, end);
  constexpr std::size_t kFloats = 4 * K::kVec4s;
  const std::size_t n = end - begin;
  // The joints as 32-bit index streams and the weights as plain streams, one per influence.
  alignas(64) std::int32_t joints[4][kBlock];
  alignas(64) float weights[4][kBlock];
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t k = 0; k < 4; ++k) {
      joints[k][i] = s.joints[begin + i][k];
      weights[k][i] = s.weights[begin + i][k];
    }
  ks::In e[4 * K::kVec4s];
  for (std::size_t k = 0; k < 4; ++k)
    for (std::size_t v = 0; v < K::kVec4s; ++v)
      e[k * K::kVec4s + v] = ks::In{pal + 4 * v, static_cast<std::ptrdiff_t>(kFloats), 1, joints[k], 1, nullptr};
  const ks::In w[4] = {{weights[0]}, {weights[1]}, {weights[2]}, {weights[3]}};
  const ks::In p[3] = {{s.px + begin}, {s.py + begin}, {s.pz + begin}};
  float* const op_blades[3] = {s.ox + begin, s.oy + begin, s.oz + begin};
  const ks::Out op{nullptr, 1, 1, op_blades};
  if constexpr (kNormals) {
    const ks::In nrm[3] = {{s.nx + begin}, {s.ny + begin}, {s.nz + begin}};
    float* const on_blades[3] = {s.onx + begin, s.ony + begin, s.onz + begin};
    const ks::Out on{nullptr, 1, 1, on_blades};
    call<K, true>(n, e, w, p, nrm, op, on, std::make_index_sequence<4 * K::kVec4s>{});
    renormalize(s, begin, end);
  } else {
    call<K, false>(n, e, w, p, p, op, op, std::make_index_sequence<4 * K::kVec4s>{});
  }
  return true;
}

}  // namespace

const GeneratedBlocks& batch_blocks() {
  static const GeneratedBlocks blocks{{
#define CGA_METHOD_BLOCKS(id, ...) {batch_block<id##_batch, false>, batch_block<id##_batch, true>},
      CGA_SKINNING_METHODS(CGA_METHOD_BLOCKS)
#undef CGA_METHOD_BLOCKS
  }};
  return blocks;
}

}  // namespace cga::skinning_detail
