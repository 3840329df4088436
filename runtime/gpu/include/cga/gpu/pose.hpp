// A character's skinning palettes at one time of a clip, in the representation each skinning method reads
// (lbs: GLM matrices, dqs: GLM dual quaternions, cga_points / cga_motors: motors from the paper's
// interpolation), through the runtime's motor jobs or the GLM baseline jobs (cga/baselines/pose_jobs.hpp)
// (sampling, local-to-model, palette). For the GPU tests, pictures and the demo.
#pragma once

#include <vector>

#include "cga/runtime/jobs.hpp"
#include "cga/runtime/character.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/baselines/pose_jobs.hpp"

namespace cga::gpu {

// The pose interpolation each method is paired with: lbs -> glm_matrix, dqs -> glm_dualquat,
// cga_points / cga_motors -> paper.
Interpolation pose_mode(SkinningMethod method);

// One mesh's palette; only the array of the method it was made for is filled.
struct MeshPalette {
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
  MotorPalette motors;
};

// Samples the clip at `time` (seconds) and returns the palette of every mesh of the character, in order.
// Throws std::runtime_error when a job refuses its input.
class CharacterPoser {
 public:
  explicit CharacterPoser(const Character& character);
  std::vector<MeshPalette> pose(const Clip& clip, float time, SkinningMethod method);

 private:
  const Character* character_;
  std::vector<baseline::InverseBind> inverse_binds_;
  baseline::PoseBuffer local_, model_;
};

// Every distinct key time of any joint of the clip, sorted.
std::vector<float> key_times(const Clip& clip);

// A mesh skinned on the CPU by the runtime's SkinningJob (the reference of the GPU tests).
SkinnedOutput skin_on_cpu(const SkinnedMesh& mesh, SkinningMethod method, const MeshPalette& palette);

}  // namespace cga::gpu
