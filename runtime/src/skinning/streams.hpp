// What every skinning loop shares, method-blind: the run's streams, the block size and check, the palette's
// entry size, the portable renormalization of normals, and the staging of strided streams through packed
// blocks. The block functions are generated.hpp's scalar loop (portable.cpp) and the batch path (batch.cpp).
// Private to runtime/src/skinning/ (see docs/runtime.md, "Adding a skinning method").
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "cga/runtime/skinning_palettes.hpp"

// runtime/CMakeLists.txt compiles the skinning files with -O3 -fno-math-errno -fno-trapping-math: at the
// project's -O2, GCC 12's "very cheap" vectorizer cost model refuses gathers, and sqrt's errno and trapping
// compares keep the normal loops scalar (neither flag changes a result; nothing here reads errno or FP
// exceptions).
#define CGA_ALWAYS_INLINE inline __attribute__((always_inline))

namespace cga::skinning_detail {

// Vertices per block: a block's joints and weights are checked first (they are then in L1 for the skinning
// pass), and a split blend's prepared values of a block stay in L1 (12 x 256 floats).
constexpr std::size_t kBlock = 256;
// Floats per prepared palette entry: one 64-byte line, so an entry's offset is a shift of its joint index
// (a method's entry_vec4s vec4s, the rest of the line unused).
constexpr std::size_t kEntry = 16;

// Pointers of one run, restrict-qualified so the compiler knows outputs do not alias inputs.
struct Streams {
  const float* __restrict px;
  const float* __restrict py;
  const float* __restrict pz;
  const float* __restrict nx;
  const float* __restrict ny;
  const float* __restrict nz;
  const std::array<std::uint16_t, 4>* __restrict joints;
  const std::array<float, 4>* __restrict weights;
  float* __restrict ox;
  float* __restrict oy;
  float* __restrict oz;
  float* __restrict onx;
  float* __restrict ony;
  float* __restrict onz;
  // SkinningJob's strides (vertex i of px is px[i * ip], of joints joints[i * js], ...). 1 in packed runs; the
  // block functions read packed streams only, and strided runs are staged through packed blocks (stage_in).
  std::size_t ip = 1, in = 1, op = 1, on = 1, js = 1, ws = 1;
};

// Joint indices below the palette size and finite weights, for vertices [begin, end): two integer max
// reductions over the flat arrays (the largest joint index, the largest exponent field of the weights; an
// all-ones exponent is Inf or NaN). Inlined into every block function, so it is built for the same ISA as the
// skinning loop (vpmaxuw / vpmaxud in the batch path's AVX2 and AVX-512 copies); built for baseline
// x86-64 inside Run() it used to cost about 40 % of lbs. The caller looks for the culprit only when it fails.
CGA_ALWAYS_INLINE bool block_ok(const std::array<std::uint16_t, 4>* joints, const std::array<float, 4>* weights,
                                std::size_t begin, std::size_t end, std::size_t palette) {
  if (end == begin) return true;
  const std::uint16_t* __restrict j = joints[begin].data();
  const float* __restrict w = weights[begin].data();
  std::uint16_t max_joint = 0;
  std::uint32_t max_exponent = 0;
  for (std::size_t e = 0; e < 4 * (end - begin); ++e) {
    max_joint = std::max(max_joint, j[e]);
    max_exponent = std::max(max_exponent, std::bit_cast<std::uint32_t>(w[e]) & 0x7f800000u);
  }
  return max_exponent < 0x7f800000u && max_joint < palette;
}

// Renormalizes the normals [begin, end) in place (a contiguous pass that vectorizes across vertices);
// a degenerate normal becomes 0 rather than NaN.
CGA_ALWAYS_INLINE void renormalize(const Streams& s, std::size_t begin, std::size_t end) {
#pragma GCC ivdep
  for (std::size_t i = begin; i < end; ++i) {
    const float u = s.onx[i], v = s.ony[i], w = s.onz[i];
    const float len2 = u * u + v * v + w * w;
    // No conditional division, so the loop if-converts and vectorizes.
    const float inv = (len2 > 0.0f ? 1.0f : 0.0f) / std::sqrt(std::max(len2, 1e-30f));
    s.onx[i] = u * inv;
    s.ony[i] = v * inv;
    s.onz[i] = w * inv;
  }
}

// Vertices [begin, begin + count) of strided streams copied into packed arrays (count <= kBlock), so that a
// packed block function can skin them; stage_out writes its outputs back. Packed joints and weights are
// used in place.
struct Staged {
  alignas(64) float f[12][kBlock];  // inputs px py pz nx ny nz, outputs ox oy oz onx ony onz
  alignas(64) std::array<std::uint16_t, 4> joints[kBlock];
  alignas(64) std::array<float, 4> weights[kBlock];
};

// Vertex i's positions (and normals) into slot v of t, and slot v's outputs back to vertex i.
inline void stage_vertex_in(const Streams& s, std::size_t i, std::size_t v, bool normals, Staged& t) {
  t.f[0][v] = s.px[i * s.ip], t.f[1][v] = s.py[i * s.ip], t.f[2][v] = s.pz[i * s.ip];
  if (normals) t.f[3][v] = s.nx[i * s.in], t.f[4][v] = s.ny[i * s.in], t.f[5][v] = s.nz[i * s.in];
}
inline void stage_vertex_out(const Staged& t, const Streams& s, std::size_t i, std::size_t v, bool normals) {
  s.ox[i * s.op] = t.f[6][v], s.oy[i * s.op] = t.f[7][v], s.oz[i * s.op] = t.f[8][v];
  if (normals) s.onx[i * s.on] = t.f[9][v], s.ony[i * s.on] = t.f[10][v], s.onz[i * s.on] = t.f[11][v];
}

inline Streams stage_in(const Streams& s, std::size_t begin, std::size_t count, bool normals, Staged& t) {
  for (std::size_t v = 0; v < count; ++v) {
    const std::size_t i = begin + v;
    stage_vertex_in(s, i, v, normals, t);
    if (s.js != 1) t.joints[v] = s.joints[i * s.js];
    if (s.ws != 1) t.weights[v] = s.weights[i * s.ws];
  }
  return {t.f[0], t.f[1], t.f[2], t.f[3], t.f[4], t.f[5], s.js == 1 ? s.joints + begin : t.joints,
          s.ws == 1 ? s.weights + begin : t.weights, t.f[6], t.f[7], t.f[8], t.f[9], t.f[10], t.f[11]};
}

inline void stage_out(const Staged& t, const Streams& s, std::size_t begin, std::size_t count, bool normals) {
  for (std::size_t v = 0; v < count; ++v) stage_vertex_out(t, s, begin + v, v, normals);
}

// Checks the block [begin, end) (block_ok), then skins it; false when the block is invalid (nothing of it
// written). pal is the converted palette, palette its entry count.
using BlockFn = bool (*)(const float* pal, const Streams& s, std::size_t begin, std::size_t end, std::size_t palette);

}  // namespace cga::skinning_detail
