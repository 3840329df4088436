// The batch path of SkinningJob: every method of the table (skinning_methods.hpp) on its blend's generated
// lane-wise kernels (the simd target over runtime/scripts/skin), built once per instruction set by Highway's
// per-target inclusion of this file and dispatched to the best one of the CPU. A blend comes in one of two
// forms (skinning_batch_forms.hpp, generated from the table's SPLIT column):
//   split  the blend staged at its named values (cgagen --stage-at): pass 1 runs NAME_split_prepare once per
//          vertex on its four entries and weights (straight-line code the compiler vectorizes across the
//          entry's blades), pass 2 runs the lane kernel NAME_split across the block's vertices on the
//          prepared values;
//   whole  the lane kernel NAME across vertices on the four entries of each.
// What is written here is method-blind: the block check, the loops, prefetch, the normals' renormalization,
// and the row offsets through which the generated headers' transposer turns rows of 4 floats (a vertex's
// prepared values, a palette entry's vec4s) into lanes. The kernels are called directly on vectors, so no stream
// descriptor is looked at inside the loops. The entries are the method's prepared palette, one line of kEntry
// floats each (prepare_palette_strided), the blend's entry inputs read at 4 * v within an entry.
#ifndef CGA_SKINNING_BATCH_ONCE
#define CGA_SKINNING_BATCH_ONCE
// Before Highway's first header: the kernels take arrays of vectors, which sizeless vectors (SVE, RVV) cannot
// be elements of.
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#include <algorithm>
#include <cstdint>
#include <utility>
#include <vector>

#include "batch.hpp"
#endif

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batch.cpp"  // this file, found through the include path runtime/CMakeLists.txt sets
#include <hwy/foreach_target.h>         // IWYU pragma: keep
#include <hwy/highway.h>

#include <skinning_batch_kernels.hpp>

#ifndef CGA_SKINNING_BATCH_SHARED
#define CGA_SKINNING_BATCH_SHARED
namespace cga::skinning_detail {
namespace {
// The input lines of the 16 vertices v + kAhead on, for a large mesh: its loop is bound by the misses one core
// keeps in flight, which the hardware prefetchers alone leave too few of. Issued as the loops go, 16 vertices
// at a time, so the prefetches spread between the loads. Addresses past the arrays are formed as integers (a
// prefetch never faults). Both always inlined: GCC takes a function whose only effect is a prefetch for one
// without effects and deletes the calls to it (the prefetches vanish).
constexpr std::size_t kAhead = 1024, kAheadStep = 16;  // at least the widest vector's lanes
CGA_ALWAYS_INLINE void prefetch(const void* base, std::size_t bytes) {
  __builtin_prefetch(reinterpret_cast<const void*>(reinterpret_cast<std::uintptr_t>(base) + bytes));
}
template <bool kNormals>
CGA_ALWAYS_INLINE void prefetch_ahead(const Streams& s, std::size_t v) {
  v += kAhead;
  for (const float* p : {s.px, s.py, s.pz}) prefetch(p, 4 * v);
  if constexpr (kNormals)
    for (const float* p : {s.nx, s.ny, s.nz}) prefetch(p, 4 * v);
  for (std::size_t b = 0; b < 128; b += 64) prefetch(s.joints, 8 * v + b);
  for (std::size_t b = 0; b < 256; b += 64) prefetch(s.weights, 16 * v + b);
}
}  // namespace
}  // namespace cga::skinning_detail
#endif

