// One mesh's skinning palette in the representation its method reads (lbs: GLM 3x4 matrices, dqs: dual
// quaternions, cga_points / cga_motors: motors), as the GL backend takes it (append_palette, skinning.hpp),
// and the same mesh skinned on the CPU by the runtime's SkinningJob (the reference of the GPU tests).
// How the palette was posed is the caller's business: cga::gpu links no pose pipeline of its own.
#pragma once

#include "cga/runtime/skinning.hpp"

namespace cga::gpu {

// Only the array of the method the palette is made for needs to be filled.
struct MeshPalette {
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
  MotorPalette motors;
};

// A mesh skinned on the CPU by the runtime's SkinningJob. Throws std::runtime_error when the job refuses its
// input (the message names the mesh).
SkinnedOutput skin_on_cpu(const SkinnedMesh& mesh, SkinningMethod method, const MeshPalette& palette);

}  // namespace cga::gpu
