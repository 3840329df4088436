// SkinningJob: validation and the four CPU skinning loops (lbs, dqs, cga_points, cga_motors).
//
// Layout of the hot loops: vertices are processed in blocks of kBlock; a block's joints and weights are
// checked first (they are then in L1 for the skinning pass), and the per-vertex body is flat straight-line
// code on local arrays, written so GCC vectorizes it across vertices. The loops are built twice
// (target_clones): x86-64-v3 (AVX2 + FMA, what the speed targets assume) and the portable default.
#include "cga/runtime/skinning.hpp"

#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

#if defined(__x86_64__)
// GCC 12's AVX-512 intrinsics pass _mm512_undefined_ps() as the unused merge source of their masked builtins,
// which -Wmaybe-uninitialized reports once they are inlined (GCC bug 105593); the value is never read.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <immintrin.h>
#endif

#include <fmt/format.h>

#include "cga/runtime/skinning_palettes.hpp"

// runtime/CMakeLists.txt compiles this file with -O3 -fno-math-errno -fno-trapping-math: at the project's
// -O2, GCC 12's "very cheap" vectorizer cost model refuses gathers, and sqrt's errno and trapping compares
// keep the normal loops scalar (neither flag changes a result; nothing here reads errno or FP exceptions).
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_SKIN_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define CGA_SKIN_CLONES
#endif
#define CGA_ALWAYS_INLINE inline __attribute__((always_inline))

