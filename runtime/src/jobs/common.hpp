// What the pose jobs' files (sampling.cpp, blending.cpp, local_to_model.cpp, palette.cpp) share: the
// clone attribute of their hot kernels, blocks of 8 joints as structure of arrays and their transposes, the
// rigidity test of motor arrays, the split form of the motor product, and the checks of Validate(). Private to
// the runtime.
//
// The motor loops are the hot part of a pose: they live in kernels marked CGA_JOBS_CLONES, each compiled
// twice (x86-64-v3 with AVX2/FMA, and the baseline ISA; the loader picks at startup) with the generated
// kernels flattened in, so GCC vectorizes them across joints where the data is structure of arrays (sampling,
// paper blending) and schedules them tightly where it is not. Everything here is in an anonymous namespace
// and inline: each job's file gets its own copy, inlined into its kernels and compiled with that file's
// options (runtime/CMakeLists.txt gives every file of jobs/ the same ones).
//
// The 8-float vector helpers (detail/simd.hpp, and motor.hpp's templates on them) are inlined: the AVX
// argument ABI that -Wpsabi warns about never applies.
#pragma once
#pragma GCC diagnostic ignored "-Wpsabi"

#include "cga/runtime/jobs.hpp"

#include "cga/runtime/rotor_sign.hpp"
#include "../detail/simd.hpp"

#include <algorithm>
#include <cmath>

#include <motor_split_mul.hpp>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_JOBS_CLONES __attribute__((target_clones("arch=x86-64-v3", "default"), flatten))
#else
#define CGA_JOBS_CLONES __attribute__((flatten))
#endif

