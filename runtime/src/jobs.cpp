// Sampling, blending, local-to-model and skinning-palette jobs (see jobs.hpp). Run() loops are flat over
// joints with the mode switch outside, and never allocate. The motor loops are the hot part of a pose: they
// live in the kernels below, each compiled twice (x86-64-v3 with AVX2/FMA, and the baseline ISA; the loader
// picks at startup) with the generated kernels flattened in, so GCC vectorizes them across joints where the
// data is structure of arrays (sampling, paper blending) and schedules them tightly where it is not.
//
// The 8-float vector helpers (detail/simd.hpp, and motor.hpp's templates on them) are inlined: the AVX
// argument ABI that -Wpsabi warns about never applies.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "cga/runtime/jobs.hpp"

#include "cga/runtime/rotor_sign.hpp"
#include "detail/simd.hpp"

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
// Every loop below says with `ivdep` that its streams do not overlap (distinct job buffers): without it GCC
// gives up on the aliasing of the float pointers.

constexpr std::size_t kR = ClipIntervals::kRigid, kM = ClipIntervals::kMotor;

// Blocks of kB joints as structure of arrays: block[c][lane] is coefficient c of joint j0 + lane. The motor
// math runs on blocks in loops over lanes that GCC vectorizes; the job buffers stay arrays of Motor (the
// API), converted with 4x4 transposes instead of 12 scattered stores per joint.
constexpr std::size_t kB = 8;
using Block = float[kM][kB];

#if defined(__GNUC__)
// The 8-float vectors and the 8x8 transpose of the shared SIMD header (detail/simd.hpp).
using simd::load8;
using simd::sqrt8;
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
    g[k] = __builtin_shufflevector(detail::load4(&m(k).c[8]), detail::load4(&m(k + 4).c[8]), 0, 1, 2, 3, 4, 5, 6, 7);
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
    detail::store4(&m[k].c[8], __builtin_shufflevector(h[k], h[k], 0, 1, 2, 3));
    detail::store4(&m[k + 4].c[8], __builtin_shufflevector(h[k], h[k], 4, 5, 6, 7));
  }
}