namespace cga {

static_assert(sizeof(glm::mat3x4) == 12 * sizeof(float), "matrix palette entries are read as 12 floats");
static_assert(sizeof(Motor) == 12 * sizeof(float), "motor palette entries are read as 12 floats");

std::string_view to_string(SkinningMethod method) {
  switch (method) {
    case SkinningMethod::lbs: return "lbs";
    case SkinningMethod::dqs: return "dqs";
    case SkinningMethod::cga_points: return "cga-points";
    case SkinningMethod::cga_motors: return "cga-motors";
  }
  throw std::invalid_argument(fmt::format("to_string: unknown SkinningMethod {}", static_cast<int>(method)));
}

SkinningMethod parse_skinning_method(std::string_view text) {
  std::string canonical(text);
  for (char& c : canonical)
    if (c == '_') c = '-';
  for (SkinningMethod m : kAllSkinningMethods)
    if (to_string(m) == canonical) return m;
  throw std::invalid_argument(
      fmt::format("unknown skinning method '{}' (choose lbs, dqs, cga-points or cga-motors)", text));
}

void SkinnedOutput::resize_for(const SkinnedMesh& mesh) {
  const std::size_t n = mesh.vertex_count();
  px.assign(n, 0.0f);
  py.assign(n, 0.0f);
  pz.assign(n, 0.0f);
  const std::size_t nn = mesh.has_normals() ? n : 0;
  nx.assign(nn, 0.0f);
  ny.assign(nn, 0.0f);
  nz.assign(nn, 0.0f);
}

SkinningJob make_skinning_job(SkinningMethod method, const SkinnedMesh& mesh, SkinnedOutput& out) {
  out.resize_for(mesh);
  SkinningJob job;
  job.method = method;
  job.in_px = mesh.px;
  job.in_py = mesh.py;
  job.in_pz = mesh.pz;
  job.in_nx = mesh.nx;
  job.in_ny = mesh.ny;
  job.in_nz = mesh.nz;
  job.joints = mesh.joints;
  job.weights = mesh.weights;
  job.out_px = out.px;
  job.out_py = out.py;
  job.out_pz = out.pz;
  job.out_nx = out.nx;
  job.out_ny = out.ny;
  job.out_nz = out.nz;
  return job;
}

namespace {

constexpr std::size_t kBlock = 256;
// From this many vertices on, a mesh is "large": prefetching and non-temporal stores (see Run).
constexpr std::size_t kLargeVertices = std::size_t{1} << 17;

std::size_t palette_size(const SkinningJob& job) {
  switch (job.method) {
    case SkinningMethod::lbs: return job.matrices.size();
    case SkinningMethod::dqs: return job.dual_quats.size();
    case SkinningMethod::cga_points:
    case SkinningMethod::cga_motors: return job.motors.size();
  }
  return 0;
}

// The O(1) checks: sizes, normals, palette limits.
std::string shape_error(const SkinningJob& job) {
  const std::size_t n = job.in_px.size();
  if (job.in_py.size() != n || job.in_pz.size() != n)
    return fmt::format("input positions differ in size (x {}, y {}, z {})", n, job.in_py.size(), job.in_pz.size());
  if (job.out_px.size() != n || job.out_py.size() != n || job.out_pz.size() != n)
    return fmt::format("output positions must hold {} vertices (x {}, y {}, z {})", n, job.out_px.size(),
                       job.out_py.size(), job.out_pz.size());
  if (job.joints.size() != n) return fmt::format("{} joint quadruples for {} vertices", job.joints.size(), n);
  if (job.weights.size() != n) return fmt::format("{} weight quadruples for {} vertices", job.weights.size(), n);
  const bool any_in_normals = !job.in_nx.empty() || !job.in_ny.empty() || !job.in_nz.empty();
  const bool any_out_normals = !job.out_nx.empty() || !job.out_ny.empty() || !job.out_nz.empty();
  if (any_in_normals) {
    if (job.in_nx.size() != n || job.in_ny.size() != n || job.in_nz.size() != n)
      return fmt::format("input normals must be empty or hold {} vertices (x {}, y {}, z {})", n,
                         job.in_nx.size(), job.in_ny.size(), job.in_nz.size());
    if (job.out_nx.size() != n || job.out_ny.size() != n || job.out_nz.size() != n)
      return fmt::format("output normals must hold {} vertices (x {}, y {}, z {})", n, job.out_nx.size(),
                         job.out_ny.size(), job.out_nz.size());
  } else if (any_out_normals) {
    return "output normals given without input normals";
  }
  const std::size_t palette = palette_size(job);
  if (palette > kMaxConvertedPalette)
    return fmt::format("{} converts at most {} palette entries per run, the palette has {}",
                       to_string(job.method), kMaxConvertedPalette, palette);
  return {};
}

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

std::string data_error(const SkinningJob& job) {
  const std::size_t palette = palette_size(job);
  for (std::size_t i = 0; i < job.vertex_count(); ++i)
    for (int k = 0; k < 4; ++k) {
      if (job.joints[i][k] >= palette)
        return fmt::format("vertex {} influence {}: joint {} is outside the {} palette of {} entries", i, k,
                           job.joints[i][k], to_string(job.method), palette);
      if (!std::isfinite(job.weights[i][k]))
        return fmt::format("vertex {} influence {}: weight {} is not finite", i, k, job.weights[i][k]);
      if (job.weights[i][k] < 0.0f)
        return fmt::format("vertex {} influence {}: weight {} is negative", i, k, job.weights[i][k]);
    }
  // lbs and cga-points scale a vertex by its weight sum: an unnormalized vertex would be silently misplaced.
  for (std::size_t i = 0; i < job.vertex_count(); ++i) {
    const auto& w = job.weights[i];
    const float sum = w[0] + w[1] + w[2] + w[3];
    if (!(std::abs(sum - 1.0f) <= kWeightSumTolerance))
      return fmt::format("vertex {}: weights sum to {}, not 1 (renormalize them)", i, sum);
  }
  return {};
}

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
};

// Applies a row-major 3x4 matrix to the point i (and the linear part to its normal, renormalized).
template <bool kNormals>
CGA_ALWAYS_INLINE void apply_matrix(const float m[12], const Streams& s, std::size_t i) {
  const float x = s.px[i], y = s.py[i], z = s.pz[i];
  s.ox[i] = m[0] * x + m[1] * y + m[2] * z + m[3];
  s.oy[i] = m[4] * x + m[5] * y + m[6] * z + m[7];
  s.oz[i] = m[8] * x + m[9] * y + m[10] * z + m[11];
  if constexpr (kNormals) {
    const float a = s.nx[i], b = s.ny[i], c = s.nz[i];
    const float u = m[0] * a + m[1] * b + m[2] * c;
    const float v = m[4] * a + m[5] * b + m[6] * c;
    const float w = m[8] * a + m[9] * b + m[10] * c;
    const float len2 = u * u + v * v + w * w;
    // A degenerate blend (zero linear part) gives a zero normal rather than NaN.
    // Written without a conditional division so the loop if-converts and vectorizes.
    const float inv = (len2 > 0.0f ? 1.0f : 0.0f) / std::sqrt(std::max(len2, 1e-30f));
    s.onx[i] = u * inv;
    s.ony[i] = v * inv;
    s.onz[i] = w * inv;
  }
}

// The 8-float vector helpers below are always inlined and file-local, so the AVX argument-passing ABI
// that -Wpsabi warns about never applies.
#pragma GCC diagnostic ignored "-Wpsabi"

// Palettes in the loops' layout: 16 floats per entry, read as two 8-float vectors. GCC's vector extensions
// keep this portable: the default clone splits each 8-float operation into two SSE ones.
using v4 = float __attribute__((vector_size(16)));
using v8 = float __attribute__((vector_size(32)));
constexpr std::size_t kEntry = 16;

CGA_ALWAYS_INLINE v8 load8(const float* p) {
  v8 v;
  __builtin_memcpy(&v, p, sizeof v);
  return v;
}
CGA_ALWAYS_INLINE v4 low(v8 v) { return v4{v[0], v[1], v[2], v[3]}; }
CGA_ALWAYS_INLINE v4 high(v8 v) { return v4{v[4], v[5], v[6], v[7]}; }

// A matrix entry is column-major with padded columns: (m00 m10 m20 0)(m01 m11 m21 0)(m02 m12 m22 0)(t 0).
void matrix_entry_from_rows(const float rows[12], float out[kEntry]) {
  for (int c = 0; c < 4; ++c) {
    for (int r = 0; r < 3; ++r) out[4 * c + r] = rows[4 * r + c];
    out[4 * c + 3] = 0.0f;
  }
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

CGA_SKIN_CLONES bool matrix_block_p(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  matrix_block<false>(pal, s, begin, end);
  return true;
}
CGA_SKIN_CLONES bool matrix_block_pn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  matrix_block<true>(pal, s, begin, end);
  return true;
}

// dqs: blend 8 dual-quaternion coefficients with the antipodality fix, then transform by the normalized
// blend. Written on the unnormalized blend b = (r, d) with n = |r|^2:
//   p' = ((r_w^2 - r_v.r_v) p + 2 (r_v.p) r_v + 2 r_w (r_v x p)) / n + 2 (r_w d_v - d_w r_v + r_v x d_v) / n
template <bool kNormals>
CGA_ALWAYS_INLINE void dq_block(const float* __restrict pal, const Streams& s, std::size_t begin,
                                std::size_t end) {
#pragma GCC ivdep
  for (std::size_t i = begin; i < end; ++i) {
    const std::size_t j[4] = {s.joints[i][0], s.joints[i][1], s.joints[i][2], s.joints[i][3]};
    // Weights read one by one: GCC does not vectorize the copy of the whole std::array here.
    const float w[4] = {s.weights[i][0], s.weights[i][1], s.weights[i][2], s.weights[i][3]};
    const float* q[4] = {pal + 8 * j[0], pal + 8 * j[1], pal + 8 * j[2], pal + 8 * j[3]};
    float b[8];
    for (int e = 0; e < 8; ++e) b[e] = w[0] * q[0][e];
    for (int k = 1; k < 4; ++k) {
      const float dot = q[0][0] * q[k][0] + q[0][1] * q[k][1] + q[0][2] * q[k][2] + q[0][3] * q[k][3];
      const float wk = std::copysign(w[k], dot);
      for (int e = 0; e < 8; ++e) b[e] += wk * q[k][e];
    }
    // Packed as (r_x, r_y, r_z, r_w, d_x, d_y, d_z, d_w), see pack_dual_quats.
    const float rx = b[0], ry = b[1], rz = b[2], rw = b[3];
    const float dx = b[4], dy = b[5], dz = b[6], dw = b[7];
    const float inv = 1.0f / (rx * rx + ry * ry + rz * rz + rw * rw);
    const float diag = rw * rw - (rx * rx + ry * ry + rz * rz);
    const float tx = 2.0f * (rw * dx - dw * rx + (ry * dz - rz * dy));
    const float ty = 2.0f * (rw * dy - dw * ry + (rz * dx - rx * dz));
    const float tz = 2.0f * (rw * dz - dw * rz + (rx * dy - ry * dx));
    // Rotation as a matrix (columns are the rotated axes), scaled by n; shared by point and normal.
    const float m[12] = {
        (diag + 2 * rx * rx) * inv, 2 * (rx * ry - rw * rz) * inv, 2 * (rx * rz + rw * ry) * inv, tx * inv,
        2 * (ry * rx + rw * rz) * inv, (diag + 2 * ry * ry) * inv, 2 * (ry * rz - rw * rx) * inv, ty * inv,
        2 * (rz * rx - rw * ry) * inv, 2 * (rz * ry + rw * rx) * inv, (diag + 2 * rz * rz) * inv, tz * inv};
    apply_matrix<kNormals>(m, s, i);
  }
}

CGA_SKIN_CLONES bool dq_block_p(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  dq_block<false>(pal, s, begin, end);
  return true;
}
CGA_SKIN_CLONES bool dq_block_pn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  dq_block<true>(pal, s, begin, end);
  return true;
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

// Pass 2 over the vertices [begin, end) whose blended motors are in rows[.][i - begin].
template <bool kNormals>
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
  if constexpr (kNormals) renormalize(s, begin, end);
}

