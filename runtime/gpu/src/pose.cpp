// CharacterPoser: the runtime's sampling -> local-to-model -> palette jobs for one mesh palette per method.
#include "cga/gpu/pose.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace cga::gpu {

Interpolation pose_mode(SkinningMethod method) {
  switch (method) {
    case SkinningMethod::lbs: return Interpolation::glm_matrix;
    case SkinningMethod::dqs: return Interpolation::glm_dualquat;
    case SkinningMethod::cga_points:
    case SkinningMethod::cga_motors: return Interpolation::paper;
  }
  return Interpolation::paper;
}

CharacterPoser::CharacterPoser(const Character& character)
    : character_(&character),
      local_(static_cast<std::size_t>(character.skeleton.joint_count())),
      model_(static_cast<std::size_t>(character.skeleton.joint_count())) {
  for (const SkinnedMesh& mesh : character.meshes) inverse_binds_.push_back(make_inverse_bind(mesh));
}

std::vector<MeshPalette> CharacterPoser::pose(const Clip& clip, float time, SkinningMethod method) {
  const Interpolation mode = pose_mode(method);
  SamplingJob sampling;
  sampling.clip = &clip, sampling.time = time, sampling.mode = mode;
  sampling.out_motors = local_.motors, sampling.out_transforms = local_.transforms,
  sampling.out_dual_quats = local_.dual_quats, sampling.out_scales = local_.scales;
  if (!sampling.Run())
    throw std::runtime_error("cga::gpu::CharacterPoser: sampling clip '" + clip.name + "' at " +
                             std::to_string(time) + " s failed");
  LocalToModelJob l2m;
  l2m.skeleton = &character_->skeleton, l2m.mode = mode;
  l2m.local_motors = local_.motors, l2m.local_transforms = local_.transforms,
  l2m.local_dual_quats = local_.dual_quats, l2m.local_scales = local_.scales;
  l2m.model_motors = model_.motors, l2m.model_matrices = model_.matrices, l2m.model_dual_quats = model_.dual_quats,
  l2m.model_scales = model_.scales;
  if (!l2m.Run()) throw std::runtime_error("cga::gpu::CharacterPoser: local-to-model job failed");
  std::vector<MeshPalette> out(character_->meshes.size());
  for (std::size_t m = 0; m < out.size(); ++m) {
    const SkinnedMesh& mesh = character_->meshes[m];
    const std::size_t n = mesh.joint_remap.size();
    MeshPalette& pal = out[m];
    SkinningPaletteJob job;
    job.mode = mode, job.joint_remap = mesh.joint_remap, job.inverse_bind = &inverse_binds_[m];
    job.model_motors = model_.motors, job.model_matrices = model_.matrices,
    job.model_dual_quats = model_.dual_quats, job.model_scales = model_.scales;
    if (uses_motors(mode)) {
      pal.motors.resize(n);
      job.out_motors = pal.motors;
    } else if (mode == Interpolation::glm_matrix) {
      pal.matrices.resize(n);
      job.out_matrices = pal.matrices;
    } else {
      pal.dual_quats.resize(n);
      job.out_dual_quats = pal.dual_quats;
    }
    if (!job.Run())
      throw std::runtime_error("cga::gpu::CharacterPoser: palette job failed for mesh '" + mesh.name + "'");
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
