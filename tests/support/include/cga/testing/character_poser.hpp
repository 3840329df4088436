// A character's skinning palettes at one time of a clip, in the representation each skinning method reads,
// each posed by the pipeline it is paired with: lbs by the GLM matrix baseline, dqs by the GLM
// dual-quaternion baseline, cga_points / cga_motors by the runtime's motor jobs in the paper's mode
// (sampling, local-to-model, palette; cga/baselines/pose_jobs.hpp). For the GPU tests. Header-only, like
// twist_strip.hpp: it needs cga::gpu's MeshPalette, and cga::test_support does not link cga::gpu.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/gpu/palette.hpp"
#include "cga/runtime/character.hpp"
#include "cga/runtime/skinning.hpp"

namespace cga::testing {

// The pose pipeline each method is paired with: lbs -> glm-matrix, dqs -> glm-dualquat,
// cga_points / cga_motors -> paper.
inline baseline::PoseMode pose_mode(SkinningMethod method) {
  switch (method) {
    case SkinningMethod::lbs: return baseline::PoseMode::glm_matrix;
    case SkinningMethod::dqs: return baseline::PoseMode::glm_dualquat;
    case SkinningMethod::cga_points:
    case SkinningMethod::cga_motors: return baseline::PoseMode::paper;
  }
  return baseline::PoseMode::paper;
}

// Samples a clip and returns the palette of every mesh of the character, in order. Throws
// std::runtime_error when a job refuses its input.
class CharacterPoser {
 public:
  explicit CharacterPoser(const Character& character)
      : character_(&character),
        local_(static_cast<std::size_t>(character.skeleton.joint_count())),
        model_(static_cast<std::size_t>(character.skeleton.joint_count())) {
    for (const SkinnedMesh& mesh : character.meshes) inverse_binds_.push_back(baseline::make_inverse_bind(mesh));
  }

  // Only the array of the method's representation is filled in each palette.
  std::vector<gpu::MeshPalette> pose(const Clip& clip, float time, SkinningMethod method) {
    const baseline::PoseMode mode = pose_mode(method);
    if (!baseline::sample(mode, clip, time, local_))
      throw std::runtime_error("CharacterPoser: sampling clip '" + clip.name + "' at " + std::to_string(time) +
                               " s failed");
    if (!baseline::local_to_model(mode, character_->skeleton, local_, model_))
      throw std::runtime_error("CharacterPoser: local-to-model job failed");
    std::vector<gpu::MeshPalette> out(character_->meshes.size());
    for (std::size_t m = 0; m < out.size(); ++m) {
      const SkinnedMesh& mesh = character_->meshes[m];
      baseline::PaletteBuffer pal(mesh.joint_remap.size());
      if (!baseline::palette(mode, mesh.joint_remap, inverse_binds_[m], model_, pal))
        throw std::runtime_error("CharacterPoser: palette job failed for mesh '" + mesh.name + "'");
      if (baseline::uses_motors(mode))
        out[m].motors = std::move(pal.motors);
      else if (mode == baseline::PoseMode::glm_matrix)
        out[m].matrices = std::move(pal.matrices);
      else
        out[m].dual_quats = std::move(pal.dual_quats);
    }
    return out;
  }

 private:
  const Character* character_;
  std::vector<baseline::InverseBind> inverse_binds_;
  baseline::PoseBuffer local_, model_;
};

}  // namespace cga::testing