namespace cga {

namespace {

// ------------------------------------------------------------------------------------------- hot kernels
// Every loop of the kernels says with `ivdep` that its streams do not overlap (distinct job buffers): without
// it GCC gives up on the aliasing of the float pointers.

constexpr std::size_t kR = ClipIntervals::kRigid, kM = ClipIntervals::kMotor;

// Blocks of kB joints as structure of arrays: block[c][lane] is coefficient c of joint j0 + lane. The motor
// math runs on blocks in loops over lanes that GCC vectorizes; the job buffers stay arrays of Motor (the
// API), converted with 4x4 transposes instead of 12 scattered stores per joint.
constexpr std::size_t kB = 8;
using Block = float[kM][kB];

#if defined(__GNUC__)
// The 8-float vectors and the 8x8 transpose of the shared SIMD header (detail/simd.hpp).
using simd::load4;
using simd::load8;
using simd::store4;
using simd::store8;
using simd::transpose8;
using simd::v8f;

// 8 motors (m(0) .. m(7), each a Motor&) into 12 coefficient rows.
template <class Get>
inline void gather_rows(Get m, v8f rows[kM]) {
  for (int l = 0; l < 8; ++l) rows[l] = load8(&m(l).c[0]);
  transpose8(rows);
  // Coefficients 8-11: motors l and l + 4 in the halves of one vector, then 4x4 transposes within the halves.
  v8f g[4];
  for (int k = 0; k < 4; ++k)
    g[k] = __builtin_shufflevector(load4(&m(k).c[8]), load4(&m(k + 4).c[8]), 0, 1, 2, 3, 4, 5, 6, 7);
  const v8f a01 = __builtin_shufflevector(g[0], g[1], 0, 8, 1, 9, 4, 12, 5, 13);
  const v8f b01 = __builtin_shufflevector(g[0], g[1], 2, 10, 3, 11, 6, 14, 7, 15);
  const v8f a23 = __builtin_shufflevector(g[2], g[3], 0, 8, 1, 9, 4, 12, 5, 13);
  const v8f b23 = __builtin_shufflevector(g[2], g[3], 2, 10, 3, 11, 6, 14, 7, 15);
  rows[8] = __builtin_shufflevector(a01, a23, 0, 1, 8, 9, 4, 5, 12, 13);
  rows[9] = __builtin_shufflevector(a01, a23, 2, 3, 10, 11, 6, 7, 14, 15);
  rows[10] = __builtin_shufflevector(b01, b23, 0, 1, 8, 9, 4, 5, 12, 13);
  rows[11] = __builtin_shufflevector(b01, b23, 2, 3, 10, 11, 6, 7, 14, 15);
}
// 12 coefficient rows into 8 motors (rows is clobbered).
inline void scatter_rows(v8f rows[kM], Motor* __restrict m) {
  const v8f a = __builtin_shufflevector(rows[8], rows[9], 0, 8, 1, 9, 4, 12, 5, 13);
  const v8f b = __builtin_shufflevector(rows[10], rows[11], 0, 8, 1, 9, 4, 12, 5, 13);
  const v8f c = __builtin_shufflevector(rows[8], rows[9], 2, 10, 3, 11, 6, 14, 7, 15);
  const v8f d = __builtin_shufflevector(rows[10], rows[11], 2, 10, 3, 11, 6, 14, 7, 15);
  const v8f h[4] = {__builtin_shufflevector(a, b, 0, 1, 8, 9, 4, 5, 12, 13),
                    __builtin_shufflevector(a, b, 2, 3, 10, 11, 6, 7, 14, 15),
                    __builtin_shufflevector(c, d, 0, 1, 8, 9, 4, 5, 12, 13),
                    __builtin_shufflevector(c, d, 2, 3, 10, 11, 6, 7, 14, 15)};
  transpose8(rows);
  for (int l = 0; l < 8; ++l) store8(&m[l].c[0], rows[l]);
  for (int k = 0; k < 4; ++k) {
    store4(&m[k].c[8], __builtin_shufflevector(h[k], h[k], 0, 1, 2, 3));
    store4(&m[k + 4].c[8], __builtin_shufflevector(h[k], h[k], 4, 5, 6, 7));
  }
}

// motor_normalize_fast (the generated motor_normalize) on 8 motors' coefficient rows, in place: the kernel
// once per lane, a loop GCC vectorizes across the lanes (the kernel is inlined, flatten). The script's SIMD
// batch kernel over the Motor arrays (12-float stride) was more than twice as slow (docs/runtime.md).
inline void normalize_rows(v8f m[kM]) {
  float in[kM][kB], out[kM][kB];
  for (std::size_t c = 0; c < kM; ++c) store8(in[c], m[c]);
  for (std::size_t l = 0; l < kB; ++l) {
    float x[kM], y[kM];
    for (std::size_t c = 0; c < kM; ++c) x[c] = in[c][l];
    kernels::motor_normalize(x, y);
    for (std::size_t c = 0; c < kM; ++c) out[c][l] = y[c];
  }
  for (std::size_t c = 0; c < kM; ++c) m[c] = load8(out[c]);
}
// 8 rows into out[0..count): straight for a whole block, else through a local block.
inline void scatter_rows(v8f rows[kM], std::size_t count, Motor* __restrict out) {
  if (count == kB) return scatter_rows(rows, out);
  Motor tmp[kB];
  scatter_rows(rows, tmp);
  for (std::size_t l = 0; l < count; ++l) out[l] = tmp[l];
}
#endif

// Joints m[0..count) into a block; lanes past count hold the identity.
inline void load_block(const Motor* __restrict m, std::size_t count, Block& b) {
#if defined(__GNUC__)
  if (count == kB) {
    v8f rows[kM];
    gather_rows([m](int l) -> const Motor& { return m[l]; }, rows);
    for (std::size_t c = 0; c < kM; ++c) store8(b[c], rows[c]);
    return;
  }
#endif
  const Motor one;
  for (std::size_t l = 0; l < kB; ++l)
    for (std::size_t c = 0; c < kM; ++c) b[c][l] = l < count ? m[l].c[c] : one.c[c];
}
// The first count lanes of a block into m[0..count).
inline void store_block(const Block& b, std::size_t count, Motor* __restrict m) {
#if defined(__GNUC__)
  if (count == kB) {
    v8f rows[kM];
    for (std::size_t c = 0; c < kM; ++c) rows[c] = load8(b[c]);
    scatter_rows(rows, m);
    return;
  }
#endif
  for (std::size_t l = 0; l < count; ++l)
    for (std::size_t c = 0; c < kM; ++c) m[l].c[c] = b[c][l];
}

// No motor of m[0..n) has a dilation (see motor_is_rigid): OR the b groups' bits (coefficient 7, lane 3 of
// the second 16 bytes; 9-11, lanes 1-3 of the third) over whole 16-byte words, without the sign bits.
inline bool all_rigid(const Motor* __restrict m, std::size_t n) {
#if defined(__GNUC__)
  using v4u = unsigned __attribute__((vector_size(16)));
  v4u mid = {}, high = {};
  for (std::size_t j = 0; j < n; ++j) {
    v4u x, y;
    __builtin_memcpy(&x, &m[j].c[4], sizeof x);
    __builtin_memcpy(&y, &m[j].c[8], sizeof y);
    mid |= x, high |= y;
  }
  return ((mid[3] | high[1] | high[2] | high[3]) << 1) == 0u;
#else
  std::uint32_t bits = 0;
  for (std::size_t j = 0; j < n; ++j)
    for (int c : {7, 9, 10, 11}) bits |= std::bit_cast<std::uint32_t>(m[j].c[c]);
  return (bits << 1) == 0u;
#endif
}

// Motors with a dilation are composed in split form (runtime/scripts/motor_split_mul.clu): G = a + b, H = a - b,
// U the einf blades, in c[0..3], c[4..7], c[8..11]. The blade form's product cancels when scales s and 1/s
// meet (1 - k^2 and k - k from terms of size 1, k = (1-s)/(1+s)): at s = 100 it loses about 6 bits per level
// of the hierarchy; the split form's G = GA GB, H = HA HB, U = HA UB + UA GB are plain products (and fewer:
// 64 mul + 52 add instead of 96 + 92). Forming G and H from a stored motor is exact for 1/3 <= s <= 3
// (Sterbenz) and otherwise rounds once.
inline void to_split(const Motor& m, float* __restrict s) { rotor_sign::split(m.c.data(), s, s + 4, s + 8); }
inline void from_split(const float* __restrict s, Motor& m) {
  for (int i = 0; i < 4; ++i) {
    m.c[rotor_sign::rotor_blade(i)] = 0.5f * (s[i] + s[4 + i]);
    m.c[rotor_sign::e_blade(i)] = 0.5f * (s[i] - s[4 + i]);
    m.c[rotor_sign::einf_blade(i)] = s[8 + i];
  }
}
// The product, scaled so that |G| + |H| = 2 (the normalization of motor_from_trs, where a = R): a product of
// dilators 1 + k1 E and 1 + k2 E is (1 + k1 k2)(1 + k E), so without it every level of a scaled hierarchy
// multiplies the magnitude by 1 + k1 k2 (0.04 for scales 100 and 0.01), and cga-motors, which blends the
// palette's coefficients, would weight each bone by its magnitude as well as by its skin weight.
inline void split_mul(const float* x, const float* y, float* out) {
  kernels::motor_split_mul(x, x + 4, x + 8, y, y + 4, y + 8, out, out + 4, out + 8);
  const float gg = out[0] * out[0] + out[1] * out[1] + out[2] * out[2] + out[3] * out[3];
  const float hh = out[4] * out[4] + out[5] * out[5] + out[6] * out[6] + out[7] * out[7];
  const float f = 2.0f / (std::sqrt(gg) + std::sqrt(hh));
  for (int c = 0; c < 12; ++c) out[c] *= f;
}

// ------------------------------------------------------------------------------------------------ checks

static_assert(sizeof(Motor) == 12 * sizeof(float), "the jobs treat Motor arrays as flat float arrays");

template <class Span>
bool fits(const Span& s, std::size_t n) {
  return s.size() >= n;
}

// The mode switches of Run() take any mode they do not name for screw, so Validate() admits only the enum's
// values (an Interpolation cast from an integer may hold another).
constexpr bool known_mode(Interpolation m) {
  return m == Interpolation::paper || m == Interpolation::nlerp || m == Interpolation::screw;
}

}  // namespace

}  // namespace cga
