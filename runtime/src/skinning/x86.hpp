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

}  // namespace cga::skinning_detail