HWY_BEFORE_NAMESPACE();
namespace cga::skinning_detail::HWY_NAMESPACE {
namespace {

namespace hn = hwy::HWY_NAMESPACE;
namespace ks = ::cga::kernels::simd;
namespace kl = ::cga::kernels::simd::HWY_NAMESPACE;

// Each blend's kernels as a function object, in the form the table gives it: the scalar prepare (split) and
// the lane kernels with and without normals.
#define CGA_BLEND_FORM_split(blend)                                                              \
  struct blend##_form {                                                                          \
    static constexpr bool kSplit = true;                                                         \
    static constexpr std::size_t kPrepared = ks::blend##_split_prepare_prepared_blades.size();   \
    template <class... A>                                                                        \
    static HWY_INLINE void prepare(A... a) {                                                     \
      ks::blend##_split_prepare(a...);                                                           \
    }                                                                                            \
    template <class... A>                                                                        \
    static HWY_INLINE void both(A&&... a) {                                                      \
      kl::blend##_split(a...);                                                                   \
    }                                                                                            \
    template <class... A>                                                                        \
    static HWY_INLINE void positions(A&&... a) {                                                 \
      kl::blend##_split_positions(a...);                                                         \
    }                                                                                            \
  };
#define CGA_BLEND_FORM_whole(blend)                                                              \
  struct blend##_form {                                                                          \
    static constexpr bool kSplit = false;                                                        \
    static constexpr std::size_t kPrepared = 0;                                                  \
    template <class... A>                                                                        \
    static HWY_INLINE void both(A&&... a) {                                                      \
      kl::blend(a...);                                                                           \
    }                                                                                            \
    template <class... A>                                                                        \
    static HWY_INLINE void positions(A&&... a) {                                                 \
      kl::blend##_positions(a...);                                                               \
    }                                                                                            \
  };
#define CGA_BLEND_FORM(blend, form) CGA_BLEND_FORM_##form(blend)
#include <skinning_batch_forms.hpp>
#undef CGA_BLEND_FORM
#undef CGA_BLEND_FORM_split
#undef CGA_BLEND_FORM_whole

// A method: its blend's form and its entry size.
#define CGA_METHOD_BATCH(id, name, palette, bone, blend, vec4s, r, g, b) \
  struct id##_batch : blend##_form {                                   \
    static constexpr std::size_t kVec4s = vec4s;                       \
  };
CGA_SKINNING_METHODS(CGA_METHOD_BATCH)
#undef CGA_METHOD_BATCH

// Floats k .. k + kN - 1 of the rows base + offs[j], j < Lanes(d), as kN vectors, lane j from row j: the
// generated headers' transposer (cgagen_rows4: one 128-bit load per row and a 4 x 4 transpose within each
// 128-bit block) 4 floats at a time, a gather for the rest and on one lane.
template <std::size_t kN, class D>
HWY_INLINE void transpose(D d, const float* base, const std::int32_t* offs, hn::Vec<D>* out) {
  std::size_t k = 0;
#if HWY_TARGET != HWY_SCALAR
  if constexpr (hn::MaxLanes(D()) % 4 == 0)
    for (; k + 4 <= kN; k += 4) kl::cgagen_rows4(d, base + k, offs, out[k], out[k + 1], out[k + 2], out[k + 3]);
#endif
  const hn::RebindToSigned<D> di;
  for (; k < kN; ++k) out[k] = hn::GatherIndex(d, base + k, hn::Load(di, offs));
}

// Row offsets j * stride of lanes j < Lanes(d), for rows of `stride` floats laid out one after another.
template <class D>
struct Strided {
  alignas(64) std::int32_t offs[hn::MaxLanes(D())];
  explicit Strided(std::size_t stride) {
    for (std::size_t j = 0; j < hn::MaxLanes(D()); ++j) offs[j] = static_cast<std::int32_t>(j * stride);
  }
};

