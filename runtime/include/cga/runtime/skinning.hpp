// CPU skinning of positions (and optionally normals) with up to 4 influences per vertex, four methods behind
// one ozz-style job (a struct of non-owning spans with Validate() and Run()):
//
//   lbs         linear blend skinning with 3x4 matrices (GLM), the industry baseline: p' = sum_k w_k M_k p.
//   dqs         dual-quaternion skinning (Kavan et al. 2008): blend the bones' unit dual quaternions with the
//               antipodality fix (q_k is negated when dot(q_0, q_k) < 0), normalize, transform once. Dual
//               quaternions hold no scale, so bones with a scale are not supported by this method.
//   cga_points  the paper's method: transform the vertex by every bone motor (X' = M_k X ~M_k), normalize each
//               resulting point by its weight -X'.einf, then average the Euclidean points with the skin weights.
//               Mathematically this IS linear blend skinning (the point transform of a motor is affine in x),
//               so it shares LBS's candy-wrapper collapse. It runs as LBS does: each palette motor is turned
//               into its weight-normalized 3x4 point-transform matrix once per Run by the generated
//               transform_point_split_prepare kernel (the staged point transform's prepare), then the
//               per-vertex work is the matrix blend.
//   cga_motors  blend the 12 motor coefficients per vertex (sign fix: M_k is negated when the dot product of the
//               rotor parts <M_0, M_k> < 0), then transform once with the blended motor and divide by the weight
//               (the generated transform_point_split_prepare does both). For rigid bones this equals DQS; unlike dual
//               quaternions it also carries uniform scale (dilation). See docs/skinning.md.
//
// Normals: lbs/cga_points use the blended linear part, cga_motors the linear part of the blended motor, dqs the
// blended rotation; all are renormalized.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cga/runtime/types.hpp"

namespace cga {

enum class SkinningMethod { lbs, dqs, cga_points, cga_motors };

inline constexpr std::array<SkinningMethod, 4> kAllSkinningMethods{
    SkinningMethod::lbs, SkinningMethod::dqs, SkinningMethod::cga_points, SkinningMethod::cga_motors};

// "lbs", "dqs", "cga-points", "cga-motors" (the CLI spelling).
std::string_view to_string(SkinningMethod method);
// Accepts the to_string() names and the enum spelling with '_'; throws std::invalid_argument naming the choices.
SkinningMethod parse_skinning_method(std::string_view text);

// Largest palette a run takes: every method converts its palette once per run into the loop's layout (cga_points:
// motors -> 3x4 matrices with the generated kernel), on Run()'s stack (64 KiB), since Run() never allocates.
inline constexpr std::size_t kMaxConvertedPalette = 1024;

// How far a vertex's weight sum may be from 1 for Validate() (float rounding of four normalized weights).
inline constexpr float kWeightSumTolerance = 1e-3f;

// Skins vertices [0, vertex count) from rest (mesh space) to posed. Every span is non-owning. The palette of
// the chosen method must hold an entry for every joint index used; the others may be empty.
//
// Size rules (n = vertex_count()):
//   packed streams (every stride 1, the default): each position/normal span holds exactly n floats;
//   strided streams: vertex i of a stream is at [i * stride], so each span covers at least (n - 1) * stride + 1
//     elements (an interleaved buffer: in_px = {buf, size}, in_py = {buf + 1, size - 1}, ..., stride = floats
//     per vertex); n is then ceil(joints.size() / joints_stride);
//   joints, weights: n entries each when packed, (n - 1) * stride + 1 when strided (skin data interleaved with
//     the vertex: a 48-byte vertex x y z nx ny nz w0..w3 j0..j3 has weights at byte 24, stride 3 quadruples of
//     floats, and joints at byte 40, stride 6 quadruples of uint16);
//   palette of `method`: at most kMaxConvertedPalette entries.
struct SkinningJob {
  SkinningMethod method = SkinningMethod::lbs;

  // Rest positions; packed, their common size is the vertex count.
  std::span<const float> in_px, in_py, in_pz;
  // Optional rest normals: all three empty (no normals) or all of the vertex count, and then the output
  // normals must be given too.
  std::span<const float> in_nx, in_ny, in_nz;
  // Influences: up to 4 per vertex; an unused slot has weight 0 (any joint index within the palette).
  std::span<const std::array<std::uint16_t, 4>> joints;
  std::span<const std::array<float, 4>> weights;

  // The palette of `method`: lbs -> matrices, dqs -> dual_quats, cga_points / cga_motors -> motors.
  std::span<const glm::mat3x4> matrices;   // row-major 3x4, see MatrixPalette
  std::span<const glm::dualquat> dual_quats;
  std::span<const Motor> motors;

  // Outputs, the vertex count each (normals only when input normals are given). May not alias the inputs.
  std::span<float> out_px, out_py, out_pz;
  std::span<float> out_nx, out_ny, out_nz;

  // Floats from one vertex to the next in each stream group (ozz's in_positions_stride, in floats rather than
  // bytes); 1 = packed structure of arrays. Strided runs stage 256 vertices at a time on the stack.
  std::size_t in_positions_stride = 1, in_normals_stride = 1;
  std::size_t out_positions_stride = 1, out_normals_stride = 1;
  // Entries of their own span (quadruples) from one vertex's joints / weights to the next; 1 = packed.
  std::size_t joints_stride = 1, weights_stride = 1;

  // Run lbs / cga_points / cga_motors on the hand-written AVX2 + FMA loops when the CPU has them (the default).
  // false: always the portable loops, which agree to float rounding; tests use it to check both paths.
  bool use_simd = true;
  // With use_simd, take the AVX-512 loops where the CPU has them (cga_motors); false keeps the AVX2 ones, so
  // tests and A/B benchmarks reach those on an AVX-512 machine too.
  bool use_avx512 = true;

  // Checks sizes, the palette against every joint index and that every weight is finite and >= 0 with each
  // vertex's weights summing to 1 within kWeightSumTolerance (Run() itself checks only indices and finiteness).
  bool Validate() const { return ValidationError().empty(); }
  // Empty when valid, otherwise why not (the first problem found, with the vertex/joint it concerns).
  std::string ValidationError() const;
  // Validates cheaply (sizes) and checks joints and weights block by block while skinning; returns false
  // on the first invalid block (vertices before it are already written). Never allocates.
  bool Run() const;

  bool is_packed() const {
    return in_positions_stride == 1 && in_normals_stride == 1 && out_positions_stride == 1 &&
           out_normals_stride == 1 && joints_stride == 1 && weights_stride == 1;
  }
  std::size_t vertex_count() const {
    return is_packed() || joints_stride == 0 ? in_px.size() : (joints.size() + joints_stride - 1) / joints_stride;
  }
  bool has_normals() const { return !in_nx.empty(); }
};

// Convenience: fills the input/output spans of a job from a mesh and output arrays sized like it.
struct SkinnedOutput {
  std::vector<float> px, py, pz, nx, ny, nz;
  void resize_for(const SkinnedMesh& mesh);
};
SkinningJob make_skinning_job(SkinningMethod method, const SkinnedMesh& mesh, SkinnedOutput& out);

}  // namespace cga
