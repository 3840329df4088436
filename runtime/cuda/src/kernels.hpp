// The boundary between the host library (C++ compiler) and crowd_skinning.cu (nvcc): plain types only,
// no GLM, so nvcc never parses the runtime's headers.
#pragma once

#include <cstddef>
#include <string>

namespace cga::cuda::detail {

// method: 0 lbs, 1 dqs, 2 cga_points, 3 cga_motors (the order of cga::SkinningMethod).
struct LaunchArgs {
  int method = 0;
  std::size_t vertex_count = 0, instances = 0, bones = 0;
  bool per_instance_inputs = true;
  const float* positions = nullptr;
  const float* normals = nullptr;
  const void* joints = nullptr;
  bool joints_u8 = false;
  const void* weights = nullptr;
  bool weights_unorm16 = false;
  const float* palettes = nullptr;
  float* out_positions = nullptr;
  float* out_normals = nullptr;
};

// Launches (asynchronously) on `stream`; returns the CUDA error text, empty on success.
std::string launch(const LaunchArgs& args, void* stream);

}  // namespace cga::cuda::detail
