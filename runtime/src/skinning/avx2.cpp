// Hand-written AVX2 + FMA skinning loops (x86-64 only; SkinningJob takes them when the CPU has both).
//
// The portable loops keep one vertex per iteration and write three scalars per output stream; these blend
// within the vertex as before but gather 8 vertices' results in registers, transpose them and store whole
// 8-float rows, so the stores, the point transform and the normal renormalization run across vertices.
// Results agree with the portable loops to float rounding (other summation order, FMA).
#include "loops.hpp"

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
#include "x86.hpp"

namespace cga::skinning_detail {
namespace {

// Blended 3x4 matrix of a vertex with joints j and weights w as (c0 | c1), (c2 | t), from the matrix palette
// layout.
CGA_AVX2 CGA_ALWAYS_INLINE void blend_matrix_avx2(const float* __restrict pal, const std::array<std::uint16_t, 4>& j,
                                                  const float* w, __m256& lo, __m256& hi) {
  const float* a = pal + kEntry * j[0];
  const float* b = pal + kEntry * j[1];
  const float* c = pal + kEntry * j[2];
  const float* d = pal + kEntry * j[3];
  const __m256 w0 = _mm256_broadcast_ss(w), w1 = _mm256_broadcast_ss(w + 1);
  const __m256 w2 = _mm256_broadcast_ss(w + 2), w3 = _mm256_broadcast_ss(w + 3);
  // Two partial sums per half: shorter FMA dependency chains.
  lo = _mm256_add_ps(_mm256_fmadd_ps(w1, _mm256_loadu_ps(b), _mm256_mul_ps(w0, _mm256_loadu_ps(a))),
                     _mm256_fmadd_ps(w3, _mm256_loadu_ps(d), _mm256_mul_ps(w2, _mm256_loadu_ps(c))));
  hi = _mm256_add_ps(_mm256_fmadd_ps(w1, _mm256_loadu_ps(b + 8), _mm256_mul_ps(w0, _mm256_loadu_ps(a + 8))),
                     _mm256_fmadd_ps(w3, _mm256_loadu_ps(d + 8), _mm256_mul_ps(w2, _mm256_loadu_ps(c + 8))));
}

// lo * (x x x x y y y y) + hi * (z z z z h h h h): its two halves sum to (c0 x + c1 y + c2 z + h t, 0).
CGA_AVX2 CGA_ALWAYS_INLINE __m256 apply_halves(__m256 lo, __m256 hi, const float* x, const float* y,
                                               const float* z, __m256 h) {
  const __m256 xy = _mm256_blend_ps(_mm256_broadcast_ss(x), _mm256_broadcast_ss(y), 0xF0);
  const __m256 zh = _mm256_blend_ps(_mm256_broadcast_ss(z), h, 0xF0);
  return _mm256_fmadd_ps(lo, xy, _mm256_mul_ps(hi, zh));
}

// (x y z 0 of a | of b) from two vertices' apply_halves results.
CGA_AVX2 CGA_ALWAYS_INLINE __m256 pair_halves(__m256 a, __m256 b) {
  return _mm256_add_ps(_mm256_permute2f128_ps(a, b, 0x20), _mm256_permute2f128_ps(a, b, 0x31));
}

// u[k] = (x y z 0 of vertex k | of vertex k + 4), k < 4: the 8 vertices' x, y and z rows.
CGA_AVX2 CGA_ALWAYS_INLINE void transpose_pairs(const __m256 u[4], __m256& rx, __m256& ry, __m256& rz) {
  const __m256 xy01 = _mm256_unpacklo_ps(u[0], u[1]);  // x0 x1 y0 y1 | x4 x5 y4 y5
  const __m256 z01 = _mm256_unpackhi_ps(u[0], u[1]);   // z0 z1 0 0  | z4 z5 0 0
  const __m256 xy23 = _mm256_unpacklo_ps(u[2], u[3]);
  const __m256 z23 = _mm256_unpackhi_ps(u[2], u[3]);
  rx = _mm256_shuffle_ps(xy01, xy23, 0x44);
  ry = _mm256_shuffle_ps(xy01, xy23, 0xEE);
  rz = _mm256_shuffle_ps(z01, z23, 0x44);
}


// The renormalization factor on 8 lanes: 1 / |n|, or 0 when |n| = 0, as the portable loops' but from the
// reciprocal square root estimate and one Newton step (relative error below 1e-6): the square root and the
// division it replaces kept this host's divider busy about 20 cycles per 8 vertices (lbs with normals on 64 K
// vertices: 147 -> 172 M vertices/s, medians of an A/B).
CGA_AVX2 CGA_ALWAYS_INLINE __m256 inv_length8(__m256 x, __m256 y, __m256 z) {
  const __m256 sum = _mm256_fmadd_ps(z, z, _mm256_fmadd_ps(y, y, _mm256_mul_ps(x, x)));
  const __m256 nonzero = _mm256_cmp_ps(sum, _mm256_setzero_ps(), _CMP_GT_OQ);
  const __m256 len2 = _mm256_max_ps(sum, _mm256_set1_ps(1e-30f));
  const __m256 r = _mm256_rsqrt_ps(len2);
  // r (1.5 - 0.5 len2 r^2)
  const __m256 t = _mm256_fnmadd_ps(_mm256_mul_ps(_mm256_mul_ps(_mm256_set1_ps(0.5f), len2), r), r, _mm256_set1_ps(1.5f));
  return _mm256_and_ps(nonzero, _mm256_mul_ps(r, t));
}

// renormalize (loops.hpp) 8 vertices at a time with inv_length8; a last group of fewer the portable way.
CGA_AVX2 CGA_ALWAYS_INLINE void renormalize_avx2(const Streams& s, std::size_t begin, std::size_t end) {
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) {
    const __m256 x = _mm256_loadu_ps(s.onx + i), y = _mm256_loadu_ps(s.ony + i), z = _mm256_loadu_ps(s.onz + i);
    const __m256 inv = inv_length8(x, y, z);
    _mm256_storeu_ps(s.onx + i, _mm256_mul_ps(x, inv));
    _mm256_storeu_ps(s.ony + i, _mm256_mul_ps(y, inv));
    _mm256_storeu_ps(s.onz + i, _mm256_mul_ps(z, inv));
  }
  renormalize(s, i, end);
}

// Strided streams hold each vertex's x y z as one triple (p, p + 1, p + 2: SkinningJob::Run takes the strided
// loops only then). A triple is loaded as 8 + 4 bytes and stored as 8 + 4 bytes, never touching the float
// after it (another attribute of the vertex, or past the end of the buffer).
CGA_AVX2 CGA_ALWAYS_INLINE __m128 load3(const float* p) {
  const __m128 xy = _mm_castpd_ps(_mm_load_sd(reinterpret_cast<const double*>(p)));
  return _mm_insert_ps(xy, _mm_load_ss(p + 2), 0x20);  // (x y z 0)
}
CGA_AVX2 CGA_ALWAYS_INLINE void store3(float* p, __m128 v) {
  _mm_storel_pi(reinterpret_cast<__m64*>(p), v);
  _mm_store_ss(p + 2, _mm_movehl_ps(v, v));
}
// Lanes 0-3 and 4-7 of a pair register (x y z . of vertex k | of vertex k + 4) to the triples a and b.
CGA_AVX2 CGA_ALWAYS_INLINE void store3_pair(float* a, float* b, __m256 v) {
  store3(a, _mm256_castps256_ps128(v));
  store3(b, _mm256_extractf128_ps(v, 1));
}

// The triples of vertices p + v * stride, v < 8, as x, y and z rows.
CGA_AVX2 CGA_ALWAYS_INLINE void load_triples8(const float* p, std::size_t stride, __m256& x, __m256& y, __m256& z) {
  __m256 u[4];
#pragma GCC unroll 4
  for (int k = 0; k < 4; ++k)
    u[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(load3(p + k * stride)), load3(p + (k + 4) * stride), 1);
  transpose_pairs(u, x, y, z);
}

// Rows x, y, z of 8 vertices to the triples p + v * stride (the inverse of load_triples8).
CGA_AVX2 CGA_ALWAYS_INLINE void store_triples8(float* p, std::size_t stride, __m256 x, __m256 y, __m256 z) {
  const __m256 xy0 = _mm256_unpacklo_ps(x, y), xy1 = _mm256_unpackhi_ps(x, y);  // x0 y0 x1 y1 | x4 y4 x5 y5
  const __m256 z0 = _mm256_unpacklo_ps(z, z), z1 = _mm256_unpackhi_ps(z, z);    // z0 z0 z1 z1 | z4 z4 z5 z5
  store3_pair(p, p + 4 * stride, _mm256_shuffle_ps(xy0, z0, 0x44));
  store3_pair(p + stride, p + 5 * stride, _mm256_shuffle_ps(xy0, z0, 0xEE));
  store3_pair(p + 2 * stride, p + 6 * stride, _mm256_shuffle_ps(xy1, z1, 0x44));
  store3_pair(p + 3 * stride, p + 7 * stride, _mm256_shuffle_ps(xy1, z1, 0xEE));
}

template <bool kNormals, bool kPrefetch>
CGA_AVX2 CGA_ALWAYS_INLINE void matrix_block_avx2(const float* __restrict pal, const Streams& streams,
                                                  std::size_t begin, std::size_t end) {
  const Streams s = streams;  // a local copy: GCC reloads the pointers after every store otherwise
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  // A group's normals are scaled and stored one group later, as in matrix_strided_avx2_fn.
  __m256 pending[3], pending_inv;
  std::size_t pending_i = begin;
  bool have_pending = false;
  const auto finish_pending = [&]() CGA_AVX2 {
    _mm256_storeu_ps(s.onx + pending_i, _mm256_mul_ps(pending[0], pending_inv));
    _mm256_storeu_ps(s.ony + pending_i, _mm256_mul_ps(pending[1], pending_inv));
    _mm256_storeu_ps(s.onz + pending_i, _mm256_mul_ps(pending[2], pending_inv));
  };
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) {
    if constexpr (kPrefetch) prefetch_ahead<kNormals>(s, i);
    // Vertices k and k + 4 together, so only the 4 (or 8) pair registers live across the group; unrolled,
    // so they stay in registers.
    __m256 p[4], n[4];
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      __m256 lo, hi, lo4, hi4;
      const std::size_t a = i + k, b = i + k + 4;
      blend_matrix_avx2(pal, s.joints[a], s.weights[a].data(), lo, hi);
      blend_matrix_avx2(pal, s.joints[b], s.weights[b].data(), lo4, hi4);
      p[k] = pair_halves(apply_halves(lo, hi, s.px + a, s.py + a, s.pz + a, one),
                         apply_halves(lo4, hi4, s.px + b, s.py + b, s.pz + b, one));
      if constexpr (kNormals)
        n[k] = pair_halves(apply_halves(lo, hi, s.nx + a, s.ny + a, s.nz + a, zero),
                           apply_halves(lo4, hi4, s.nx + b, s.ny + b, s.nz + b, zero));
    }
    __m256 x, y, z;
    transpose_pairs(p, x, y, z);
    _mm256_storeu_ps(s.ox + i, x);
    _mm256_storeu_ps(s.oy + i, y);
    _mm256_storeu_ps(s.oz + i, z);
    if constexpr (kNormals) {
      if (have_pending) finish_pending();
      transpose_pairs(n, pending[0], pending[1], pending[2]);
      pending_inv = inv_length8(pending[0], pending[1], pending[2]);
      pending_i = i, have_pending = true;
    }
  }
  if constexpr (kNormals)
    if (have_pending) finish_pending();
  if (i < end) matrix_block<kNormals>(pal, s, i, end);
}

