// Skinner: uploads a rest mesh once, then skins instances of it through the vertex shader with transform
// feedback or through the compute shader; both share the same input buffers.
#include "cga/gpu/skinning.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include "skin_streams.hpp"

#include "cga/runtime/skinning_palettes.hpp"
#include "embedded_shaders.hpp"

namespace cga::gpu {
namespace {

const detail::EmbeddedShader& find_shader(std::string_view name) {
  for (const detail::EmbeddedShader& s : detail::embedded_shaders())
    if (s.name == name) return s;
  throw std::invalid_argument("cga::gpu: no shader named '" + std::string(name) + "'");
}

ShaderSource source(unsigned stage, std::string_view name) {
  const detail::EmbeddedShader& s = find_shader(name);
  return {stage, std::string(s.path), std::string(s.text)};
}

// -1 is legal (the compiler may drop an unused uniform) and glProgramUniform ignores it.
GLint uniform(unsigned program, const char* name) { return glGetUniformLocation(program, name); }

unsigned groups(std::size_t n, std::size_t size) { return static_cast<unsigned>((n + size - 1) / size); }

// Vertices per compute work group: local_size_x (256) x VERTICES_PER_INVOCATION (4) of shaders/skin_main.comp.
constexpr std::size_t kComputeGroup = 1024;

}  // namespace

std::string_view to_string(SkinPath path) {
  return path == SkinPath::vertex_feedback ? "vertex+feedback" : "compute";
}

std::string_view shader_text(std::string_view name) { return find_shader(name).text; }
std::string_view shader_path(std::string_view name) { return find_shader(name).path; }

std::string shader_method_name(SkinningMethod m) {
  std::string s(cga::to_string(m));
  std::replace(s.begin(), s.end(), '-', '_');
  return s;
}

Skinner::Skinner(const Context& context, SkinningMethod method) : context_(&context), method_(method) {
  const std::string base = "skin_" + shader_method_name(method);
  const ShaderSource vs[] = {source(GL_VERTEX_SHADER, base + ".vert")};
  ProgramOptions feedback;
  feedback.feedback_varyings = {"skinned_position", "skinned_normal"};
  vertex_program_ = context.make_program(vs, feedback);
  const ShaderSource cs[] = {source(GL_COMPUTE_SHADER, base + ".comp")};
  compute_program_ = context.make_program(cs);
  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vao_ = Object(ObjectKind::vertex_array, vao);
  context.check("creating the skinning programs");
}

const Object& Skinner::vertex_program(bool normals) {
  if (normals) return vertex_program_;
  // Positions only: capture 12 bytes per vertex instead of 24. Linked on first use.
  if (!vertex_program_positions_) {
    const ShaderSource vs[] = {source(GL_VERTEX_SHADER, "skin_" + shader_method_name(method_) + ".vert")};
    ProgramOptions feedback;
    feedback.feedback_varyings = {"skinned_position"};
    vertex_program_positions_ = context_->make_program(vs, feedback);
  }
  return vertex_program_positions_;
}

void Skinner::set_mesh(const SkinnedMesh& mesh) { upload_mesh(mesh, 0); }

void Skinner::set_mesh_per_instance(const SkinnedMesh& mesh, std::size_t copies) {
  if (copies == 0)
    throw std::invalid_argument("cga::gpu::Skinner::set_mesh_per_instance: 0 copies of mesh '" + mesh.name + "'");
  upload_mesh(mesh, copies);
}

void Skinner::upload_mesh(const SkinnedMesh& mesh, std::size_t copies) {
  const std::size_t n = mesh.vertex_count();
  if (mesh.py.size() != n || mesh.pz.size() != n || mesh.joints.size() != n || mesh.weights.size() != n)
    throw std::invalid_argument("cga::gpu::Skinner::set_mesh: mesh '" + mesh.name +
                                "' has arrays of different sizes");
  if (mesh.has_normals() && (mesh.nx.size() != n || mesh.ny.size() != n || mesh.nz.size() != n))
    throw std::invalid_argument("cga::gpu::Skinner::set_mesh: mesh '" + mesh.name + "' has " +
                                std::to_string(mesh.nx.size()) + " normals for " + std::to_string(n) + " vertices");
  const std::size_t stored = n * std::max<std::size_t>(copies, 1);
  // The shaders index floats with 32-bit unsigned integers (3 per position).
  if (3 * stored > 0xffffffffu)
    throw std::invalid_argument("cga::gpu::Skinner::set_mesh: " + std::to_string(stored) +
                                " rest vertices in all is more than the shaders can index (2^32 / 3)");
  std::vector<float> p(3 * n), nrm(3 * n, 0.0f);
  for (std::size_t v = 0; v < n; ++v) {
    p[3 * v] = mesh.px[v], p[3 * v + 1] = mesh.py[v], p[3 * v + 2] = mesh.pz[v];
    if (mesh.has_normals()) nrm[3 * v] = mesh.nx[v], nrm[3 * v + 1] = mesh.ny[v], nrm[3 * v + 2] = mesh.nz[v];
  }
  max_joint_ = 0;
  for (const auto& j : mesh.joints)
    for (std::uint16_t k : j) max_joint_ = std::max<unsigned>(max_joint_, k);
  // One copy uploaded, then doubled on the GPU until there are `copies`.
  auto replicated = [&](const void* data, std::size_t one) {
    if (copies <= 1) return context_->make_buffer(one, data);
    Buffer b = context_->make_buffer(one * copies);
    context_->upload(b, data, one);
    for (std::size_t have = 1; have < copies;) {
      const std::size_t add = std::min(have, copies - have);
      context_->copy(b, b, add * one, 0, have * one);
      have += add;
    }
    return b;
  };
  positions_ = replicated(p.data(), p.size() * sizeof(float));
  normals_ = replicated(nrm.data(), nrm.size() * sizeof(float));
  joints_ = replicated(mesh.joints.data(), n * sizeof(mesh.joints[0]));
  weights_ = replicated(mesh.weights.data(), n * sizeof(mesh.weights[0]));
  vertex_count_ = n;
  per_instance_copies_ = copies;
  mesh_has_normals_ = mesh.has_normals();
  last_ = {};

  const GLuint vao = vao_.get();
  detail::bind_skin_streams(vao, positions_.get(), normals_.get(), joints_.get(), weights_.get());
  context_->check("uploading the rest mesh");
}

void Skinner::set_palettes(std::span<const float> palettes, std::size_t bone_count, std::size_t instances) {
  const std::size_t expected = palette_floats(method_) * bone_count * instances;
  if (palettes.size() != expected)
    throw std::invalid_argument("cga::gpu::Skinner::run: " + std::to_string(palettes.size()) +
                                " palette floats for " + std::to_string(instances) + " instances of " +
                                std::to_string(bone_count) + " " + std::string(cga::to_string(method_)) +
                                " entries (expected " + std::to_string(expected) + ")");
  if (vertex_count_ > 0 && max_joint_ >= bone_count)
    throw std::invalid_argument("cga::gpu::Skinner::run: the mesh uses joint " + std::to_string(max_joint_) +
                                " but the palette has " + std::to_string(bone_count) + " entries");
  if (palette_.bytes < palettes.size_bytes())
    palette_ = context_->make_buffer(palettes);
  else
    context_->upload(palette_, palettes.data(), palettes.size_bytes());
  bone_count_ = bone_count;
  instances_ = instances;
  palettes_set_ = true;
}

void Skinner::dispatch(SkinPath path, bool normals) {
  if (!palettes_set_) throw std::logic_error("cga::gpu::Skinner::dispatch: no set_palettes before");
  if (vertex_count_ > 0 && max_joint_ >= bone_count_)
    throw std::invalid_argument("cga::gpu::Skinner::dispatch: the mesh uses joint " + std::to_string(max_joint_) +
                                " but the palette has " + std::to_string(bone_count_) + " entries");
  const std::size_t instances = instances_;
  if (per_instance_copies_ > 0 && instances > per_instance_copies_)
    throw std::invalid_argument("cga::gpu::Skinner::dispatch: " + std::to_string(instances) +
                                " instances but the mesh was uploaded for " + std::to_string(per_instance_copies_));
  normals = normals && mesh_has_normals_;
  const std::size_t total = vertex_count_ * instances;
  if (3 * total > 0xffffffffu || total > 0x7fffffffu)
    throw std::invalid_argument("cga::gpu::Skinner::dispatch: " + std::to_string(total) +
                                " skinned vertices is more than the shaders can index (2^32 / 3)");
  last_ = {};  // until this dispatch is queued
  if (total == 0) {
    last_ = {true, path, normals, instances};
    return;
  }
  const bool per_instance = per_instance_copies_ > 0;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, palette_.get());
  if (path == SkinPath::vertex_feedback) {
    const GLuint prog = vertex_program(normals).get();
    glProgramUniform1i(prog, uniform(prog, "u_bone_count"), static_cast<GLint>(bone_count_));
    glProgramUniform1i(prog, uniform(prog, "u_normals"), normals ? 1 : 0);
    glProgramUniform1i(prog, uniform(prog, "u_vertex_count"), static_cast<GLint>(vertex_count_));
    glProgramUniform1i(prog, uniform(prog, "u_per_instance_inputs"), per_instance ? 1 : 0);
    // Captured per vertex: position (3 floats), then the normal (3 floats) when normals.
    const std::size_t bytes = total * skinned_vertex_bytes(normals);
    if (feedback_out_.bytes < bytes) {
      feedback_out_ = Buffer();  // free the old one first: crowds are large
      feedback_out_ = context_->make_buffer(bytes);
    }
    // Per-instance inputs: one plain draw over all copies (the shader derives the instance from
    // gl_VertexID); shared inputs: an instanced draw of the one mesh.
    if (per_instance)
      context_->feedback_points(prog, vao_.get(), total, 1, feedback_out_);
    else
      context_->feedback_points(prog, vao_.get(), vertex_count_, instances, feedback_out_);
  } else {
    if (instances > 65535)
      throw std::invalid_argument("cga::gpu::Skinner::run: at most 65535 instances per compute dispatch");
    const GLuint prog = compute_program_.get();
    glProgramUniform1ui(prog, uniform(prog, "u_vertex_count"), static_cast<GLuint>(vertex_count_));
    glProgramUniform1i(prog, uniform(prog, "u_bone_count"), static_cast<GLint>(bone_count_));
    glProgramUniform1i(prog, uniform(prog, "u_normals"), normals ? 1 : 0);
    glProgramUniform1i(prog, uniform(prog, "u_per_instance_inputs"), per_instance ? 1 : 0);
    const std::size_t bytes = total * 3 * sizeof(float);
    if (out_positions_.bytes < bytes) {
      out_positions_ = Buffer();
      out_positions_ = context_->make_buffer(bytes);
    }
    if (normals && out_normals_.bytes < bytes) {
      out_normals_ = Buffer();
      out_normals_ = context_->make_buffer(bytes);
    }
    if (!out_normals_.object) out_normals_ = context_->make_buffer(0);  // bound even when unused
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, positions_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, normals_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, joints_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, weights_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, out_positions_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, out_normals_.get());
    context_->dispatch(prog, groups(vertex_count_, kComputeGroup), static_cast<unsigned>(instances));
  }
  last_ = {true, path, normals, instances};
}

