// Skinner: uploads a rest mesh once, then skins instances of it through the vertex shader with transform
// feedback or through the compute shader; both share the same input buffers.
#include "cga/gpu/skinning.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

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

// Must match local_size_x of shaders/skin_main.comp.
constexpr std::size_t kComputeGroup = 128;

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

std::size_t palette_floats(SkinningMethod method) { return method == SkinningMethod::dqs ? 8 : 12; }

void append_palette(SkinningMethod method, std::span<const glm::mat3x4> matrices,
                    std::span<const glm::dualquat> dual_quats, std::span<const Motor> motors,
                    std::vector<float>& out) {
  switch (method) {
    case SkinningMethod::lbs:
      for (const glm::mat3x4& m : matrices)
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 4; ++c) out.push_back(m[r][c]);
      break;
    case SkinningMethod::dqs: {
      const std::size_t at = out.size();
      out.resize(at + 8 * dual_quats.size());
      pack_dual_quats(dual_quats, std::span<float>(out).subspan(at));
      break;
    }
    case SkinningMethod::cga_points:
    case SkinningMethod::cga_motors:
      // Blade k at float k is the std430 mat3x4 with blade k at column k/4, row k%4 (the paper's packing).
      for (const Motor& m : motors) out.insert(out.end(), m.c.begin(), m.c.end());
      break;
  }
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

void Skinner::set_mesh(const SkinnedMesh& mesh) {
  const std::size_t n = mesh.vertex_count();
  if (mesh.py.size() != n || mesh.pz.size() != n || mesh.joints.size() != n || mesh.weights.size() != n)
    throw std::invalid_argument("cga::gpu::Skinner::set_mesh: mesh '" + mesh.name +
                                "' has arrays of different sizes");
  if (mesh.has_normals() && (mesh.nx.size() != n || mesh.ny.size() != n || mesh.nz.size() != n))
    throw std::invalid_argument("cga::gpu::Skinner::set_mesh: mesh '" + mesh.name + "' has " +
                                std::to_string(mesh.nx.size()) + " normals for " + std::to_string(n) + " vertices");
  std::vector<float> p(3 * n), nrm(3 * n, 0.0f);
  for (std::size_t v = 0; v < n; ++v) {
    p[3 * v] = mesh.px[v], p[3 * v + 1] = mesh.py[v], p[3 * v + 2] = mesh.pz[v];
    if (mesh.has_normals()) nrm[3 * v] = mesh.nx[v], nrm[3 * v + 1] = mesh.ny[v], nrm[3 * v + 2] = mesh.nz[v];
  }
  max_joint_ = 0;
  for (const auto& j : mesh.joints)
    for (std::uint16_t k : j) max_joint_ = std::max<unsigned>(max_joint_, k);
  positions_ = context_->make_buffer(std::span<const float>(p));
  normals_ = context_->make_buffer(std::span<const float>(nrm));
  joints_ = context_->make_buffer(std::span<const std::array<std::uint16_t, 4>>(mesh.joints));
  weights_ = context_->make_buffer(std::span<const std::array<float, 4>>(mesh.weights));
  vertex_count_ = n;
  mesh_has_normals_ = mesh.has_normals();

  const GLuint vao = vao_.get();
  glVertexArrayVertexBuffer(vao, 0, positions_.get(), 0, 3 * sizeof(float));
  glVertexArrayVertexBuffer(vao, 1, normals_.get(), 0, 3 * sizeof(float));
  glVertexArrayVertexBuffer(vao, 2, joints_.get(), 0, 4 * sizeof(std::uint16_t));
  glVertexArrayVertexBuffer(vao, 3, weights_.get(), 0, 4 * sizeof(float));
  glVertexArrayAttribFormat(vao, 0, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribFormat(vao, 1, 3, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribIFormat(vao, 2, 4, GL_UNSIGNED_SHORT, 0);
  glVertexArrayAttribFormat(vao, 3, 4, GL_FLOAT, GL_FALSE, 0);
  for (GLuint a = 0; a < 4; ++a) {
    glVertexArrayAttribBinding(vao, a, a);
    glEnableVertexArrayAttrib(vao, a);
  }
  context_->check("uploading the rest mesh");
}

void Skinner::upload_palettes(std::span<const float> palettes, std::size_t bone_count, std::size_t instances) {
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
}

SkinnedVertices Skinner::run(SkinPath path, std::span<const float> palettes, std::size_t bone_count,
                             std::size_t instances, bool normals) {
  upload_palettes(palettes, bone_count, instances);
  normals = normals && mesh_has_normals_;
  SkinnedVertices out;
  const std::size_t total = vertex_count_ * instances;
  if (total == 0) return out;
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, palette_.get());
  if (path == SkinPath::vertex_feedback) {
    const GLuint prog = vertex_program_.get();
    glProgramUniform1i(prog, uniform(prog, "u_bone_count"), static_cast<GLint>(bone_count));
    glProgramUniform1i(prog, uniform(prog, "u_normals"), normals ? 1 : 0);
    // Interleaved capture: position (3 floats), normal (3 floats) per vertex.
    Buffer captured = context_->make_buffer(total * 6 * sizeof(float));
    context_->capture_points(prog, vao_.get(), vertex_count_, instances, captured);
    const std::vector<float> all = context_->read_all<float>(captured);
    out.positions.resize(3 * total);
    if (normals) out.normals.resize(3 * total);
    for (std::size_t v = 0; v < total; ++v)
      for (int e = 0; e < 3; ++e) {
        out.positions[3 * v + e] = all[6 * v + e];
        if (normals) out.normals[3 * v + e] = all[6 * v + 3 + e];
      }
  } else {
    if (instances > 65535)
      throw std::invalid_argument("cga::gpu::Skinner::run: at most 65535 instances per compute dispatch");
    const GLuint prog = compute_program_.get();
    glProgramUniform1ui(prog, uniform(prog, "u_vertex_count"), static_cast<GLuint>(vertex_count_));
    glProgramUniform1i(prog, uniform(prog, "u_bone_count"), static_cast<GLint>(bone_count));
    glProgramUniform1i(prog, uniform(prog, "u_normals"), normals ? 1 : 0);
    Buffer out_p = context_->make_buffer(total * 3 * sizeof(float));
    Buffer out_n = context_->make_buffer(normals ? total * 3 * sizeof(float) : 0);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, positions_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, normals_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 3, joints_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 4, weights_.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 5, out_p.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 6, out_n.get());
    context_->dispatch(prog, groups(vertex_count_, kComputeGroup), static_cast<unsigned>(instances));
    out.positions = context_->read_all<float>(out_p);
    if (normals) out.normals = context_->read_all<float>(out_n);
  }
  return out;
}

}  // namespace cga::gpu