template <bool kNormals, bool kPrefetch>
CGA_AVX2 bool matrix_block_avx2_fn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
                                   std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  matrix_block_avx2<kNormals, kPrefetch>(pal, s, begin, end);
  return true;
}

// lbs and cga_points on strided streams (an engine's interleaved vertex buffer): matrix_block_avx2's arithmetic
// with each vertex's inputs read in place and its outputs written lane by lane, positions straight from the
// pair registers and normals after the 8-wide renormalization, so nothing goes through a staging buffer and
// the results are bit-identical to the packed loop's. A block's last (end - begin) % 8 vertices are staged
// and take the portable loop, as they do in a packed run.
// block_ok (loops.hpp) for strided joints and weights (Streams::js, ws) on 128-bit vectors: a vertex's 4
// joints and 4 weight exponents are one load and one unsigned max each (a scalar loop took ~20
// instructions per vertex, 15 % of an interleaved lbs run).
CGA_AVX2 CGA_ALWAYS_INLINE bool block_ok_strided_avx2(const Streams& s, std::size_t begin, std::size_t end,
                                                      std::size_t palette) {
  const __m128i exponent = _mm_set1_epi32(0x7f800000);
  __m128i joints = _mm_setzero_si128(), exponents = _mm_setzero_si128();
  for (std::size_t i = begin; i < end; ++i) {
    joints = _mm_max_epu16(joints, _mm_loadl_epi64(reinterpret_cast<const __m128i*>(s.joints[i * s.js].data())));
    exponents = _mm_max_epu32(
        exponents, _mm_and_si128(exponent, _mm_loadu_si128(reinterpret_cast<const __m128i*>(s.weights[i * s.ws].data()))));
  }
  joints = _mm_max_epu16(joints, _mm_srli_si128(joints, 4));
  joints = _mm_max_epu16(joints, _mm_srli_si128(joints, 2));
  exponents = _mm_max_epu32(exponents, _mm_srli_si128(exponents, 8));
  exponents = _mm_max_epu32(exponents, _mm_srli_si128(exponents, 4));
  const auto max_joint = static_cast<std::uint16_t>(_mm_extract_epi16(joints, 0));
  const auto max_exponent = static_cast<std::uint32_t>(_mm_cvtsi128_si32(exponents));
  return max_exponent < 0x7f800000u && max_joint < palette;
}

