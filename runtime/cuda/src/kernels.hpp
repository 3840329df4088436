// The boundary between the host library (C++ compiler) and crowd_skinning.cu (nvcc): plain types only, no
// GLM; of the runtime's headers nvcc parses only the method table (skinning_methods.hpp, plain C++).
#pragma once

#include <cstddef>
#include <string>

#include "cga/runtime/skinning_methods.hpp"

#ifdef __CUDACC__
#define CGA_HOST_DEVICE __host__ __device__
#else
#define CGA_HOST_DEVICE
#endif

namespace cga::cuda::detail {

// The shared-memory palette layout, shared by the kernels and the host (which sizes the launch and models
// the bank conflicts). Shared memory serves a warp's 128-bit loads a quarter warp (8 lanes) at a time in
// wavefronts of 128 B: 8 bank groups of 16 B (4 banks each), at most one distinct 16-B slot per group per
// wavefront. A palette entry is `units` 16-B units (the method's entry_vec4s, 2 or 3). The palette is stored `copies`
// times (1, 2, 4 or 8) and copy c of unit u sits in bank groups [c * 8 / copies, (c + 1) * 8 / copies): lane
// l reads copy l % copies. With 8 copies each copy owns one bank group, so whatever joints a quarter warp's
// lanes read, they hit 8 different groups: one wavefront per quarter, 4 per instruction, the minimum of a
// 128-bit load, where one copy lets random joints pile up in one group (9.3 measured).
inline constexpr unsigned kBankGroups = 8;
inline constexpr std::size_t kPaletteSharedBudget = 24 * 1024;  // bytes per 256-thread block, see copies_for

CGA_HOST_DEVICE inline unsigned palette_slot(unsigned unit, unsigned copy, unsigned copy_shift) {
  const unsigned per_copy_shift = 3u - copy_shift;  // log2 of the bank groups each copy owns
  return ((unit >> per_copy_shift) << 3) + (copy << per_copy_shift) + (unit & ((1u << per_copy_shift) - 1u));
}

// The unit slot `s` holds (the inverse of palette_slot, whatever the copy): what the staging loop reads for
// each slot. May be >= the palette's units in the last row of a layout with fewer than 8 copies.
CGA_HOST_DEVICE inline unsigned palette_unit_of_slot(unsigned s, unsigned copy_shift) {
  const unsigned per_copy_shift = 3u - copy_shift;
  return ((s >> 3) << per_copy_shift) + (s & ((1u << per_copy_shift) - 1u));
}

// 16-B slots the layout spans for `total_units` units (bones * units per entry).
CGA_HOST_DEVICE inline unsigned palette_slots(unsigned total_units, unsigned copy_shift) {
  const unsigned per_copy_shift = 3u - copy_shift;
  return ((total_units + (1u << per_copy_shift) - 1u) >> per_copy_shift) << 3;
}

// log2 of the copies for `bones` entries of `units` 16-B units: as many as fit in kPaletteSharedBudget (24 KiB
// keeps 8 blocks of 256 threads, the 2048 threads an sm_90 SM holds, within its 228 KiB of shared memory).
inline unsigned copy_shift_for(std::size_t bones, unsigned units) {
  unsigned shift = 3;
  while (shift > 0 && std::size_t{palette_slots(static_cast<unsigned>(bones * units), shift)} * 16u > kPaletteSharedBudget)
    --shift;
  return shift;
}

// method: the method's row in the method table (skinning_methods.hpp), i.e. its cga::SkinningMethod value.
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

// The palette's 16-B units per entry: the prepared entry's vec4s (prepared_entry_floats / 4). `method` must be
// a row of the table.
inline unsigned palette_units(int method) {
  return static_cast<unsigned>(kSkinningMethods[static_cast<std::size_t>(method)].entry_vec4s);
}

// Launches (asynchronously) on `stream`; returns the CUDA error text, empty on success.
std::string launch(const LaunchArgs& args, void* stream);

// Runs the kernels' code on the host instead, on host pointers (the same staging into the shared-memory
// layout, the same gathers and blends, block by block): the check without a GPU. Same return value.
std::string run_on_host(const LaunchArgs& args);

}  // namespace cga::cuda::detail
