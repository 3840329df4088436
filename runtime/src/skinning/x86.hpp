// x86 helpers shared by the AVX2 and AVX-512 skinning files: prefetching a large mesh's input streams ahead.
#pragma once

#include <immintrin.h>

#include "loops.hpp"

#define CGA_AVX2 __attribute__((target("avx2,fma")))

namespace cga::skinning_detail {

// Prefetches the input streams of the 8 vertices kPrefetchAhead after i. A large mesh's loop reads 8 streams
// (6 with positions only) and is bound by how many misses one core keeps in flight; the hardware prefetchers
// alone leave lbs with normals at ~220 M vertices/s on 1 M vertices, this at ~245. The addresses may lie past
// the arrays: a prefetch never faults, and they are formed as integers, not as out-of-range pointers.
constexpr std::size_t kPrefetchAhead = 1024;
CGA_AVX2 CGA_ALWAYS_INLINE void prefetch(const void* base, std::size_t byte_offset) {
  _mm_prefetch(reinterpret_cast<const char*>(reinterpret_cast<std::uintptr_t>(base) + byte_offset), _MM_HINT_T0);
}
template <bool kNormals>
CGA_AVX2 CGA_ALWAYS_INLINE void prefetch_ahead(const Streams& s, std::size_t i) {
  const std::size_t v = i + kPrefetchAhead;
  for (const float* p : {s.px, s.py, s.pz}) prefetch(p, 4 * v);
  if constexpr (kNormals)
    for (const float* p : {s.nx, s.ny, s.nz}) prefetch(p, 4 * v);
  prefetch(s.joints, 8 * v);        // 8 vertices: one 64-byte line
  prefetch(s.weights, 16 * v);      // 8 vertices: two lines
  prefetch(s.weights, 16 * v + 64);
}

// The strided loops' prefetch: the lines of the 8 vertices kPrefetchAhead after i, in the positions' stream
// and in the joints', weights' and normals' streams where those do not start inside the positions' window (in
// an interleaved vertex buffer they share its lines). py and pz are taken to share px's lines.
CGA_AVX2 CGA_ALWAYS_INLINE void prefetch_window(const void* base, std::size_t stride_bytes, std::size_t v,
                                                std::uintptr_t window, std::size_t span) {
  if (reinterpret_cast<std::uintptr_t>(base) + stride_bytes * v - window < span) return;
  for (std::size_t b = 0; b < 8 * stride_bytes; b += 64) prefetch(base, stride_bytes * v + b);
}
template <bool kNormals>
CGA_AVX2 CGA_ALWAYS_INLINE void prefetch_ahead_strided(const Streams& s, std::size_t i) {
  const std::size_t v = i + kPrefetchAhead;
  const std::uintptr_t window = reinterpret_cast<std::uintptr_t>(s.px) + 4 * s.ip * v;
  const std::size_t span = 8 * 4 * s.ip;
  for (std::size_t b = 0; b < span; b += 64) prefetch(s.px, 4 * s.ip * v + b);
  prefetch_window(s.joints, 8 * s.js, v, window, span);
  prefetch_window(s.weights, 16 * s.ws, v, window, span);
  if constexpr (kNormals) prefetch_window(s.nx, 4 * s.in, v, window, span);
}

// The output lines of the 8 vertices from i on (positions, and normals where they do not start inside the
// positions' window), for cga_motors: its pass 2 writes a whole block in one burst, and lines not yet in
// cache stall that burst on their reads for ownership.
template <bool kNormals>
CGA_AVX2 CGA_ALWAYS_INLINE void prefetch_outputs_strided(const Streams& s, std::size_t i) {
  const std::uintptr_t window = reinterpret_cast<std::uintptr_t>(s.ox) + 4 * s.op * i;
  const std::size_t span = 8 * 4 * s.op;
  for (std::size_t b = 0; b < span; b += 64) prefetch(s.ox, 4 * s.op * i + b);
  if constexpr (kNormals) prefetch_window(s.onx, 4 * s.on, i, window, span);
}

}  // namespace cga::skinning_detail