// A strided stream's cursor: the vertex it points at and the bytes to the next one. The strided loops walk
// vertex by vertex with one cursor per stream, so each vertex costs one add per stream (computing the 8
// vertices' addresses of each stream from their indices needed ~50 live values and spilled them).
template <class T>
struct Cursor {
  T* p;
  std::size_t step;  // bytes
  CGA_ALWAYS_INLINE Cursor(T* base, std::size_t stride, std::size_t i)
      : p(reinterpret_cast<T*>(reinterpret_cast<std::uintptr_t>(base) + sizeof(T) * stride * i)),
        step(sizeof(T) * stride) {}
  CGA_ALWAYS_INLINE T* at(std::size_t k) const {
    return reinterpret_cast<T*>(reinterpret_cast<std::uintptr_t>(p) + step * k);
  }
  CGA_ALWAYS_INLINE void next() { p = at(1); }
};

template <bool kNormals, bool kPrefetch>
CGA_AVX2 bool matrix_strided_avx2_fn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
                                     std::size_t palette) {
  if (!block_ok_strided_avx2(s, begin, end, palette)) return false;
  Cursor<const float> p(s.px, s.ip, begin), nrm(s.nx, s.in, begin);
  Cursor<const std::array<std::uint16_t, 4>> j(s.joints, s.js, begin);
  Cursor<const std::array<float, 4>> w(s.weights, s.ws, begin);
  Cursor<float> o(s.ox, s.op, begin), on(s.onx, s.on, begin);
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  // A group's normals are scaled and stored one group later (software pipelining): their factors' latency then
  // runs under the next group's blends instead of stalling the loop (with the square root and division of the
  // time, finishing in their own iteration cost 30 % of an interleaved run with normals).
  __m256 pending[4], pending_inv;
  Cursor<float> pending_on = on;
  bool have_pending = false;
  const auto finish_pending = [&]() CGA_AVX2 {
    // The packed loop's factors applied to the pair registers lane by lane: the same products, so the same bits.
    const Cursor<float>& c = pending_on;
    store3_pair(c.at(0), c.at(4), _mm256_mul_ps(pending[0], _mm256_permute_ps(pending_inv, 0x00)));
    store3_pair(c.at(1), c.at(5), _mm256_mul_ps(pending[1], _mm256_permute_ps(pending_inv, 0x55)));
    store3_pair(c.at(2), c.at(6), _mm256_mul_ps(pending[2], _mm256_permute_ps(pending_inv, 0xAA)));
    store3_pair(c.at(3), c.at(7), _mm256_mul_ps(pending[3], _mm256_permute_ps(pending_inv, 0xFF)));
  };
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) {
    if constexpr (kPrefetch) prefetch_ahead_strided<kNormals>(s, i);
    __m128 n[8];
#pragma GCC unroll 8
    for (int v = 0; v < 8; ++v) {
      __m256 lo, hi;
      blend_matrix_avx2(pal, *j.p, w.p->data(), lo, hi);
      const __m256 t = apply_halves(lo, hi, p.p, p.p + 1, p.p + 2, one);
      store3(o.p, _mm_add_ps(_mm256_castps256_ps128(t), _mm256_extractf128_ps(t, 1)));
      if constexpr (kNormals) {
        const __m256 u = apply_halves(lo, hi, nrm.p, nrm.p + 1, nrm.p + 2, zero);
        n[v] = _mm_add_ps(_mm256_castps256_ps128(u), _mm256_extractf128_ps(u, 1));
        nrm.next();
      }
      p.next(), j.next(), w.next(), o.next();
    }
    if constexpr (kNormals) {
      if (have_pending) finish_pending();
      // The packed loop's factors: the rows are transposed only to compute them.
      __m256 x, y, z;
      for (int k = 0; k < 4; ++k) pending[k] = _mm256_insertf128_ps(_mm256_castps128_ps256(n[k]), n[k + 4], 1);
      transpose_pairs(pending, x, y, z);
      pending_inv = inv_length8(x, y, z);
      pending_on = on, have_pending = true;
      on.p = on.at(8);
    }
  }
  if constexpr (kNormals)
    if (have_pending) finish_pending();
  if (i < end) {
    Staged t;
    matrix_block<kNormals>(pal, stage_in(s, i, end - i, kNormals, t), 0, end - i);
    stage_out(t, s, i, end - i, kNormals);
  }
  return true;
}