// Pass 1 for one vertex, portable: the blended motor's coefficients into rows[.][b].
CGA_ALWAYS_INLINE void motor_blend_one(const float* __restrict pal, const Streams& s, std::size_t i,
                                       MotorRows& rows, std::size_t b) {
  const std::array<std::uint16_t, 4> j = s.joints[i];
  const std::array<float, 4> w = s.weights[i];
  const float* q0 = pal + kEntry * j[0];
  v8 lo = w[0] * load8(q0);
  v8 hi = w[0] * load8(q0 + 8);
  for (int k = 1; k < 4; ++k) {
    const float* q = pal + kEntry * j[k];
    const float dot = q0[0] * q[0] + q0[1] * q[1] + q0[2] * q[2] + q0[3] * q[3];
    const float wk = __builtin_copysignf(w[k], dot);
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

// flatten: GCC does not inline the generated kernel on its own, and the call would keep pass 2 scalar.
CGA_SKIN_CLONES __attribute__((flatten)) bool motor_block_p(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block<false>(pal, s, begin, end);
  return true;
}
CGA_SKIN_CLONES __attribute__((flatten)) bool motor_block_pn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block<true>(pal, s, begin, end);
  return true;
}

// ---- Hand-written AVX2 + FMA paths (x86-64 only, chosen at run time when the CPU has both) ----
//
// The portable loops above keep one vertex per iteration and write three scalars per output stream; the
// paths below blend within the vertex as before but gather 8 vertices' results in registers, transpose them
// and store whole 8-float rows, so the stores, the point transform and the normal renormalization run across
// vertices. Results agree with the portable loops to float rounding (other summation order, FMA).
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_SKIN_HAVE_AVX2 1
#define CGA_AVX2 __attribute__((target("avx2,fma")))

// Blended 3x4 matrix of vertex i as (c0 | c1), (c2 | t), from the matrix palette layout.
CGA_AVX2 CGA_ALWAYS_INLINE void blend_matrix_avx2(const float* __restrict pal, const Streams& s, std::size_t i,
                                                  __m256& lo, __m256& hi) {
  const std::array<std::uint16_t, 4> j = s.joints[i];
  const float* w = s.weights[i].data();
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

// Stores 8 floats at p; kStream: as non-temporal stores (two 16-byte ones: p is only 16-byte aligned).
template <bool kStream>
CGA_AVX2 CGA_ALWAYS_INLINE void store8(float* __restrict p, __m256 v) {
  if constexpr (kStream) {
    _mm_stream_ps(p, _mm256_castps256_ps128(v));
    _mm_stream_ps(p + 4, _mm256_extractf128_ps(v, 1));
  } else {
    _mm256_storeu_ps(p, v);
  }
}

// The portable renormalization on 8 lanes: n / |n|, or 0 when |n| = 0.
template <bool kStream>
CGA_AVX2 CGA_ALWAYS_INLINE void store_unit8(__m256 x, __m256 y, __m256 z, float* __restrict ox,
                                            float* __restrict oy, float* __restrict oz) {
  const __m256 len2 = _mm256_fmadd_ps(z, z, _mm256_fmadd_ps(y, y, _mm256_mul_ps(x, x)));
  const __m256 one_if_nonzero = _mm256_and_ps(_mm256_cmp_ps(len2, _mm256_setzero_ps(), _CMP_GT_OQ), _mm256_set1_ps(1.0f));
  const __m256 inv = _mm256_div_ps(one_if_nonzero, _mm256_sqrt_ps(_mm256_max_ps(len2, _mm256_set1_ps(1e-30f))));
  store8<kStream>(ox, _mm256_mul_ps(x, inv));
  store8<kStream>(oy, _mm256_mul_ps(y, inv));
  store8<kStream>(oz, _mm256_mul_ps(z, inv));
}

template <bool kNormals, bool kStream>
CGA_AVX2 CGA_ALWAYS_INLINE void matrix_block_avx2(const float* __restrict pal, const Streams& streams,
                                                  std::size_t begin, std::size_t end) {
  const Streams s = streams;  // a local copy: GCC reloads the pointers after every store otherwise
  const __m256 one = _mm256_set1_ps(1.0f), zero = _mm256_setzero_ps();
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) {
    if constexpr (kStream) prefetch_ahead<kNormals>(s, i);
    // Vertices k and k + 4 together, so only the 4 (or 8) pair registers live across the group; unrolled,
    // so they stay in registers.
    __m256 p[4], n[4];
#pragma GCC unroll 4
    for (int k = 0; k < 4; ++k) {
      __m256 lo, hi, lo4, hi4;
      const std::size_t a = i + k, b = i + k + 4;
      blend_matrix_avx2(pal, s, a, lo, hi);
      blend_matrix_avx2(pal, s, b, lo4, hi4);
      p[k] = pair_halves(apply_halves(lo, hi, s.px + a, s.py + a, s.pz + a, one),
                         apply_halves(lo4, hi4, s.px + b, s.py + b, s.pz + b, one));
      if constexpr (kNormals)
        n[k] = pair_halves(apply_halves(lo, hi, s.nx + a, s.ny + a, s.nz + a, zero),
                           apply_halves(lo4, hi4, s.nx + b, s.ny + b, s.nz + b, zero));
    }
    __m256 x, y, z;
    transpose_pairs(p, x, y, z);
    store8<kStream>(s.ox + i, x);
    store8<kStream>(s.oy + i, y);
    store8<kStream>(s.oz + i, z);
    if constexpr (kNormals) {
      transpose_pairs(n, x, y, z);
      store_unit8<kStream>(x, y, z, s.onx + i, s.ony + i, s.onz + i);
    }
  }
  if (i < end) matrix_block<kNormals>(pal, s, i, end);
}

template <bool kNormals, bool kStream>
CGA_AVX2 bool matrix_block_avx2_fn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
                                   std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  matrix_block_avx2<kNormals, kStream>(pal, s, begin, end);
  return true;
}

