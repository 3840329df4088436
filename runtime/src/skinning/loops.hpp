// The skinning loops every instruction set shares (inlined into each ISA file's block functions): the run's
// streams, the block check, and the per-vertex bodies the hand-written SIMD loops of lbs / cga_points (matrix)
// and cga_motors fall back on at block edges. Also the dispatch table each ISA file fills (SkinKernels) and the
// layouts of the converted palettes those loops read (the generated path's are the table's prepared entries):
//   matrix entry  16 floats, column-major with padded columns (m00 m10 m20 0)(m01 m11 m21 0)(m02 ..)(t 0)
//   motor entry   16 floats, split form: lanes 0-3 G = a + b, 4-7 U (einf blades), 8-11 H = a - b, 12-15 zero
//   with SkinKernels::motor_signed (cga_motors), after the palette's motor entries:
//     negated motors  palette entries, entry e negated (at kEntry * (palette + e))
//     pair signs      palette x palette bytes: [a * palette + b] = palette when <G_a, G_b> has its sign bit
//                     set (influence b of a vertex whose first joint is a takes the negated entry), else 0
// Private to runtime/src/skinning/ (see docs/runtime.md, "Adding a skinning method or an instruction set").
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "cga/runtime/rotor_sign.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "../detail/simd.hpp"

// runtime/CMakeLists.txt compiles the skinning files with -O3 -fno-math-errno -fno-trapping-math: at the
// project's -O2, GCC 12's "very cheap" vectorizer cost model refuses gathers, and sqrt's errno and trapping
// compares keep the normal loops scalar (neither flag changes a result; nothing here reads errno or FP
// exceptions).
#define CGA_ALWAYS_INLINE inline __attribute__((always_inline))

namespace cga::skinning_detail {

using simd::load8;
using v4 = simd::v4f;
using v8 = simd::v8f;
using simd::low;
using simd::high;

// Vertices per block: a block's joints and weights are checked first (they are then in L1 for the skinning
// pass), and cga_motors' blended rows of a block fit in L1 (12 x 256 floats).
constexpr std::size_t kBlock = 256;
// From this many vertices on, a mesh is "large": the SIMD loops prefetch their inputs (see SkinningJob::Run).
constexpr std::size_t kLargeVertices = std::size_t{1} << 17;
// Floats per converted palette entry (matrix and motor entries; dq entries take 8).
constexpr std::size_t kEntry = 16;
// Largest palette for which cga_motors builds the pair-sign data: the negated entries and palette^2 bytes,
// which must fit after the motor entries in Run()'s converted palette (kMaxConvertedPalette x kEntry floats),
// and a table byte must hold the palette size.
constexpr std::size_t kMaxPairSignPalette = 128;

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
  // SkinningJob's strides (vertex i of px is px[i * ip], of joints joints[i * js], ...). 1 in packed runs; only
  // the strided block functions (SkinKernels::matrix_strided) read them.
  std::size_t ip = 1, in = 1, op = 1, on = 1, js = 1, ws = 1;
};

// Joint indices below the palette size and finite weights, for vertices [begin, end): two integer max
// reductions over the flat arrays (the largest joint index, the largest exponent field of the weights; an
// all-ones exponent is Inf or NaN). Inlined into every block function, so it is built for the same ISA as the
// skinning loop (AVX2 vpmaxuw / vpmaxud in the x86-64-v3 clones and the hand-written paths); built for baseline
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

// lbs and cga_points: blend the vertex's 4 matrices (vectorized within the vertex: columns 0-1 and 2-3 are
// one 8-float vector each), then apply: p' = c0 x + c1 y + c2 z + t.
template <bool kNormals>
CGA_ALWAYS_INLINE void matrix_block(const float* __restrict pal, const Streams& s, std::size_t begin,
                                    std::size_t end) {
  for (std::size_t i = begin; i < end; ++i) {
    const std::array<std::uint16_t, 4> j = s.joints[i];
    const std::array<float, 4> w = s.weights[i];
    // Two partial sums per half: shorter FMA dependency chains.
    const float* a = pal + kEntry * j[0];
    const float* b = pal + kEntry * j[1];
    const float* c = pal + kEntry * j[2];
    const float* d = pal + kEntry * j[3];
    const v8 lo = (w[0] * load8(a) + w[1] * load8(b)) + (w[2] * load8(c) + w[3] * load8(d));
    const v8 hi = (w[0] * load8(a + 8) + w[1] * load8(b + 8)) + (w[2] * load8(c + 8) + w[3] * load8(d + 8));
    const float x = s.px[i], y = s.py[i], z = s.pz[i];
    const v8 t = lo * v8{x, x, x, x, y, y, y, y} + hi * v8{z, z, z, z, 1, 1, 1, 1};
    const v4 p = low(t) + high(t);
    s.ox[i] = p[0];
    s.oy[i] = p[1];
    s.oz[i] = p[2];
    if constexpr (kNormals) {
      const float a = s.nx[i], b = s.ny[i], c = s.nz[i];
      const v8 u = lo * v8{a, a, a, a, b, b, b, b} + hi * v8{c, c, c, c, 0, 0, 0, 0};
      const v4 n = low(u) + high(u);
      s.onx[i] = n[0];
      s.ony[i] = n[1];
      s.onz[i] = n[2];
    }
  }
  if constexpr (kNormals) renormalize(s, begin, end);
}