// <G_a, G_b> of two motor entries' lanes 0-3 as motor_blend8_avx2 computes it: (g0 h0 + g1 h1) + (g2 h2 + g3 h3),
// each product rounded (no FMA), so a table of its signs gives the same bits as the dot products.
CGA_AVX2 CGA_ALWAYS_INLINE float rotor_dot_avx2(const float* a, const float* b) {
  const __m128 p = _mm_mul_ps(_mm_loadu_ps(a), _mm_loadu_ps(b));
  const __m128 h = _mm_hadd_ps(p, p);
  return _mm_cvtss_f32(_mm_hadd_ps(h, h));
}

// The pair-sign data after the motor entries (loops.hpp, "negated motors" and "pair signs").
CGA_AVX2 void pair_signs_avx2(float* pal, std::size_t palette) {
  float* negated = pal + kEntry * palette;
  for (std::size_t e = 0; e < kEntry * palette; ++e) negated[e] = -pal[e];
  std::uint8_t* out = reinterpret_cast<std::uint8_t*>(pal + 2 * kEntry * palette);
  for (std::size_t a = 0; a < palette; ++a)
    for (std::size_t b = 0; b < palette; ++b)
      out[a * palette + b] =
          std::signbit(rotor_dot_avx2(pal + kEntry * a, pal + kEntry * b)) ? static_cast<std::uint8_t>(palette) : 0;
}

