// CharacterPoser: the runtime's sampling -> local-to-model -> palette jobs for one mesh palette per method.
#include "cga/gpu/pose.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cga::gpu {

Interpolation pose_mode(SkinningMethod method) {
  switch (skinning_method_info(method).palette) {
    case PaletteKind::matrices: return Interpolation::glm_matrix;
    case PaletteKind::dual_quats: return Interpolation::glm_dualquat;
    case PaletteKind::motors: return Interpolation::paper;
  }
  return Interpolation::paper;
}

CharacterPoser::CharacterPoser(const Character& character)
    : character_(&character),
      local_(static_cast<std::size_t>(character.skeleton.joint_count())),
      model_(static_cast<std::size_t>(character.skeleton.joint_count())) {
  for (const SkinnedMesh& mesh : character.meshes) inverse_binds_.push_back(baseline::make_inverse_bind(mesh));
}

std::vector<MeshPalette> CharacterPoser::pose(const Clip& clip, float time, SkinningMethod method) {
  const Interpolation mode = pose_mode(method);
  if (!baseline::sample(mode, clip, time, local_))
    throw std::runtime_error("cga::gpu::CharacterPoser: sampling clip '" + clip.name + "' at " +
                             std::to_string(time) + " s failed");
  if (!baseline::local_to_model(mode, character_->skeleton, local_, model_))
    throw std::runtime_error("cga::gpu::CharacterPoser: local-to-model job failed");
  std::vector<MeshPalette> out(character_->meshes.size());
  for (std::size_t m = 0; m < out.size(); ++m) {
    const SkinnedMesh& mesh = character_->meshes[m];
    baseline::PaletteBuffer pal(mesh.joint_remap.size());
    if (!baseline::palette(mode, mesh.joint_remap, inverse_binds_[m], model_, pal))
      throw std::runtime_error("cga::gpu::CharacterPoser: palette job failed for mesh '" + mesh.name + "'");
    // Only the array of the method's representation is kept.
    if (uses_motors(mode))
      out[m].motors = std::move(pal.motors);
    else if (mode == Interpolation::glm_matrix)
      out[m].matrices = std::move(pal.matrices);
    else
      out[m].dual_quats = std::move(pal.dual_quats);
  }
  return out;
}

std::vector<float> key_times(const Clip& clip) {
  std::vector<float> times;
  for (const JointKeys& k : clip.keys) times.insert(times.end(), k.times.begin(), k.times.end());
  std::sort(times.begin(), times.end());
  times.erase(std::unique(times.begin(), times.end()), times.end());
  return times;
}

SkinnedOutput skin_on_cpu(const SkinnedMesh& mesh, SkinningMethod method, const MeshPalette& palette) {
  SkinnedOutput out;
  out.resize_for(mesh);
  SkinningJob job = make_skinning_job(method, mesh, out);
  job.matrices = palette.matrices, job.dual_quats = palette.dual_quats, job.motors = palette.motors;
  if (!job.Validate())
    throw std::runtime_error("cga::gpu::skin_on_cpu: " + job.ValidationError() + " (mesh '" + mesh.name + "')");
  if (!job.Run()) throw std::runtime_error("cga::gpu::skin_on_cpu: SkinningJob::Run failed on '" + mesh.name + "'");
  return out;
}

}  // namespace cga::gpu