SkinnedVertices Skinner::read_back(std::size_t first_instance, std::size_t instance_count) const {
  if (!last_.done) throw std::logic_error("cga::gpu::Skinner::read_back: nothing was dispatched");
  if (first_instance > last_.instances || instance_count > last_.instances - first_instance)
    throw std::out_of_range("cga::gpu::Skinner::read_back: instances [" + std::to_string(first_instance) + ", " +
                            std::to_string(first_instance + instance_count) + ") of " +
                            std::to_string(last_.instances));
  SkinnedVertices out;
  const std::size_t first = first_instance * vertex_count_, count = instance_count * vertex_count_;
  if (count == 0) return out;
  out.positions.resize(3 * count);
  if (last_.normals) out.normals.resize(3 * count);
  if (last_.path == SkinPath::vertex_feedback) {
    const std::size_t stride = last_.normals ? 6 : 3;
    std::vector<float> all(stride * count);
    context_->read(feedback_out_, all.data(), all.size() * sizeof(float), stride * first * sizeof(float));
    for (std::size_t v = 0; v < count; ++v)
      for (int e = 0; e < 3; ++e) {
        out.positions[3 * v + e] = all[stride * v + e];
        if (last_.normals) out.normals[3 * v + e] = all[stride * v + 3 + e];
      }
  } else {
    context_->read(out_positions_, out.positions.data(), out.positions.size() * sizeof(float),
                   3 * first * sizeof(float));
    if (last_.normals)
      context_->read(out_normals_, out.normals.data(), out.normals.size() * sizeof(float),
                     3 * first * sizeof(float));
  }
  return out;
}

SkinnedVertices Skinner::run(SkinPath path, std::span<const float> palettes, std::size_t bone_count,
                             std::size_t instances, bool normals) {
  set_palettes(palettes, bone_count, instances);
  dispatch(path, normals);
  return read_back(0, instances);
}

}  // namespace cga::gpu
