// skin_on_cpu: the runtime's SkinningJob on one mesh palette (see cga/gpu/palette.hpp).
#include "cga/gpu/palette.hpp"

#include <stdexcept>
#include <string>

namespace cga::gpu {

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
