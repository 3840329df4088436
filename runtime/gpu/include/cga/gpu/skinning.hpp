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
#include "cga/runtime/packed_palette.hpp"
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

// Palettes in the shaders' layout: cga::packed_palette_floats / cga::append_packed_palette
// (cga/runtime/packed_palette.hpp), shared with the CUDA kernels.
inline std::size_t palette_floats(SkinningMethod method) { return packed_palette_floats(method); }
inline void append_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                           std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                           std::vector<float>& out) {
  append_packed_palette(method, matrices, dual_quats, motors, out);
}

// Skinned vertices of all instances, instance-major: vertex v of instance i at 3 * (i * vertex_count + v).
struct SkinnedVertices {
  std::vector<float> positions;
  std::vector<float> normals;  // empty when normals were not requested
};

// Bytes one skinned vertex reads from the rest mesh (position 12, joints u16x4 8, weights f32x4 16, normal
// 12 when `normals`) and writes (position 12, normal 12 when `normals`); palettes are not counted.
inline constexpr std::size_t rest_vertex_bytes(bool normals) { return normals ? 48 : 36; }
inline constexpr std::size_t skinned_vertex_bytes(bool normals) { return normals ? 24 : 12; }

// One method's programs (vertex + compute) and the GPU copy of one rest mesh.
//
// Two ways to use it: run() skins and reads everything back (one call); set_palettes() + dispatch() queue the
// skinning with the results left in GPU buffers the Skinner owns (no readback, no wait: what a renderer or a
// benchmark wants), and read_back() fetches some instances of the last dispatch.
class Skinner {
 public:
  Skinner(const Context& context, SkinningMethod method);
  SkinningMethod method() const { return method_; }

  // Uploads the rest positions, normals (zeros when the mesh has none), joints and weights. Every instance
  // reads this one copy (shared inputs).
  void set_mesh(const SkinnedMesh& mesh);
  // Uploads `copies` copies of the mesh one after the other (replicated on the GPU): instance i reads copy i,
  // as when each instance streams its own vertices (a crowd of distinct characters). Then at most `copies`
  // instances can be skinned. copies == 0 is an error.
  void set_mesh_per_instance(const SkinnedMesh& mesh, std::size_t copies);
  std::size_t vertex_count() const { return vertex_count_; }
  // 0 when every instance reads the one rest mesh (set_mesh), else the number of copies.
  std::size_t per_instance_copies() const { return per_instance_copies_; }

  // Skins `instances` copies of the mesh. `palettes` holds instances * bone_count entries in the layout of
  // append_palette; every joint index of the mesh must be < bone_count (checked on the CPU at set_mesh /
  // run, since the shaders do not bounds-check). Normals only when `normals` and the mesh has normals.
  SkinnedVertices run(SkinPath path, std::span<const float> palettes, std::size_t bone_count,
                      std::size_t instances, bool normals);

  // Uploads the palettes of `instances` instances for the following dispatch() calls (the checks of run).
  void set_palettes(std::span<const float> palettes, std::size_t bone_count, std::size_t instances);
  std::size_t instances() const { return instances_; }
  // Queues the skinning of every instance of the last set_palettes into the Skinner's output buffers; returns
  // without reading back or waiting for the GPU. Output buffers grow when needed (allocation happens on the
  // first call of a size, so time the later ones) and are reused otherwise. Throws GlError on a GL error,
  // std::invalid_argument / std::logic_error on a size GL cannot address or a missing set_palettes.
  void dispatch(SkinPath path, bool normals);
  // Instances [first_instance, first_instance + instance_count) of the last dispatch, read back (waits for
  // the GPU). Normals only when that dispatch wrote them. Throws std::out_of_range past its instances.
  SkinnedVertices read_back(std::size_t first_instance, std::size_t instance_count) const;

 private:
  void upload_mesh(const SkinnedMesh& mesh, std::size_t copies);
  const Object& vertex_program(bool normals);

  const Context* context_;
  SkinningMethod method_;
  // Transform feedback captures (position, normal) interleaved, or the position alone.
  Object vertex_program_, vertex_program_positions_, compute_program_, vao_;
  Buffer positions_, normals_, joints_, weights_, palette_;
  Buffer feedback_out_, out_positions_, out_normals_;
  std::size_t vertex_count_ = 0;
  std::size_t per_instance_copies_ = 0;
  unsigned max_joint_ = 0;
  bool mesh_has_normals_ = false;
  // The last set_palettes and dispatch.
  std::size_t bone_count_ = 0, instances_ = 0;
  bool palettes_set_ = false;
  struct LastDispatch {
    bool done = false;
    SkinPath path = SkinPath::compute;
    bool normals = false;
    std::size_t instances = 0;
  } last_;
};

}  // namespace cga::gpu