// 1 / |n| on each lane, or 0 where |n| = 0 (a degenerate normal becomes 0 rather than NaN): on x86 the
// reciprocal square root estimate (12 bits or more) and one Newton step, relative error below 1e-6; elsewhere
// the exact quotient (NEON's estimate has 8 bits, which one step takes only to about 16). The division and
// square root the estimate replaces kept the divider busy about 20 cycles per 8 vertices.
template <class D>
HWY_INLINE hn::Vec<D> inv_length(D d, hn::Vec<D> x, hn::Vec<D> y, hn::Vec<D> z) {
  const auto len2 = hn::MulAdd(z, z, hn::MulAdd(y, y, hn::Mul(x, x)));
  const auto safe = hn::Max(len2, hn::Set(d, 1e-30f));
#if HWY_ARCH_X86 && HWY_TARGET != HWY_SCALAR && HWY_TARGET != HWY_EMU128
  const auto r = hn::ApproximateReciprocalSqrt(safe);
  // r (1.5 - 0.5 len2 r^2)
  const auto inv = hn::Mul(r, hn::NegMulAdd(hn::Mul(hn::Mul(hn::Set(d, 0.5f), safe), r), r, hn::Set(d, 1.5f)));
#else
  const auto inv = hn::Div(hn::Set(d, 1.0f), hn::Sqrt(safe));
#endif
  return hn::IfThenElseZero(hn::Gt(len2, hn::Zero(d)), inv);
}

// The kernel on vertices i .. i + Lanes(d) - 1: their positions (and normals) loaded, `both(x, y, z, nx, ny,
// nz, p, n)` or `positions(x, y, z, p)` (the kernel with its leading inputs bound), the outputs stored, the
// normals renormalized on the way.
template <bool kNormals, class D, class Both, class Positions>
HWY_INLINE void apply(D d, const Streams& s, std::size_t i, const Both& both, const Positions& positions) {
  using V = hn::Vec<D>;
  const V x = hn::LoadU(d, s.px + i), y = hn::LoadU(d, s.py + i), z = hn::LoadU(d, s.pz + i);
  V p[3], n[3];
  if constexpr (kNormals) {
    both(x, y, z, hn::LoadU(d, s.nx + i), hn::LoadU(d, s.ny + i), hn::LoadU(d, s.nz + i), p, n);
    const V inv = inv_length(d, n[0], n[1], n[2]);
    hn::StoreU(hn::Mul(n[0], inv), d, s.onx + i), hn::StoreU(hn::Mul(n[1], inv), d, s.ony + i);
    hn::StoreU(hn::Mul(n[2], inv), d, s.onz + i);
  } else {
    positions(x, y, z, p);
  }
  hn::StoreU(p[0], d, s.ox + i), hn::StoreU(p[1], d, s.oy + i), hn::StoreU(p[2], d, s.oz + i);
}

// Split form, pass 2 on vertices i .. i + Lanes(d) - 1 (prepared: the block's prepared values, vertex b first).
template <class K, bool kNormals, class D>
HWY_INLINE void split_lanes(D d, const Streams& s, const float* prepared, std::size_t b, std::size_t i) {
  using V = hn::Vec<D>;
  V prep[K::kPrepared];
  transpose<K::kPrepared>(d, prepared + K::kPrepared * (i - b), Strided<D>(K::kPrepared).offs, prep);
  apply<kNormals>(
      d, s, i, [&](V x, V y, V z, V nx, V ny, V nz, V* p, V* n) { K::both(d, prep, x, y, z, nx, ny, nz, p, n); },
      [&](V x, V y, V z, V* p) { K::positions(d, prep, x, y, z, p); });
}

// Whole form on vertices i .. i + Lanes(d) - 1: each influence's entry transposed from its palette rows, the
// weights from the vertices' weight rows.
template <class K, bool kNormals, class D, std::size_t... I>
HWY_INLINE void whole_lanes(D d, const float* pal, const Streams& s, std::size_t i, std::index_sequence<I...>) {
  using V = hn::Vec<D>;
  V e[4][K::kVec4s][4], w[4];
  for (std::size_t k = 0; k < 4; ++k) {
    alignas(64) std::int32_t entries[hn::MaxLanes(D())];
    for (std::size_t j = 0; j < hn::MaxLanes(D()); ++j)
      entries[j] = static_cast<std::int32_t>(kEntry * s.joints[i + j][k]);
    for (std::size_t v = 0; v < K::kVec4s; ++v) transpose<4>(d, pal + 4 * v, entries, e[k][v]);
  }
  hn::LoadInterleaved4(d, s.weights[i].data(), w[0], w[1], w[2], w[3]);
  apply<kNormals>(
      d, s, i,
      [&](V x, V y, V z, V nx, V ny, V nz, V* p, V* n) {
        K::both(d, e[I / K::kVec4s][I % K::kVec4s]..., w[0], w[1], w[2], w[3], x, y, z, nx, ny, nz, p, n);
      },
      // The position kernel of the whole form lists the normal's inputs too, which it does not read.
      [&](V x, V y, V z, V* p) {
        K::positions(d, e[I / K::kVec4s][I % K::kVec4s]..., w[0], w[1], w[2], w[3], x, y, z, x, y, z, p);
      });
}

