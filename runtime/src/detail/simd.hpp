// The runtime's one SIMD vector header: 4- and 8-float GCC vector types with unaligned loads and stores, a
// lane-wise square root and the 8x8 transpose, shared by the pose jobs (jobs/) and the skinning loops
// (skinning/). GCC's vector extensions keep it portable: an 8-float operation is one AVX instruction in the
// x86-64-v3 clones and two SSE ones in the default clones. Everything is always inlined into its caller, so
// it is built for the caller's ISA and the AVX argument ABI that -Wpsabi warns about never applies.
#pragma once

#pragma GCC diagnostic ignored "-Wpsabi"

#include <cmath>

#define CGA_SIMD_INLINE inline __attribute__((always_inline))

namespace cga::simd {

using v4f = float __attribute__((vector_size(16)));
using v8f = float __attribute__((vector_size(32)));
using v8i = int __attribute__((vector_size(32)));

CGA_SIMD_INLINE v8f load8(const float* p) {
  v8f v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
CGA_SIMD_INLINE void store8(float* p, v8f v) { __builtin_memcpy(p, &v, sizeof v); }
CGA_SIMD_INLINE v4f load4(const float* p) {
  v4f v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
CGA_SIMD_INLINE void store4(float* p, v4f v) { __builtin_memcpy(p, &v, sizeof v); }
CGA_SIMD_INLINE v4f low(v8f v) { return __builtin_shufflevector(v, v, 0, 1, 2, 3); }
CGA_SIMD_INLINE v4f high(v8f v) { return __builtin_shufflevector(v, v, 4, 5, 6, 7); }

// Square root of every lane: a loop GCC turns into one vsqrtps (two sqrtps in the default clones).
CGA_SIMD_INLINE v8f sqrt8(v8f v) {
  float a[8];
  __builtin_memcpy(a, &v, sizeof a);
  for (float& x : a) x = std::sqrt(x);
  __builtin_memcpy(&v, a, sizeof a);
  return v;
}

// In place: r[i][l] becomes r[l][i] (unpcklps/unpckhps, shufps and vperm2f128).
CGA_SIMD_INLINE void transpose8(v8f r[8]) {
  v8f t[8], u[8];
  for (int k = 0; k < 4; ++k) {
    t[2 * k] = __builtin_shufflevector(r[2 * k], r[2 * k + 1], 0, 8, 1, 9, 4, 12, 5, 13);
    t[2 * k + 1] = __builtin_shufflevector(r[2 * k], r[2 * k + 1], 2, 10, 3, 11, 6, 14, 7, 15);
  }
  for (int k = 0; k < 2; ++k) {
    u[4 * k + 0] = __builtin_shufflevector(t[4 * k], t[4 * k + 2], 0, 1, 8, 9, 4, 5, 12, 13);
    u[4 * k + 1] = __builtin_shufflevector(t[4 * k], t[4 * k + 2], 2, 3, 10, 11, 6, 7, 14, 15);
    u[4 * k + 2] = __builtin_shufflevector(t[4 * k + 1], t[4 * k + 3], 0, 1, 8, 9, 4, 5, 12, 13);
    u[4 * k + 3] = __builtin_shufflevector(t[4 * k + 1], t[4 * k + 3], 2, 3, 10, 11, 6, 7, 14, 15);
  }
  for (int k = 0; k < 4; ++k) {
    r[k] = __builtin_shufflevector(u[k], u[k + 4], 0, 1, 2, 3, 8, 9, 10, 11);
    r[k + 4] = __builtin_shufflevector(u[k], u[k + 4], 4, 5, 6, 7, 12, 13, 14, 15);
  }
}

}  // namespace cga::simd