// cga_motors pass 1 for 8 vertices: blend within each vertex (sign fix from the rotor lanes 0-3 of the
// entries), then transpose the 8 blended motors into rows[.][b .. b + 8).
CGA_AVX2 CGA_ALWAYS_INLINE void motor_blend8_avx2(const float* __restrict pal, const Streams& s, std::size_t i,
                                                  MotorRows& rows, std::size_t b) {
  const __m128 sign_mask = _mm_set1_ps(-0.0f);
  __m256 lo[8], hi[8];
#pragma GCC unroll 8
  for (int v = 0; v < 8; ++v) {
    const std::array<std::uint16_t, 4> j = s.joints[i + v];
    const float* q0 = pal + kEntry * j[0];
    const float* q1 = pal + kEntry * j[1];
    const float* q2 = pal + kEntry * j[2];
    const float* q3 = pal + kEntry * j[3];
    const __m256 l0 = _mm256_loadu_ps(q0), l1 = _mm256_loadu_ps(q1), l2 = _mm256_loadu_ps(q2), l3 = _mm256_loadu_ps(q3);
    // Rotor-part dot products <q0, qk> as (0, d1, d2, d3), then the weights with those signs (copysign).
    const __m128 r0 = _mm256_castps256_ps128(l0);
    const __m128 p1 = _mm_mul_ps(r0, _mm256_castps256_ps128(l1));
    const __m128 p2 = _mm_mul_ps(r0, _mm256_castps256_ps128(l2));
    const __m128 p3 = _mm_mul_ps(r0, _mm256_castps256_ps128(l3));
    const __m128 dots = _mm_hadd_ps(_mm_hadd_ps(_mm_setzero_ps(), p1), _mm_hadd_ps(p2, p3));
    const __m128 w = _mm_loadu_ps(s.weights[i + v].data());
    const __m128 sw = _mm_or_ps(_mm_andnot_ps(sign_mask, w), _mm_and_ps(sign_mask, dots));
    const __m256 sw2 = _mm256_castps128_ps256(sw);
    const __m256 w0 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(0));
    const __m256 w1 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(1));
    const __m256 w2 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(2));
    const __m256 w3 = _mm256_permutevar8x32_ps(sw2, _mm256_set1_epi32(3));
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

