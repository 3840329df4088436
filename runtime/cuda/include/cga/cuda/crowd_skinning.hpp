// CUDA crowd skinning: many instances, one palette each, positions and optionally normals, for every method
// of the method table (cga::SkinningMethod, skinning_methods.hpp). Each method runs its per-vertex blend as
// cgagen emits it with --target cuda (runtime/scripts/skin); the palettes come prepared by the method's
// per-bone kernel (cga::append_packed_palette). Plain C++ header (no CUDA types) so host code built by the
// C++ compiler can call it; the kernels live in crowd_skinning.cu.
//
// Layouts: positions 3 floats packed, joints 4 x uint16 (or 4 x uint8 in the compact
// layout), weights 4 x float (or 4 x unorm16), output positions 3 floats; normals 3 floats in and out.
// Instance i reads palette entries [i * bones, (i + 1) * bones) and writes vertices
// [i * vertex_count, (i + 1) * vertex_count); its inputs are either its own copy of the mesh (vertex
// i * vertex_count + v, what a crowd of distinct characters streams) or one shared mesh.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

#include "cga/runtime/packed_palette.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/types.hpp"

namespace cga::cuda {

enum class JointFormat { u16x4, u8x4 };
enum class WeightFormat { f32x4, unorm16x4 };

// A CUDA call failed (the message has cudaGetErrorString), or the arguments are inconsistent.
struct CudaError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Palettes in the kernels' layout: cga::packed_palette_floats / cga::append_packed_palette
// (cga/runtime/packed_palette.hpp), prepared_entry_floats(method) floats per entry, the layout the GL shaders
// read too.
inline std::size_t palette_floats(SkinningMethod m) { return packed_palette_floats(m); }
using cga::append_packed_palette;

// Device pointers and sizes of one launch.
struct CrowdArgs {
  SkinningMethod method = SkinningMethod::lbs;
  std::size_t vertex_count = 0;  // per instance
  std::size_t instances = 0;
  std::size_t bones = 0;         // palette entries per instance (<= kMaxBones)
  bool per_instance_inputs = true;
  const float* positions = nullptr;
  const float* normals = nullptr;      // null: positions only
  const void* joints = nullptr;
  JointFormat joint_format = JointFormat::u16x4;
  const void* weights = nullptr;
  WeightFormat weight_format = WeightFormat::f32x4;
  const float* palettes = nullptr;     // instances * bones * palette_floats(method)
  float* out_positions = nullptr;
  float* out_normals = nullptr;        // required when normals is given
};

// Palettes are staged in shared memory per block: 256 entries of at most 12 floats = 12 KiB per copy.
inline constexpr std::size_t kMaxBones = 256;

// Bytes read and written per skinned vertex by the layout (palettes not counted: they are per instance).
std::size_t bytes_per_vertex(const CrowdArgs& args);

// How a block stages its palette in shared memory (see docs/gpu.md): `copies` copies (1, 2, 4, 8) spread over
// the 8 bank groups of 16 B so that lane l of a warp reads copy l % copies; `shared_bytes` per block.
struct PaletteLayout {
  unsigned copies = 1;
  std::size_t shared_bytes = 0;
};
PaletteLayout palette_layout(SkinningMethod method, std::size_t bones);

// Shared-memory wavefronts of one warp-wide palette load, modelled: a 128-bit load is served per quarter
// warp (8 lanes, 128 B), and a quarter takes as many wavefronts as its busiest bank group has distinct 16-B
// slots (equal addresses broadcast): 4 per load at the least. On make_random_skinned_mesh with one copy
// the model gives 9.3, what Nsight Compute measured on an H200 (58.7 M wavefronts / 6.29 M loads). Returns
// the mean over the mesh's warps (32 consecutive vertices) and its palette reads (4 joint slots x units).
double modelled_palette_wavefronts(const PaletteLayout& layout, SkinningMethod method,
                                   std::span<const std::array<std::uint16_t, 4>> joints);

// Checks the arguments and launches on `stream` (a cudaStream_t, null = default stream); asynchronous.
// Throws CudaError on bad arguments or a launch error.
void launch_crowd_skinning(const CrowdArgs& args, void* stream = nullptr);

}  // namespace cga::cuda
