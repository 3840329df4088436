// The AVX-512 (x86-64-v4) cga_motors loop (x86-64 only; SkinningJob takes it over the AVX2 one when the CPU
// has AVX-512 F/VL/DQ/BW and the job allows it). The other methods use the AVX2 table's loops.
#include "loops.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
// GCC 12's AVX-512 intrinsics pass _mm512_undefined_ps() as the unused merge source of their masked builtins,
// which -Wmaybe-uninitialized reports once they are inlined (GCC bug 105593); the value is never read.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include "x86.hpp"

namespace cga::skinning_detail {
namespace {

// ---- AVX-512 (x86-64-v4) cga_motors path, chosen at run time over the AVX2 one ----
//
// A 16-float motor entry is one zmm register, so pass 1 blends a vertex with 4 loads and 4 FMAs (AVX2: 8 and
// 8). The sign fix puts the three rotor-part products <q0, qk> in the 128-bit lanes 0-2 of one register and
// sums within the lanes by two in-lane swaps, instead of three hadd chains; the signed weight is a bitwise
// select of the dot's sign bit and the weight's other bits (the AVX2 path's copysign). 16 blended vertices
// are transposed into the rows in registers, and pass 2 (the generated kernel's ~126 operations per vertex)
// runs on 16 lanes.
#define CGA_AVX512 __attribute__((target("arch=x86-64-v4,prefer-vector-width=512")))

// rows[c][b .. b + 16) = coefficient c of z[0..16), c < 12: 16x16 transpose (unpack, in-lane shuffle, then
// two rounds of 128-bit lane shuffles), keeping only the 12 rows that hold coefficients.
CGA_AVX512 CGA_ALWAYS_INLINE void store_rows16_avx512(const __m512 z[16], MotorRows& rows, std::size_t b) {
  __m512 t[16], u[16];
  for (int k = 0; k < 8; ++k) {
    t[2 * k] = _mm512_unpacklo_ps(z[2 * k], z[2 * k + 1]);
    t[2 * k + 1] = _mm512_unpackhi_ps(z[2 * k], z[2 * k + 1]);
  }
  // u[4g + i], 128-bit lane L: coefficient 4L + i of vertices 4g .. 4g + 3.
  for (int g = 0; g < 4; ++g) {
    u[4 * g + 0] = _mm512_shuffle_ps(t[4 * g], t[4 * g + 2], 0x44);
    u[4 * g + 1] = _mm512_shuffle_ps(t[4 * g], t[4 * g + 2], 0xEE);
    u[4 * g + 2] = _mm512_shuffle_ps(t[4 * g + 1], t[4 * g + 3], 0x44);
    u[4 * g + 3] = _mm512_shuffle_ps(t[4 * g + 1], t[4 * g + 3], 0xEE);
  }
  for (int i = 0; i < 4; ++i) {
    // Lanes 0 and 1 of u[i], u[4 + i] | of u[8 + i], u[12 + i]; then lane 0 of each, and lane 1 of each.
    const __m512 p01 = _mm512_shuffle_f32x4(u[i], u[4 + i], 0x44), q01 = _mm512_shuffle_f32x4(u[8 + i], u[12 + i], 0x44);
    _mm512_store_ps(&rows[i][b], _mm512_shuffle_f32x4(p01, q01, 0x88));
    _mm512_store_ps(&rows[4 + i][b], _mm512_shuffle_f32x4(p01, q01, 0xDD));
    const __m512 p2 = _mm512_shuffle_f32x4(u[i], u[4 + i], 0xAA), q2 = _mm512_shuffle_f32x4(u[8 + i], u[12 + i], 0xAA);
    _mm512_store_ps(&rows[8 + i][b], _mm512_shuffle_f32x4(p2, q2, 0x88));
  }
}

// rotor_sign::signed_weight broadcast: the weight w with the sign of `dot` (copysign).
CGA_AVX512 CGA_ALWAYS_INLINE __m512 signed_weight(float w, __m512 dot) {
  const __m512i sign_mask = _mm512_set1_epi32(static_cast<int>(0x80000000u));
  return _mm512_castsi512_ps(
      _mm512_ternarylogic_epi32(sign_mask, _mm512_castps_si512(dot), _mm512_castps_si512(_mm512_set1_ps(w)), 0xCA));
}

// cga_motors pass 1 for the 16 vertices [i, i + 16) into rows[.][b .. b + 16).
CGA_AVX512 CGA_ALWAYS_INLINE void motor_blend16_avx512(const float* __restrict pal, const Streams& s, std::size_t i,
                                                       MotorRows& rows, std::size_t b) {
  __m512 z[16];
#pragma GCC unroll 16
  for (int v = 0; v < 16; ++v) {
    std::uint64_t j;
    __builtin_memcpy(&j, s.joints[i + v].data(), sizeof j);
    const float* w = s.weights[i + v].data();
    const __m512 z0 = _mm512_load_ps(pal + kEntry * (j & 0xffff));
    const __m512 z1 = _mm512_load_ps(pal + kEntry * ((j >> 16) & 0xffff));
    const __m512 z2 = _mm512_load_ps(pal + kEntry * ((j >> 32) & 0xffff));
    const __m512 z3 = _mm512_load_ps(pal + kEntry * (j >> 48));
    const __m128 r0 = _mm512_castps512_ps128(z0);
    __m512 d = _mm512_zextps128_ps512(_mm_mul_ps(r0, _mm512_castps512_ps128(z1)));
    d = _mm512_insertf32x4(d, _mm_mul_ps(r0, _mm512_castps512_ps128(z2)), 1);
    d = _mm512_insertf32x4(d, _mm_mul_ps(r0, _mm512_castps512_ps128(z3)), 2);
    d = _mm512_add_ps(d, _mm512_permute_ps(d, 0xB1));
    d = _mm512_add_ps(d, _mm512_permute_ps(d, 0x4E));  // 128-bit lane k - 1: <q0, qk> in all 4 floats
    const __m512 w1 = signed_weight(w[1], _mm512_shuffle_f32x4(d, d, 0x00));
    const __m512 w2 = signed_weight(w[2], _mm512_shuffle_f32x4(d, d, 0x55));
    const __m512 w3 = signed_weight(w[3], _mm512_shuffle_f32x4(d, d, 0xAA));
    z[v] = _mm512_add_ps(_mm512_fmadd_ps(w1, z1, _mm512_mul_ps(_mm512_set1_ps(w[0]), z0)),
                         _mm512_fmadd_ps(w3, z3, _mm512_mul_ps(w2, z2)));
  }
  store_rows16_avx512(z, rows, b);
}

template <bool kNormals, bool kLarge>
CGA_AVX512 CGA_ALWAYS_INLINE void motor_block_avx512(const float* __restrict pal, const Streams& s,
                                                     std::size_t begin, std::size_t end) {
  alignas(64) MotorRows rows;
  std::size_t i = begin;
  for (; i + 16 <= end; i += 16) {
    if constexpr (kLarge) prefetch_ahead<kNormals>(s, i), prefetch_ahead<kNormals>(s, i + 8);
    motor_blend16_avx512(pal, s, i, rows, i - begin);
  }
  for (; i < end; ++i) motor_blend_one(pal, s, i, rows, i - begin);
  motor_rows_apply<kNormals>(rows, s, begin, end);
}

// flatten: pass 2's generated kernel is inlined and vectorized on 16 lanes.
template <bool kNormals, bool kLarge>
CGA_AVX512 __attribute__((flatten)) bool motor_block_avx512_fn(const float* pal, const Streams& s, std::size_t begin,
                                                               std::size_t end, std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block_avx512<kNormals, kLarge>(pal, s, begin, end);
  return true;
}

}  // namespace

const SkinKernels* avx512_kernels() {
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                          __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
  const SkinKernels* avx2 = avx2_kernels();
  if (!has || !avx2) return nullptr;
  static const SkinKernels k{
      "avx512",
      {{avx2->matrix[0][0], avx2->matrix[0][1]}, {avx2->matrix[1][0], avx2->matrix[1][1]}},
      {{motor_block_avx512_fn<false, false>, motor_block_avx512_fn<false, true>},
       {motor_block_avx512_fn<true, false>, motor_block_avx512_fn<true, true>}},
      {{nullptr, nullptr}, {nullptr, nullptr}},
      nullptr,
      {{avx2->matrix_strided[0][0], avx2->matrix_strided[0][1]},
       {avx2->matrix_strided[1][0], avx2->matrix_strided[1][1]}},
      {}};
  return &k;
}

}  // namespace cga::skinning_detail
#else
namespace cga::skinning_detail {
const SkinKernels* avx512_kernels() { return nullptr; }
}  // namespace cga::skinning_detail
#endif