bool cpu_has_avx512() {
  static const bool has = __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
                          __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512bw");
  return has;
}

template <bool kNormals>
CGA_AVX2 CGA_ALWAYS_INLINE void motor_block_avx2(const float* __restrict pal, const Streams& s, std::size_t begin,
                                                 std::size_t end) {
  alignas(64) MotorRows rows;
  std::size_t i = begin;
  for (; i + 8 <= end; i += 8) motor_blend8_avx2(pal, s, i, rows, i - begin);
  for (; i < end; ++i) motor_blend_one(pal, s, i, rows, i - begin);
  motor_rows_apply<kNormals>(rows, s, begin, end);
}

template <bool kNormals>
CGA_AVX2 __attribute__((flatten)) bool motor_block_avx2_fn(const float* pal, const Streams& s, std::size_t begin,
                                                           std::size_t end, std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block_avx2<kNormals>(pal, s, begin, end);
  return true;
}

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

// The weight w with the sign of `dot` (copysign), broadcast.
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

using SimdBlockFn = bool (*)(const float*, const Streams&, std::size_t, std::size_t, std::size_t);
// stream: a large mesh with aligned outputs (prefetching, non-temporal stores).
SimdBlockFn matrix_block_avx2_for(bool normals, bool stream) {
  if (normals) return stream ? matrix_block_avx2_fn<true, true> : matrix_block_avx2_fn<true, false>;
  return stream ? matrix_block_avx2_fn<false, true> : matrix_block_avx2_fn<false, false>;
}
SimdBlockFn motor_block_avx512_for(bool normals, bool large) {
  if (normals) return large ? motor_block_avx512_fn<true, true> : motor_block_avx512_fn<true, false>;
  return large ? motor_block_avx512_fn<false, true> : motor_block_avx512_fn<false, false>;
}