// cga_motors, in two passes over a block. 1: blend the vertex's 4 motors (sign fix on the rotor parts: blades
// 1, e12, e13, e23), vectorized within the vertex, and store the 12 blended coefficients transposed (one row
// per coefficient, kBlock vertices wide). 2: turn each blended motor into its weight-normalized point-transform
// matrix with the generated kernel and apply it; this pass reads the rows contiguously and vectorizes across
// vertices. A motor entry is the motor in split form (skinning_palettes.hpp, motor_split): lanes 0-3 G = a + b
// (the rotor part scaled by 1 + k > 0, so the sign fix reads lanes 0-3), 4-7 U (the einf blades), 8-11
// H = a - b, padded to 16. The split form is linear in the blades, so the blend is the same; pass 2's kernel
// on G, H, U has no cancellation for scaled motors (and fewer operations than on the blades).

using MotorRows = float[12][kBlock];

// Pass 2 over the vertices [begin, end) whose blended motors are in rows[.][i - begin]. kRenormalize false
// leaves the normals unnormalized for the caller's own renormalization (the AVX2 one).
template <bool kNormals, bool kRenormalize = true>
CGA_ALWAYS_INLINE void motor_rows_apply(const MotorRows& rows, const Streams& s, std::size_t begin,
                                        std::size_t end) {
#pragma GCC ivdep
  for (std::size_t i = begin; i < end; ++i) {
    float g[4], u[4], h[4];
    for (int r = 0; r < 4; ++r) g[r] = rows[r][i - begin], u[r] = rows[4 + r][i - begin], h[r] = rows[8 + r][i - begin];
    float m[12];
    detail::motor_split_matrix(g, h, u, m);
    const float x = s.px[i], y = s.py[i], z = s.pz[i];
    s.ox[i] = m[0] * x + m[1] * y + m[2] * z + m[3];
    s.oy[i] = m[4] * x + m[5] * y + m[6] * z + m[7];
    s.oz[i] = m[8] * x + m[9] * y + m[10] * z + m[11];
    if constexpr (kNormals) {
      const float a = s.nx[i], b = s.ny[i], c = s.nz[i];
      s.onx[i] = m[0] * a + m[1] * b + m[2] * c;
      s.ony[i] = m[4] * a + m[5] * b + m[6] * c;
      s.onz[i] = m[8] * a + m[9] * b + m[10] * c;
    }
  }
  if constexpr (kNormals && kRenormalize) renormalize(s, begin, end);
}

// Pass 1 for one vertex, portable: the blended motor's coefficients into rows[.][b]. Reads joints and
// weights at their strides (1 in packed runs).
CGA_ALWAYS_INLINE void motor_blend_one(const float* __restrict pal, const Streams& s, std::size_t i,
                                       MotorRows& rows, std::size_t b) {
  const std::array<std::uint16_t, 4> j = s.joints[i * s.js];
  const std::array<float, 4> w = s.weights[i * s.ws];
  const float* q0 = pal + kEntry * j[0];
  v8 lo = w[0] * load8(q0);
  v8 hi = w[0] * load8(q0 + 8);
  for (int k = 1; k < 4; ++k) {
    const float* q = pal + kEntry * j[k];
    const float wk = rotor_sign::signed_weight(w[k], rotor_sign::dot(q0, q));  // G lanes 0-3
    lo += wk * load8(q);
    hi += wk * load8(q + 8);
  }
  for (int r = 0; r < 8; ++r) rows[r][b] = lo[r];
  for (int r = 0; r < 4; ++r) rows[8 + r][b] = hi[r];
}

template <bool kNormals>
CGA_ALWAYS_INLINE void motor_block(const float* __restrict pal, const Streams& s, std::size_t begin,
                                   std::size_t end) {
  alignas(64) MotorRows rows;
  for (std::size_t i = begin; i < end; ++i) motor_blend_one(pal, s, i, rows, i - begin);
  motor_rows_apply<kNormals>(rows, s, begin, end);
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

// One instruction set's hand-written block functions. A table entry may be another set's function (the
// AVX-512 table uses the AVX2 matrix loops); a null entry, and every method without a member here (dqs,
// cga_log), runs on the generated path (generated.hpp).
struct SkinKernels {
  const char* name;
  BlockFn matrix[2][2];  // lbs and cga_points, [normals][large mesh]
  BlockFn motor[2][2];   // cga_motors, [normals][large mesh]
  // cga_motors reading the rotor signs from the pair-sign table after the palette, [normals][large mesh];
  // pair_signs writes the negated entries and that table (the signs with the same arithmetic as
  // motor[.][.]'s dot products), so the results are the same bits. Null where the ISA has none.
  BlockFn motor_signed[2][2];
  void (*pair_signs)(float* pal, std::size_t palette);
  // lbs and cga_points reading and writing strided streams in place, [normals][large mesh]; bit-identical to
  // matrix[.][.]. Run() takes them (and motor_strided) only when every stream group holds x y z as one triple
  // (y at x + 1, z at x + 2); otherwise, or when null, it stages strided streams through packed blocks
  // (run_strided), as it does for dqs.
  BlockFn matrix_strided[2][2];
  // cga_motors on strided streams, [normals][large mesh][pair-sign table]: joints and weights read in place,
  // positions and normals staged per block for pass 2; bit-identical to motor[.][.] / motor_signed[.][.].
  BlockFn motor_strided[2][2][2];
};

// The tables, each defined in its ISA's file; the SIMD ones are null where the build or the CPU lacks them.
const SkinKernels& portable_kernels();
const SkinKernels* avx2_kernels();
const SkinKernels* avx512_kernels();

}  // namespace cga::skinning_detail
