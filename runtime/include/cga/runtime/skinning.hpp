// CPU skinning of positions (and optionally normals) with up to 4 influences per vertex, the methods of the
// method table (skinning_methods.hpp) behind one ozz-style job (a struct of non-owning spans with Validate()
// and Run()). Each method is two scripts (runtime/scripts/skin): a per-bone prepare and a per-vertex blend,
// generated into SIMD batch kernels (the simd target, dispatched to the CPU's best instruction set) and into
// a scalar loop (use_simd = false) that agrees with them to float rounding. No blend is written by hand.
//
//   lbs         linear blend skinning with 3x4 matrices (GLM), the industry baseline: p' = sum_k w_k M_k p.
//   dqs         dual-quaternion skinning (Kavan et al. 2008): blend the bones' unit dual quaternions with the
//               antipodality fix, normalize, transform once. Dual quaternions hold no scale, so bones with a
//               scale are not supported by this method.
//   cga_points  the paper's method: transform the vertex by every bone motor (X' = M_k X ~M_k), normalize each
//               resulting point by its weight, then average the Euclidean points with the skin weights. The
//               point transform of a motor is affine in x, so this IS linear blend skinning (it shares LBS's
//               candy-wrapper collapse) and runs as LBS does, on each motor's weight-normalized 3x4 map.
//   cga_motors  blend the motors per vertex (sign fix on the rotor parts), then transform once with the blend
//               divided by its point weight. For rigid bones this equals DQS; unlike dual quaternions it also
//               carries uniform scale (dilation). See docs/skinning.md.
//   cga_log     blend the bones' motor logarithms (computed once per bone and frame) linearly per vertex and
//               take the closed-form exponential: a screw about the blend's own axis, the scale geometric.
//
// Normals: every method moves the normal by the linear part of its blended map; all are renormalized.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "cga/runtime/skinning_methods.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

// The method's table name: "lbs", "dqs", "cga-points", ... (the CLI spelling).
std::string_view to_string(SkinningMethod method);
// Accepts the to_string() names and the enum spelling with '_'; throws std::invalid_argument naming the choices.
// (SkinningMethod, kAllSkinningMethods and skinning_method_info() come from skinning_methods.hpp.)
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

  // The palette of `method` (its table row's PALETTE): lbs -> matrices, dqs -> dual_quats, the cga methods -> motors.
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

  // Run the method on its blend's generated SIMD batch kernels (the default; the CPU's best instruction set,
  // or the one a ScopedSimdTarget pins: cga/runtime/simd_targets.hpp). false: the generated scalar loop, one
  // vertex at a time, which agrees to float rounding; tests use it to check the batch path.
  bool use_simd = true;

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