// The split form's pass 1 for one vertex: the prepare on its four entries and weights, into `out`.
template <class K, std::size_t... I>
HWY_INLINE void prepare_one(const float* pal, const std::uint16_t* j, const float* w, float* out,
                            std::index_sequence<I...>) {
  K::prepare((pal + kEntry * j[I / K::kVec4s] + 4 * (I % K::kVec4s))..., w[0], w[1], w[2], w[3], out);
}

// Vertices [begin, end) of packed streams (strided runs are staged into packed blocks by the caller): whole
// vectors, then the tail one lane at a time (the same kernel on one lane).
template <class K, bool kNormals>
HWY_NOINLINE bool batch_block(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
                              std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  const hn::ScalableTag<float> d;
  const hn::CappedTag<float, 1> d1;
  const std::size_t N = hn::Lanes(d);
  // The prefetch for each chunk of kAheadStep vertices (a whole number of vectors) as the loops reach it.
  static_assert(kAheadStep % hn::MaxLanes(d) == 0, "a chunk must hold whole vectors");
  std::size_t i = begin;
  if constexpr (K::kSplit) {
    // Pass 1 vertex after vertex into one prepared block, pass 2 across it.
    alignas(64) float prepared[kBlock * K::kPrepared];
    for (std::size_t c = begin; c < end; c += kAheadStep) {
      prefetch_ahead<kNormals>(s, c);
      for (std::size_t v = c; v < std::min(end, c + kAheadStep); ++v)
        prepare_one<K>(pal, s.joints[v].data(), s.weights[v].data(), prepared + K::kPrepared * (v - begin),
                       std::make_index_sequence<4 * K::kVec4s>{});
    }
    for (; i + N <= end; i += N) split_lanes<K, kNormals>(d, s, prepared, begin, i);
    for (; i < end; ++i) split_lanes<K, kNormals>(d1, s, prepared, begin, i);
  } else {
    constexpr auto kInputs = std::make_index_sequence<4 * K::kVec4s>{};
    std::size_t fetched = begin;
    for (; i + N <= end; i += N) {
      if (i >= fetched) prefetch_ahead<kNormals>(s, fetched), fetched += kAheadStep;
      whole_lanes<K, kNormals>(d, pal, s, i, kInputs);
    }
    for (; i < end; ++i) whole_lanes<K, kNormals>(d1, pal, s, i, kInputs);
  }
  return true;
}

}  // namespace

// The block functions of this instruction set, [method][normals].
const GeneratedBlocks& blocks() {
  static const GeneratedBlocks table{{
#define CGA_METHOD_BLOCKS(id, ...) {batch_block<id##_batch, false>, batch_block<id##_batch, true>},
      CGA_SKINNING_METHODS(CGA_METHOD_BLOCKS)
#undef CGA_METHOD_BLOCKS
  }};
  return table;
}

}  // namespace cga::skinning_detail::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace cga::skinning_detail {

HWY_EXPORT(blocks);

const GeneratedBlocks& batch_blocks() { return HWY_DYNAMIC_DISPATCH(blocks)(); }

// This file's instruction sets; ik_chain_batch.cpp is built for the same (runtime/CMakeLists.txt).
std::vector<std::int64_t> batch_targets() { return hwy::SupportedAndGeneratedTargets(); }

}  // namespace cga::skinning_detail
#endif