// cga_motors pass 1 for 8 vertices: blend within each vertex with the rotor sign fix, then transpose the 8
// blended motors into rows[.][b .. b + 8). The sign fix either computes the G-lane dot products and signs
// the weights, or (kSigns) reads the pair-sign table and takes influence k from the negated copy of its
// entry: w (-q) is -(w q) exactly, so both give the same bits, and the table takes the dot products, the
// horizontal adds and the weight shuffles off each vertex's dependency chain.
// Joints and weights come through cursors (packed runs pass stride-1 cursors), which this advances by 8.
template <bool kSigns>
CGA_AVX2 CGA_ALWAYS_INLINE void motor_blend8_avx2(const float* __restrict pal, std::size_t palette,
                                                  Cursor<const std::array<std::uint16_t, 4>>& jc,
                                                  Cursor<const std::array<float, 4>>& wc, MotorRows& rows,
                                                  std::size_t b) {
  __m256 lo[8], hi[8];
#pragma GCC unroll 8
  for (int v = 0; v < 8; ++v) {
    const std::array<std::uint16_t, 4> j = *jc.p;
    const float* wp = wc.p->data();
    jc.next(), wc.next();
    const float* q0 = pal + kEntry * j[0];
    const float *q1, *q2, *q3;
    __m256 w0, w1, w2, w3;
    if constexpr (kSigns) {
      const std::uint8_t* row = reinterpret_cast<const std::uint8_t*>(pal + 2 * kEntry * palette) + palette * j[0];
      q1 = pal + kEntry * (j[1] + row[j[1]]);
      q2 = pal + kEntry * (j[2] + row[j[2]]);
      q3 = pal + kEntry * (j[3] + row[j[3]]);
      // |w|, as copysign gives it on the other path.
      const __m256 abs_mask = _mm256_castsi256_ps(_mm256_set1_epi32(0x7fffffff));
      w0 = _mm256_and_ps(abs_mask, _mm256_broadcast_ss(wp));
      w1 = _mm256_and_ps(abs_mask, _mm256_broadcast_ss(wp + 1));
      w2 = _mm256_and_ps(abs_mask, _mm256_broadcast_ss(wp + 2));
      w3 = _mm256_and_ps(abs_mask, _mm256_broadcast_ss(wp + 3));
    } else {
      q1 = pal + kEntry * j[1];
      q2 = pal + kEntry * j[2];
      q3 = pal + kEntry * j[3];
      // rotor_sign::signed_weight on 4 lanes: the G-lane dot products <q0, qk> as (0, d1, d2, d3), then the
      // weights with those signs (copysign).
      const __m128 sign_mask = _mm_set1_ps(-0.0f);
      const __m128 r0 = _mm_loadu_ps(q0);
      const __m128 p1 = _mm_mul_ps(r0, _mm_loadu_ps(q1));
      const __m128 p2 = _mm_mul_ps(r0, _mm_loadu_ps(q2));
      const __m128 p3 = _mm_mul_ps(r0, _mm_loadu_ps(q3));
      const __m128 dots = _mm_hadd_ps(_mm_hadd_ps(_mm_setzero_ps(), p1), _mm_hadd_ps(p2, p3));
      const __m128 sw = _mm_or_ps(_mm_andnot_ps(sign_mask, _mm_loadu_ps(wp)), _mm_and_ps(sign_mask, dots));
      const __m256 sw2 = _mm256_castps128_ps256(sw);
      w0 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(0));
      w1 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(1));
      w2 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(2));
      w3 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(3));
    }
    const __m256 l0 = _mm256_loadu_ps(q0), l1 = _mm256_loadu_ps(q1), l2 = _mm256_loadu_ps(q2), l3 = _mm256_loadu_ps(q3);
    lo[v] = _mm256_add_ps(_mm256_fmadd_ps(w1, l1, _mm256_mul_ps(w0, l0)), _mm256_fmadd_ps(w3, l3, _mm256_mul_ps(w2, l2)));
    // The last 4 lanes of an entry are padding: 128-bit halves suffice.
    const __m128 h = _mm_add_ps(_mm_fmadd_ps(_mm256_castps256_ps128(w1), _mm_loadu_ps(q1 + 8),
                                             _mm_mul_ps(_mm256_castps256_ps128(w0), _mm_loadu_ps(q0 + 8))),
                                _mm_fmadd_ps(_mm256_castps256_ps128(w3), _mm_loadu_ps(q3 + 8),
                                             _mm_mul_ps(_mm256_castps256_ps128(w2), _mm_loadu_ps(q2 + 8))));
    hi[v] = _mm256_castps128_ps256(h);
  }
  // 8x8 transpose of the first 8 coefficients.
  __m256 t[8], u[8];
  for (int k = 0; k < 4; ++k) {
    t[2 * k] = _mm256_unpacklo_ps(lo[2 * k], lo[2 * k + 1]);
    t[2 * k + 1] = _mm256_unpackhi_ps(lo[2 * k], lo[2 * k + 1]);
  }
  for (int k = 0; k < 2; ++k) {
    u[4 * k + 0] = _mm256_shuffle_ps(t[4 * k], t[4 * k + 2], 0x44);
    u[4 * k + 1] = _mm256_shuffle_ps(t[4 * k], t[4 * k + 2], 0xEE);
    u[4 * k + 2] = _mm256_shuffle_ps(t[4 * k + 1], t[4 * k + 3], 0x44);
    u[4 * k + 3] = _mm256_shuffle_ps(t[4 * k + 1], t[4 * k + 3], 0xEE);
  }
  for (int r = 0; r < 4; ++r) {
    _mm256_store_ps(&rows[r][b], _mm256_permute2f128_ps(u[r], u[r + 4], 0x20));
    _mm256_store_ps(&rows[r + 4][b], _mm256_permute2f128_ps(u[r], u[r + 4], 0x31));
  }
  // 8x4 transpose of the last 4: pair vertices v and v + 4 in one register, then 4x4 within the halves.
  __m256 g[4];
  for (int k = 0; k < 4; ++k) g[k] = _mm256_insertf128_ps(hi[k], _mm256_castps256_ps128(hi[k + 4]), 1);
  const __m256 a01 = _mm256_unpacklo_ps(g[0], g[1]), b01 = _mm256_unpackhi_ps(g[0], g[1]);
  const __m256 a23 = _mm256_unpacklo_ps(g[2], g[3]), b23 = _mm256_unpackhi_ps(g[2], g[3]);
  _mm256_store_ps(&rows[8][b], _mm256_shuffle_ps(a01, a23, 0x44));
  _mm256_store_ps(&rows[9][b], _mm256_shuffle_ps(a01, a23, 0xEE));
  _mm256_store_ps(&rows[10][b], _mm256_shuffle_ps(b01, b23, 0x44));
  _mm256_store_ps(&rows[11][b], _mm256_shuffle_ps(b01, b23, 0xEE));
}


