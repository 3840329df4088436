// The batch path of SkinningJob: every method of the table (skinning_methods.hpp) on its blend's generated
// SIMD batch kernels (the simd target over runtime/scripts/skin), which Highway dispatches to the best
// instruction set of the CPU. A blend comes in one of two forms (skinning_batch_forms.hpp, generated from the
// table's SPLIT column):
//   split  the blend staged at its named values (cgagen --stage-at): pass 1 runs NAME_split_prepare once per
//          vertex on its four entries and weights (straight-line code the compiler vectorizes across the
//          entry's blades), pass 2 runs NAME_split_batch lane-wise across the block's vertices on the
//          prepared values;
//   whole  NAME_batch lane-wise across vertices, gathering the four entries through the joints as 32-bit index
//          streams.
// What is written here is method-blind: the block check, the two loops, the index streams and the stream
// descriptors. The entries are the method's prepared palette (prepare_palette: 4 * VEC4S floats each), the
// blend's entry inputs read at 4 * v within an entry.
#define CGAGEN_SIMD_DISPATCH
// Before Highway's first header: the generated kernels take arrays of vectors, which sizeless vectors (SVE,
// RVV) cannot be elements of.
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "skinning_batch_kernels.hpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <skinning_batch_kernels.hpp>

#include <utility>

#include "batch.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_BATCH_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#define CGA_BATCH_INLINE __attribute__((always_inline)) inline
#else
#define CGA_BATCH_CLONES
#define CGA_BATCH_INLINE inline
#endif

namespace cga::skinning_detail {
namespace {

namespace ks = ::cga::kernels::simd;

// Each blend's kernels as a function object, in the form the table gives it.
#define CGA_BLEND_FORM_split(blend)                                                              \
  struct blend##_form {                                                                          \
    static constexpr bool kSplit = true;                                                         \
    static constexpr std::size_t kPrepared = ks::blend##_split_prepare_prepared_blades.size();   \
    template <class... A>                                                                        \
    static void prepare(A... a) {                                                                \
      ks::blend##_split_prepare(a...);                                                           \
    }                                                                                            \
    template <class... A>                                                                        \
    static void both(A... a) {                                                                   \
      ks::blend##_split_batch(a...);                                                             \
    }                                                                                            \
    template <class... A>                                                                        \
    static void positions(A... a) {                                                              \
      ks::blend##_split_positions_batch(a...);                                                   \
    }                                                                                            \
  };
#define CGA_BLEND_FORM_whole(blend)                                                              \
  struct blend##_form {                                                                          \
    static constexpr bool kSplit = false;                                                        \
    static constexpr std::size_t kPrepared = 0;                                                  \
    template <class... A>                                                                        \
    static void both(A... a) {                                                                   \
      ks::blend##_batch(a...);                                                                   \
    }                                                                                            \
    template <class... A>                                                                        \
    static void positions(A... a) {                                                              \
      ks::blend##_positions_batch(a...);                                                         \
    }                                                                                            \
  };
#define CGA_BLEND_FORM(blend, form) CGA_BLEND_FORM_##form(blend)
#include <skinning_batch_forms.hpp>
#undef CGA_BLEND_FORM

// A method: its blend's form and its entry size.
#define CGA_METHOD_BATCH(id, name, palette, bone, blend, vec4s, r, g, b) \
  struct id##_batch : blend##_form {                                   \
    static constexpr std::size_t kVec4s = vec4s;                       \
  };
CGA_SKINNING_METHODS(CGA_METHOD_BATCH)
#undef CGA_METHOD_BATCH

