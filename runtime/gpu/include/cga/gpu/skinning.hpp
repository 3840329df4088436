// GPU skinning on the GL backend, for the four methods of cga::SkinningMethod: the vertex-shader path
// (transform feedback captures the skinned vertices) and the compute path (SSBO in/out). Both skin many
// instances of one rest mesh at once, instance i with palette entries [i * bone_count, (i + 1) * bone_count).
// The shaders are assembled at build time from the generated GLSL kernels (see runtime/gpu/shaders).
#pragma once

#include <cstddef>
#include <span>
#include <string>
#include <vector>

#include "cga/gpu/context.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/types.hpp"

namespace cga::gpu {

enum class SkinPath { vertex_feedback, compute };
inline constexpr SkinPath kAllSkinPaths[] = {SkinPath::vertex_feedback, SkinPath::compute};
std::string_view to_string(SkinPath path);  // "vertex+feedback", "compute"

// The assembled GLSL text of a program ("skin_cga_motors.vert", "skin_lbs.comp", "render.frag", ...);
// throws std::invalid_argument for an unknown name.
std::string_view shader_text(std::string_view name);
// Where the build wrote that program (what glslangValidator checked); used in error messages.
std::string_view shader_path(std::string_view name);
// The method as shader file names spell it: "lbs", "dqs", "cga_points", "cga_motors".
std::string shader_method_name(SkinningMethod method);

// How many floats one palette entry takes on the GPU: lbs 12 (3 rows), dqs 8 (real xyzw, dual xyzw),
// cga_points / cga_motors 12 (the motor's blades in order = the paper's mat3x4, blade k at column k/4).
std::size_t palette_floats(SkinningMethod method);

// Appends the method's palette (matrices for lbs, dual_quats for dqs, motors for the cga methods; the
// others are ignored) to `out` in the GPU layout. Use once per instance to build a crowd's palettes.
void append_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                    std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                    std::vector<float>& out);

// Skinned vertices of all instances, instance-major: vertex v of instance i at 3 * (i * vertex_count + v).
struct SkinnedVertices {
  std::vector<float> positions;
  std::vector<float> normals;  // empty when normals were not requested
};

// One method's programs (vertex + compute) and the GPU copy of one rest mesh.
class Skinner {
 public:
  Skinner(const Context& context, SkinningMethod method);
  SkinningMethod method() const { return method_; }

  // Uploads the rest positions, normals (zeros when the mesh has none), joints and weights.
  void set_mesh(const SkinnedMesh& mesh);
  std::size_t vertex_count() const { return vertex_count_; }

  // Skins `instances` copies of the mesh. `palettes` holds instances * bone_count entries in the layout of
  // append_palette; every joint index of the mesh must be < bone_count (checked on the CPU at set_mesh /
  // run, since the shaders do not bounds-check). Normals only when `normals` and the mesh has normals.
  SkinnedVertices run(SkinPath path, std::span<const float> palettes, std::size_t bone_count,
                      std::size_t instances, bool normals);

 private:
  void upload_palettes(std::span<const float> palettes, std::size_t bone_count, std::size_t instances);

  const Context* context_;
  SkinningMethod method_;
  Object vertex_program_, compute_program_, vao_;
  Buffer positions_, normals_, joints_, weights_, palette_;
  std::size_t vertex_count_ = 0;
  unsigned max_joint_ = 0;
  bool mesh_has_normals_ = false;
};

}  // namespace cga::gpu