template <bool kNormals, bool kPrefetch, bool kSigns>
CGA_AVX2 CGA_ALWAYS_INLINE void motor_block_avx2(const float* __restrict pal, std::size_t palette, const Streams& s,
                                                 std::size_t begin, std::size_t end) {
  alignas(64) MotorRows rows;
  Cursor<const std::array<std::uint16_t, 4>> j(s.joints, 1, begin);
  Cursor<const std::array<float, 4>> w(s.weights, 1, begin);
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) {
    if constexpr (kPrefetch) prefetch_ahead<kNormals>(s, i);
    motor_blend8_avx2<kSigns>(pal, palette, j, w, rows, i - begin);
  }
  for (; i < end; ++i) motor_blend_one(pal, s, i, rows, i - begin);
  motor_rows_apply<kNormals, false>(rows, s, begin, end);
  if constexpr (kNormals) renormalize_avx2(s, begin, end);
}

template <bool kNormals, bool kPrefetch, bool kSigns = false>
CGA_AVX2 __attribute__((flatten)) bool motor_block_avx2_fn(const float* pal, const Streams& s, std::size_t begin,
                                                           std::size_t end, std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block_avx2<kNormals, kPrefetch, kSigns>(pal, palette, s, begin, end);
  return true;
}

// stage_in / stage_out (loops.hpp) for cga_motors' pass 2 on strided triples, 8 vertices at a time through
// load_triples8 / store_triples8 (the scalar copies took a quarter of an interleaved run). Joints and weights
// are not staged: pass 2 reads neither. Vertices [i, i + 8) go to slots [v, v + 8).
CGA_AVX2 CGA_ALWAYS_INLINE void stage_triples8_in_avx2(const Streams& s, std::size_t i, std::size_t v, bool normals,
                                                      Staged& t) {
  __m256 x, y, z;
  load_triples8(s.px + i * s.ip, s.ip, x, y, z);
  _mm256_store_ps(t.f[0] + v, x), _mm256_store_ps(t.f[1] + v, y), _mm256_store_ps(t.f[2] + v, z);
  if (normals) {
    load_triples8(s.nx + i * s.in, s.in, x, y, z);
    _mm256_store_ps(t.f[3] + v, x), _mm256_store_ps(t.f[4] + v, y), _mm256_store_ps(t.f[5] + v, z);
  }
}
CGA_AVX2 CGA_ALWAYS_INLINE void stage_triples_out_avx2(const Staged& t, const Streams& s, std::size_t begin,
                                                      std::size_t count, bool normals) {
  std::size_t v = 0;
  for (; v + 8 <= count; v += 8) {
    store_triples8(s.ox + (begin + v) * s.op, s.op, _mm256_load_ps(t.f[6] + v), _mm256_load_ps(t.f[7] + v),
                   _mm256_load_ps(t.f[8] + v));
    if (normals)
      store_triples8(s.onx + (begin + v) * s.on, s.on, _mm256_load_ps(t.f[9] + v), _mm256_load_ps(t.f[10] + v),
                     _mm256_load_ps(t.f[11] + v));
  }
  for (; v < count; ++v) stage_vertex_out(t, s, begin + v, v, normals);
}