// The input lines of vertices [begin, end) + kAhead, for a large mesh: its loop is bound by the misses one
// core keeps in flight, which the hardware prefetchers alone leave too few of. Addresses past the arrays are
// formed as integers (a prefetch never faults). Both always inlined: GCC takes a function whose only effect
// is a prefetch for one without effects and deletes the calls to it (the prefetches vanish).
constexpr std::size_t kAhead = 1024;
CGA_ALWAYS_INLINE void prefetch(const void* base, std::size_t bytes) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(base) + bytes));
}
template <bool kNormals>
CGA_ALWAYS_INLINE void prefetch_block(const Streams& s, std::size_t begin, std::size_t end) {
  for (std::size_t v = begin + kAhead; v < end + kAhead; v += 16) {
    for (const float* p : {s.px, s.py, s.pz}) prefetch(p, 4 * v);
    if constexpr (kNormals)
      for (const float* p : {s.nx, s.ny, s.nz}) prefetch(p, 4 * v);
    for (std::size_t b = 0; b < 128; b += 64) prefetch(s.joints, 8 * v + b);
    for (std::size_t b = 0; b < 256; b += 64) prefetch(s.weights, 16 * v + b);
  }
}

// The whole form's arguments: 4 x VEC4S entry streams, 4 weights, the position, the normal (positions only:
// the position's streams again, which the kernel does not read), then the outputs.
template <class K, bool kNormals, std::size_t... I>
void call_whole(std::size_t n, const ks::In* e, const ks::In* w, const ks::In* p, const ks::In* nrm, const ks::Out& op,
                const ks::Out& on, std::index_sequence<I...>) {
  if constexpr (kNormals)
    K::both(n, e[I]..., w[0], w[1], w[2], w[3], p[0], p[1], p[2], nrm[0], nrm[1], nrm[2], op, on);
  else
    K::positions(n, e[I]..., w[0], w[1], w[2], w[3], p[0], p[1], p[2], p[0], p[1], p[2], op);
}

// The split form's pass 1 for one vertex: the prepare on its four entries and weights, into `out`.
template <class K, std::size_t... I>
CGA_BATCH_INLINE void prepare_one(const float* pal, const std::uint16_t* j, const float* w, float* out,
                                  std::index_sequence<I...>) {
  constexpr std::size_t kFloats = 4 * K::kVec4s;
  K::prepare((pal + kFloats * j[I / K::kVec4s] + 4 * (I % K::kVec4s))..., w[0], w[1], w[2], w[3], out);
}

// Vertices [begin, end) of packed streams (strided runs are staged into packed blocks by the caller).
template <class K, bool kNormals>
CGA_BATCH_CLONES bool batch_block(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
                                  std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  prefetch_block<kNormals>(s, begin, end);
  const std::size_t n = end - begin;
  const ks::In p[3] = {{s.px + begin}, {s.py + begin}, {s.pz + begin}};
  // Without normals their streams are null: no offset is applied to them.
  const auto at = [begin](auto* q) { return kNormals ? q + begin : q; };
  const ks::In nrm[3] = {{at(s.nx)}, {at(s.ny)}, {at(s.nz)}};
  float* const op_blades[3] = {s.ox + begin, s.oy + begin, s.oz + begin};
  float* const on_blades[3] = {at(s.onx), at(s.ony), at(s.onz)};
  const ks::Out op{nullptr, 1, 1, op_blades}, on{nullptr, 1, 1, on_blades};
  if constexpr (K::kSplit) {
    // Pass 1 vertex after vertex into one prepared block, pass 2 across it.
    alignas(64) float prepared[kBlock * K::kPrepared];
    for (std::size_t i = 0; i < n; ++i)
      prepare_one<K>(pal, s.joints[begin + i].data(), s.weights[begin + i].data(), prepared + K::kPrepared * i,
                     std::make_index_sequence<4 * K::kVec4s>{});
    const ks::In prep{prepared, static_cast<std::ptrdiff_t>(K::kPrepared), 1};
    if constexpr (kNormals)
      K::both(n, prep, p[0], p[1], p[2], nrm[0], nrm[1], nrm[2], op, on);
    else
      K::positions(n, prep, p[0], p[1], p[2], op);
  } else {
    constexpr std::size_t kFloats = 4 * K::kVec4s;
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
    call_whole<K, kNormals>(n, e, w, p, nrm, op, on, std::make_index_sequence<4 * K::kVec4s>{});
  }
  if constexpr (kNormals) renormalize(s, begin, end);
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
