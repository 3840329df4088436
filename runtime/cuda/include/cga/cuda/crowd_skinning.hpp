// CUDA crowd skinning: many instances, one palette each, positions and optionally normals, for the four
// methods of cga::SkinningMethod. The cga methods run on the kernels cgagen emits with --target cuda
// (transform_point_split.cuh). Plain C++ header (no CUDA types) so host code built by the
// C++ compiler can call it; the kernels live in crowd_skinning.cu.
//
// Layouts: positions 3 floats packed, joints 4 x uint16 (or 4 x uint8 in the compact
// layout), weights 4 x float (or 4 x unorm16), output positions 3 floats; normals 3 floats in and out.
// Instance i reads palette entries [i * bones, (i + 1) * bones) and writes vertices
// [i * vertex_count, (i + 1) * vertex_count); its inputs are either its own copy of the mesh (vertex
// i * vertex_count + v, what a crowd of distinct characters streams) or one shared mesh.
#pragma once

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
// (cga/runtime/packed_palette.hpp), the layout the GL shaders read too.
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

// Palettes are staged in shared memory per block: 256 entries * 12 floats = 12 KiB.
inline constexpr std::size_t kMaxBones = 256;

// Bytes read and written per skinned vertex by the layout (palettes not counted: they are per instance).
std::size_t bytes_per_vertex(const CrowdArgs& args);

// Checks the arguments and launches on `stream` (a cudaStream_t, null = default stream); asynchronous.
// Throws CudaError on bad arguments or a launch error.
void launch_crowd_skinning(const CrowdArgs& args, void* stream = nullptr);

}  // namespace cga::cuda