// cga_motors on strided streams: the strided check and prefetch of matrix_strided_avx2_fn, pass 1 reading
// joints and weights in place and staging the block's positions (and normals) for pass 2, which vectorizes
// across vertices over packed arrays only. The same arithmetic as motor_block_avx2_fn, so the same bits.
template <bool kNormals, bool kPrefetch, bool kSigns>
CGA_AVX2 __attribute__((flatten)) bool motor_strided_avx2_fn(const float* pal, const Streams& streams,
                                                             std::size_t begin, std::size_t end, std::size_t palette) {
  const Streams s = streams;
  if (!block_ok_strided_avx2(s, begin, end, palette)) return false;
  alignas(64) MotorRows rows;
  Cursor<const std::array<std::uint16_t, 4>> j(s.joints, s.js, begin);
  Cursor<const std::array<float, 4>> w(s.weights, s.ws, begin);
  // Positions (and normals) are staged during pass 1, while their records are in L1 from its joint and
  // weight loads.
  Staged t;
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) {
    if constexpr (kPrefetch) prefetch_ahead_strided<kNormals>(s, i), prefetch_outputs_strided<kNormals>(s, i);
    motor_blend8_avx2<kSigns>(pal, palette, j, w, rows, i - begin);
    stage_triples8_in_avx2(s, i, i - begin, kNormals, t);
  }
  for (; i < end; ++i) motor_blend_one(pal, s, i, rows, i - begin), stage_vertex_in(s, i, i - begin, kNormals, t);
  const std::size_t count = end - begin;
  const Streams staged{t.f[0], t.f[1], t.f[2], t.f[3], t.f[4],  t.f[5],  nullptr,
                       nullptr, t.f[6], t.f[7], t.f[8], t.f[9], t.f[10], t.f[11]};
  motor_rows_apply<kNormals, false>(rows, staged, 0, count);
  if constexpr (kNormals) renormalize_avx2(staged, 0, count);
  stage_triples_out_avx2(t, s, begin, count, kNormals);
  return true;
}

}  // namespace