// motor_normalize_fast on 8 motors' coefficient rows, in place.
inline void normalize_rows(v8f m[kM]) {
  detail::motor_normalize_fast_t(m, m, [](v8f v) { return sqrt8(v); });
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

// The paper's lerp of every joint (generated motor_lerp_paper), reading one interval's SoA keys (stride w,
// a multiple of kB, so whole blocks are always readable).
CGA_JOBS_CLONES void sample_paper(std::size_t n, std::size_t w, float t, const float* __restrict t0,
                                  const float* __restrict inv, const float* __restrict r0,
                                  const float* __restrict r1, const float* __restrict s0,
                                  const float* __restrict s1, Motor* __restrict out) {
  for (std::size_t j0 = 0; j0 < n; j0 += kB) {
    Block res;
    for (std::size_t l = 0; l < kB; ++l) {
      const std::size_t j = j0 + l;
      const float a = (t - t0[j]) * inv[j];
      float x[kR], y[kR], m[kM];
      for (std::size_t c = 0; c < kR; ++c) x[c] = r0[c * w + j], y[c] = r1[c * w + j];
      kernels::motor_lerp_paper(x, y, s0[j], s1[j], a, m);
      for (std::size_t c = 0; c < kM; ++c) res[c][l] = m[c];
    }
    store_block(res, std::min(kB, n - j0), out + j0);
  }
}

// nlerp of every joint: key i plus alpha times the (sign-matched) difference, normalized; 8 joints per step
// as coefficient rows (the interval's SoA arrays are padded to whole blocks).
CGA_JOBS_CLONES void sample_nlerp(std::size_t n, std::size_t w, float t, const float* __restrict t0,
                                  const float* __restrict inv, const float* __restrict m0,
                                  const float* __restrict md, Motor* __restrict out) {
#if defined(__GNUC__)
  for (std::size_t j0 = 0; j0 < n; j0 += kB) {
    const v8f a = (t - load8(t0 + j0)) * load8(inv + j0);
    v8f m[kM];
    for (std::size_t c = 0; c < kM; ++c) m[c] = load8(m0 + c * w + j0) + a * load8(md + c * w + j0);
    normalize_rows(m);
    scatter_rows(m, std::min(kB, n - j0), out + j0);
  }
#else
  for (std::size_t j = 0; j < n; ++j) {
    const float a = (t - t0[j]) * inv[j];
    float m[kM];
    for (std::size_t c = 0; c < kM; ++c) m[c] = m0[c * w + j] + a * md[c * w + j];
    motor_normalize_fast(m, out[j].c.data());
  }
#endif
}

// nlerp's blend: the weighted sum with each motor's sign matched to the reference layer's, normalized; 8 joints
// per step as coefficient rows.
CGA_JOBS_CLONES void blend_nlerp(std::size_t n, std::span<const BlendLayer> layers, std::size_t first, float inv,
                                 Motor* __restrict out) {
#if defined(__GNUC__)
  using simd::v8i;
  const auto rows_of = [n](const Motor* m, std::size_t j0, v8f r[kM]) {
    if (j0 + kB <= n) return gather_rows([m, j0](int l) -> const Motor& { return m[j0 + l]; }, r);
    Block b;
    load_block(m + j0, n - j0, b);
    for (std::size_t c = 0; c < kM; ++c) r[c] = load8(b[c]);
  };
  for (std::size_t j0 = 0; j0 < n; j0 += kB) {
    v8f ref[kM], acc[kM], x[kM];
    rows_of(layers[first].motors.data(), j0, ref);
    const float w0 = layers[first].weight * inv;
    for (std::size_t c = 0; c < kM; ++c) acc[c] = w0 * ref[c];
    // The sign fix of rotor_sign.hpp on 8 joints: the reference's rotor part G = a + b.
    using rotor_sign::e_blade, rotor_sign::rotor_blade;
    v8f g[4];
    for (int i = 0; i < 4; ++i) g[i] = ref[rotor_blade(i)] + ref[e_blade(i)];
    for (std::size_t k = first + 1; k < layers.size(); ++k) {
      if (layers[k].weight <= 0.0f) continue;
      rows_of(layers[k].motors.data(), j0, x);
      const float w = layers[k].weight * inv;
      v8f dot = g[0] * (x[rotor_blade(0)] + x[e_blade(0)]);
      for (int i = 1; i < 4; ++i) dot += g[i] * (x[rotor_blade(i)] + x[e_blade(i)]);
      // rotor_sign::signed_weight: w with the dot's sign bit.
      const v8i flip = reinterpret_cast<v8i>(dot) & static_cast<int>(0x80000000u);
      const v8f s = reinterpret_cast<v8f>(reinterpret_cast<v8i>(v8f{} + w) ^ flip);
      for (std::size_t c = 0; c < kM; ++c) acc[c] += s * x[c];
    }
    normalize_rows(acc);
    scatter_rows(acc, std::min(kB, n - j0), out + j0);
  }
#else
  for (std::size_t j = 0; j < n; ++j) {
    const Motor& ref = layers[first].motors[j];
    Motor acc;
    for (std::size_t c = 0; c < kM; ++c) acc.c[c] = layers[first].weight * inv * ref.c[c];
    for (std::size_t k = first + 1; k < layers.size(); ++k) {
      if (layers[k].weight <= 0.0f) continue;
      const Motor& x = layers[k].motors[j];
      const float w = layers[k].weight * inv;
      const float s = rotor_sign::signed_weight(w, motor_rotor_dot(ref, x));
      for (std::size_t c = 0; c < kM; ++c) acc.c[c] += s * x.c[c];
    }
    motor_normalize_fast(acc.c.data(), out[j].c.data());
  }
#endif
}

// out = sum of w_l * in_l over the flat coefficient arrays (the paper's weighted sum).
CGA_JOBS_CLONES void scale_into(std::size_t count, float w, const float* __restrict in, float* __restrict out) {
#pragma GCC ivdep
  for (std::size_t x = 0; x < count; ++x) out[x] = w * in[x];
}
CGA_JOBS_CLONES void add_scaled(std::size_t count, float w, const float* __restrict in, float* __restrict out) {
#pragma GCC ivdep
  for (std::size_t x = 0; x < count; ++x) out[x] += w * in[x];
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
bool all_rigid(std::span<const Motor> m, std::size_t n) { return all_rigid(m.data(), n); }

// model[j] = model[parent] * local[j], parents first; rigid: every motor has b = 0 (8-blade product).
CGA_JOBS_CLONES void local_to_model_rigid(std::size_t n, const int* __restrict parents,
                                          const Motor* __restrict local, Motor* __restrict model) {
  for (std::size_t j = 0; j < n; ++j) {
    if (parents[j] < 0)
      model[j] = local[j];
    else
      motor_mul_rigid_simd(model[parents[j]], local[j], model[j]);
  }
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

// The hierarchy with dilations: the model motors are kept in split form in `model` while the parents are
// read (parents[j] < j), and turned back into blades at the end, so each model motor is rounded into the
// blade form once.
CGA_JOBS_CLONES void local_to_model_general(std::size_t n, const int* __restrict parents,
                                            const Motor* __restrict local, Motor* __restrict model) {
  for (std::size_t j = 0; j < n; ++j) {
    float l[12];
    to_split(local[j], l);
    if (parents[j] < 0)
      std::copy(l, l + 12, model[j].c.data());
    else
      split_mul(model[parents[j]].c.data(), l, model[j].c.data());
  }
  for (std::size_t j = 0; j < n; ++j) {
    const Motor s = model[j];
    from_split(s.c.data(), model[j]);
  }
}

// palette[k] = model[remap[k]] * inverse_bind[k], by the 8-blade product where both factors are rigid.
// The rigidity of every entry is checked first (OR of the b groups' bits), so that an all-rigid palette runs a
// loop of nothing but rigid products: with the test and the 12-blade product in the same loop body, GCC
// hoists parts of the 12-blade product above the branch and the loop costs twice as much.
__attribute__((noinline)) void palette_general(const Motor& m, const Motor& ib, Motor& out) {
  float x[12], y[12], z[12];
  to_split(m, x), to_split(ib, y);
  split_mul(x, y, z);
  from_split(z, out);
}
// The check reads every model motor (contiguous, vectorized), not only the remapped ones: a dilated joint
// that no entry uses sends the palette to the per-entry loop, which is slower but equal.
CGA_JOBS_CLONES void palette(std::size_t n, const int* __restrict remap, const Motor* __restrict model,
                             std::size_t joints, const Motor* __restrict ib, Motor* __restrict out) {
  if (all_rigid(model, joints) && all_rigid(ib, n)) {
    std::size_t k = 0;
#if defined(__GNUC__)
    // Blocks of 8 entries as structure of arrays: the generated 8-blade product vectorized across entries.
    constexpr int kRigidBlade[kR] = {0, 1, 2, 3, 4, 5, 6, 8};
    for (; k + kB <= n; k += kB) {
      v8f x[kM], y[kM];
      gather_rows([&](int l) -> const Motor& { return model[remap[k + l]]; }, x);
      gather_rows([&](int l) -> const Motor& { return ib[k + l]; }, y);
      float xs[kR][kB], ys[kR][kB], zs[kR][kB];
      for (std::size_t c = 0; c < kR; ++c) store8(xs[c], x[kRigidBlade[c]]), store8(ys[c], y[kRigidBlade[c]]);
      for (std::size_t l = 0; l < kB; ++l) {
        float a[kR], b[kR], z[kR];
        for (std::size_t c = 0; c < kR; ++c) a[c] = xs[c][l], b[c] = ys[c][l];
        kernels::motor_mul_rigid(a, b, z);
        for (std::size_t c = 0; c < kR; ++c) zs[c][l] = z[c];
      }
      v8f z[kM];
      z[7] = z[9] = z[10] = z[11] = v8f{};
      for (std::size_t c = 0; c < kR; ++c) z[kRigidBlade[c]] = load8(zs[c]);
      scatter_rows(z, out + k);
    }
#endif
    for (; k < n; ++k) motor_mul_rigid_simd(model[remap[k]], ib[k], out[k]);
    return;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Motor& m = model[remap[k]];
    if (motor_is_rigid(m) && motor_is_rigid(ib[k]))
      motor_mul_rigid_simd(m, ib[k], out[k]);
    else
      palette_general(m, ib[k], out[k]);
  }
}

// ------------------------------------------------------------------------------------------------ checks

static_assert(sizeof(Motor) == 12 * sizeof(float), "the jobs treat Motor arrays as flat float arrays");

template <class Span>
bool fits(const Span& s, std::size_t n) {
  return s.size() >= n;
}

constexpr float kRigidScaleTolerance = 8.0f * 1.1920929e-7f;  // 8 float ulps at 1

// The mode switches of Run() take any mode they do not name for screw, so Validate() admits only the enum's
// values (an Interpolation cast from an integer may hold another).
constexpr bool known_mode(Interpolation m) {
  return m == Interpolation::paper || m == Interpolation::nlerp || m == Interpolation::screw;
}

}  // namespace

// ---------------------------------------------------------------------------------------------- sampling

bool SamplingJob::Validate() const {
  if (!clip || !known_mode(mode)) return false;
  const std::size_t n = clip->keys.size();
  if (!fits(output, n)) return false;
  if (!std::isfinite(time)) return false;
  if (n == 0) return true;
  // The sampler reads clip->intervals, built by build_joint_keys; a clip whose keys were never built (or
  // a joint without keys) has none that match.
  const ClipIntervals& iv = clip->intervals;
  if (iv.joints != n || iv.times.empty()) return false;
  return iv.has_motors();
}

bool SamplingJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = clip->keys.size();
  if (n == 0) return true;
  const ClipIntervals& iv = clip->intervals;
  const std::size_t w = iv.stride;
  // Before the first key of every joint the first key holds, which interval 0 gives for t = times[0].
  const float t = std::max(std::clamp(time, 0.0f, clip->duration), iv.times.front());
  const std::size_t u = iv.find(t);
  const float* t0 = iv.t0.data() + u * w;
  const float* inv = iv.inv_span.data() + u * w;
  const std::uint32_t* key = iv.key.data() + u * w;
  switch (mode) {
    case Interpolation::paper:
      sample_paper(n, w, t, t0, inv, iv.rigid0.data() + u * kR * w, iv.rigid1.data() + u * kR * w,
                   iv.scale0.data() + u * w, iv.scale1.data() + u * w, output.data());
      break;
    case Interpolation::nlerp:
      sample_nlerp(n, w, t, t0, inv, iv.motor0.data() + u * kM * w, iv.motor_delta.data() + u * kM * w,
                   output.data());
      break;
    default:  // screw (Validate admits the motor modes only)
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        const std::size_t i = key[j];
        const float a = (t - t0[j]) * inv[j];
        output[j] = a == 0.0f ? k.motors[i] : motor_screw(k.motors[i], k.motors[i + 1], a);
      }
      break;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------- blending

namespace {

bool has_joint_weights(std::span<const BlendLayer> layers) {
  for (const BlendLayer& l : layers)
    if (l.weight > 0.0f && !l.joint_weights.empty()) return true;
  return false;
}

// The weight layer l gives joint j (0 for a layer left out).
inline float joint_weight(const BlendLayer& l, std::size_t j) {
  if (!(l.weight > 0.0f)) return 0.0f;
  return l.joint_weights.empty() ? l.weight : l.weight * l.joint_weights[j];
}

// Partial blending: every joint normalized by its own weight sum (the per-joint form of the loops above; not
// vectorized across joints, since the weights differ per joint).
void blend_per_joint(Interpolation mode, std::span<const BlendLayer> layers, std::span<const Motor> rest,
                     std::span<Motor> output) {
  for (std::size_t j = 0; j < output.size(); ++j) {
    float total = 0.0f;
    std::size_t first = layers.size();
    for (std::size_t k = 0; k < layers.size(); ++k) {
      const float w = joint_weight(layers[k], j);
      if (w > 0.0f && first == layers.size()) first = k;
      total += w;
    }
    if (!(total > 0.0f)) {
      output[j] = rest[j];
      continue;
    }
    const Motor& ref = layers[first].motors[j];
    Motor acc;
    if (mode == Interpolation::screw) {
      acc = ref;
      float sum = joint_weight(layers[first], j);
      for (std::size_t k = first + 1; k < layers.size(); ++k) {
        const float w = joint_weight(layers[k], j);
        if (!(w > 0.0f)) continue;
        sum += w;
        acc = motor_screw(acc, layers[k].motors[j], w / sum);
      }
      output[j] = motor_normalize_fast(acc);
      continue;
    }
    const float inv = 1.0f / total;
    for (std::size_t c = 0; c < kM; ++c) acc.c[c] = 0.0f;
    for (std::size_t k = first; k < layers.size(); ++k) {
      float w = joint_weight(layers[k], j) * inv;
      if (!(w > 0.0f)) continue;
      const Motor& x = layers[k].motors[j];
      if (mode == Interpolation::nlerp) w = rotor_sign::signed_weight(w, motor_rotor_dot(ref, x));
      for (std::size_t c = 0; c < kM; ++c) acc.c[c] += w * x.c[c];
    }
    output[j] = mode == Interpolation::nlerp ? motor_normalize_fast(acc) : acc;
  }
}

}  // namespace

bool BlendingJob::Validate() const {
  if (layers.empty() || !known_mode(mode)) return false;
  const std::size_t n = output.size();
  if (!rest_pose.empty() && rest_pose.size() < n) return false;
  float total = 0.0f;
  for (const BlendLayer& l : layers) {
    if (!std::isfinite(l.weight)) return false;
    if (l.weight <= 0.0f) continue;
    total += l.weight;
    if (l.motors.size() < n) return false;
    if (!l.joint_weights.empty()) {
      if (l.joint_weights.size() < n) return false;
      for (std::size_t j = 0; j < n; ++j)
        if (!(l.joint_weights[j] >= 0.0f) || !std::isfinite(l.joint_weights[j])) return false;
    }
  }
  if (!(total > 0.0f)) return false;
  // With per-joint weights a joint may get none: then it needs the rest pose.
  if (rest_pose.empty() && has_joint_weights(layers))
    for (std::size_t j = 0; j < n; ++j) {
      float sum = 0.0f;
      for (const BlendLayer& l : layers) sum += joint_weight(l, j);
      if (!(sum > 0.0f)) return false;
    }
  return true;
}

bool BlendingJob::Run() const {
  if (!Validate()) return false;
  float total = 0.0f;
  for (const BlendLayer& l : layers) total += std::max(l.weight, 0.0f);
  const float inv = 1.0f / total;
  // The first contributing layer is the reference for sign fixes and the start of the screw fold.
  std::size_t first = 0;
  while (layers[first].weight <= 0.0f) ++first;
  const std::size_t n = output.size();
  if (has_joint_weights(layers)) {
    blend_per_joint(mode, layers, rest_pose, output);
    return true;
  }

  switch (mode) {
    case Interpolation::paper: {
      float* out = output.data()->c.data();
      scale_into(n * kM, layers[first].weight * inv, layers[first].motors.data()->c.data(), out);
      for (std::size_t l = first + 1; l < layers.size(); ++l)
        if (layers[l].weight > 0.0f) add_scaled(n * kM, layers[l].weight * inv, layers[l].motors.data()->c.data(), out);
      break;
    }
    case Interpolation::nlerp: blend_nlerp(n, layers, first, inv, output.data()); break;
    default:  // screw
      for (std::size_t j = 0; j < n; ++j) {
        Motor acc = layers[first].motors[j];
        float sum = layers[first].weight;
        for (std::size_t k = first + 1; k < layers.size(); ++k) {
          if (layers[k].weight <= 0.0f) continue;
          sum += layers[k].weight;
          acc = motor_screw(acc, layers[k].motors[j], layers[k].weight / sum);
        }
        output[j] = motor_normalize_fast(acc);
      }
      break;
  }
  return true;
}

// ----------------------------------------------------------------------------------------- local to model

bool LocalToModelJob::Validate() const {
  if (!skeleton) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  for (std::size_t j = 0; j < n; ++j)
    if (skeleton->parents[j] >= static_cast<int>(j)) return false;
  return fits(input, n) && fits(output, n);
}

bool LocalToModelJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  const int* parents = skeleton->parents.data();
  // Roots copy their local motor, so rigid locals make every model motor rigid.
  if (all_rigid(input, n))
    local_to_model_rigid(n, parents, input.data(), output.data());
  else
    local_to_model_general(n, parents, input.data(), output.data());
  return true;
}

// --------------------------------------------------------------------------------------- skinning palette

std::vector<Motor> make_inverse_bind_motors(const SkinnedMesh& mesh) {
  const std::size_t n = mesh.joint_remap.size();
  std::vector<Motor> motors(n);
  for (std::size_t k = 0; k < n && k < mesh.inverse_bind.size(); ++k) {
    // A scale within float rounding of 1 (what decomposing a rigid offset matrix leaves) is taken as 1,
    // so that rigid characters get exactly rigid inverse binds and the palette its 8-blade product.
    Transform x = mesh.inverse_bind[k];
    if (std::abs(x.scale - 1.0f) <= kRigidScaleTolerance) x.scale = 1.0f;
    motors[k] = motor_from_transform(x);
  }
  return motors;
}

bool SkinningPaletteJob::Validate() const {
  const std::size_t n = joint_remap.size();
  if (!fits(output, n) || !fits(inverse_bind, n)) return false;
  for (int j : joint_remap)
    if (j < 0 || static_cast<std::size_t>(j) >= model.size()) return false;
  return true;
}

bool SkinningPaletteJob::Run() const {
  if (!Validate()) return false;
  palette(joint_remap.size(), joint_remap.data(), model.data(), model.size(), inverse_bind.data(), output.data());
  return true;
}

}  // namespace cga