bool cpu_has_avx2_fma() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
  return has;
}
#else
#define CGA_SKIN_HAVE_AVX2 0
#endif

// Checks the block (block_ok), then skins it; false when the block is invalid (nothing of it written).
using BlockFn = bool (*)(const float*, const Streams&, std::size_t, std::size_t, std::size_t);

}  // namespace

std::string SkinningJob::ValidationError() const {
  std::string error = shape_error(*this);
  if (error.empty()) error = data_error(*this);
  return error;
}

bool SkinningJob::Run() const {
  if (!shape_error(*this).empty()) return false;
  const std::size_t n = vertex_count();
  const Streams s{in_px.data(),  in_py.data(),  in_pz.data(),  in_nx.data(),  in_ny.data(),
                  in_nz.data(),  joints.data(), weights.data(), out_px.data(), out_py.data(),
                  out_pz.data(), out_nx.data(), out_ny.data(), out_nz.data()};
  const bool normals = has_normals();
  // A large mesh (kLargeVertices or more) streams from memory: the SIMD loops prefetch their inputs ahead
  // (prefetch_ahead), and the matrix loops write the outputs with non-temporal stores, which skip reading each
  // output line before writing it (its outputs are out of cache by the time anyone reads them anyway). Those
  // stores need 16-byte aligned output streams (std::vector's are). Small meshes keep plain stores: their
  // outputs stay in cache for the next stage.
  const auto aligned16 = [](std::span<float> v) {
    return v.empty() || reinterpret_cast<std::uintptr_t>(v.data()) % 16 == 0;
  };
  [[maybe_unused]] const bool large = n >= kLargeVertices;
  [[maybe_unused]] const bool stream = large && aligned16(out_px) && aligned16(out_py) && aligned16(out_pz) &&
                                       aligned16(out_nx) && aligned16(out_ny) && aligned16(out_nz);

  // Per-run palette preparation into the loops' layout, on the stack (Run() never allocates): lbs transposes
  // its matrices, cga_points converts every motor once with the generated kernel, cga_motors pads its motors
  // to 16 floats, dqs repacks GLM's dual quaternions as 8 plain floats.
  alignas(64) float converted[kMaxConvertedPalette * kEntry];
  const float* pal = converted;
  BlockFn block = nullptr;
  const std::size_t palette = palette_size(*this);
  switch (method) {
    case SkinningMethod::lbs:
      for (std::size_t k = 0; k < palette; ++k)
        matrix_entry_from_rows(reinterpret_cast<const float*>(&matrices[k]), converted + kEntry * k);
      block = normals ? matrix_block_pn : matrix_block_p;
#if CGA_SKIN_HAVE_AVX2
      if (use_simd && cpu_has_avx2_fma()) block = matrix_block_avx2_for(normals, stream);
#endif
      break;
    case SkinningMethod::cga_points:
      for (std::size_t k = 0; k < palette; ++k) {
        float rows[12];
        detail::motor_matrix(motors[k].c.data(), rows);
        matrix_entry_from_rows(rows, converted + kEntry * k);
      }
      block = normals ? matrix_block_pn : matrix_block_p;
#if CGA_SKIN_HAVE_AVX2
      if (use_simd && cpu_has_avx2_fma()) block = matrix_block_avx2_for(normals, stream);
#endif
      break;
    case SkinningMethod::dqs:
      pack_dual_quats(dual_quats, std::span<float>(converted, 8 * palette));
      block = normals ? dq_block_pn : dq_block_p;
      break;
    case SkinningMethod::cga_motors:
      for (std::size_t k = 0; k < palette; ++k) {
        float* e = converted + kEntry * k;
        detail::motor_split(motors[k].c.data(), e, e + 8, e + 4);
        for (std::size_t r = 12; r < kEntry; ++r) converted[kEntry * k + r] = 0.0f;
      }
      block = normals ? motor_block_pn : motor_block_p;
#if CGA_SKIN_HAVE_AVX2
      if (use_simd && cpu_has_avx2_fma()) block = normals ? motor_block_avx2_fn<true> : motor_block_avx2_fn<false>;
      if (use_simd && use_avx512 && cpu_has_avx512()) block = motor_block_avx512_for(normals, large);
#endif
      break;
  }
  bool ok = true;
  for (std::size_t begin = 0; begin < n && ok; begin += kBlock)
    ok = block(pal, s, begin, std::min(n, begin + kBlock), palette);
#if CGA_SKIN_HAVE_AVX2
  if (stream) _mm_sfence();  // non-temporal stores are weakly ordered: publish them before returning
#endif
  return ok;
}

}  // namespace cga