const SkinKernels* avx2_kernels() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  static const SkinKernels k{
      "avx2",
      {{matrix_block_avx2_fn<false, false>, matrix_block_avx2_fn<false, true>},
       {matrix_block_avx2_fn<true, false>, matrix_block_avx2_fn<true, true>}},
      {{motor_block_avx2_fn<false, false>, motor_block_avx2_fn<false, true>},
       {motor_block_avx2_fn<true, false>, motor_block_avx2_fn<true, true>}},
      {{motor_block_avx2_fn<false, false, true>, motor_block_avx2_fn<false, true, true>},
       {motor_block_avx2_fn<true, false, true>, motor_block_avx2_fn<true, true, true>}},
      pair_signs_avx2,
      {{matrix_strided_avx2_fn<false, false>, matrix_strided_avx2_fn<false, true>},
       {matrix_strided_avx2_fn<true, false>, matrix_strided_avx2_fn<true, true>}},
      {{{motor_strided_avx2_fn<false, false, false>, motor_strided_avx2_fn<false, false, true>},
        {motor_strided_avx2_fn<false, true, false>, motor_strided_avx2_fn<false, true, true>}},
       {{motor_strided_avx2_fn<true, false, false>, motor_strided_avx2_fn<true, false, true>},
        {motor_strided_avx2_fn<true, true, false>, motor_strided_avx2_fn<true, true, true>}}}};
  return has ? &k : nullptr;
}

}  // namespace cga::skinning_detail
#else
namespace cga::skinning_detail {
const SkinKernels* avx2_kernels() { return nullptr; }
}  // namespace cga::skinning_detail
#endif
