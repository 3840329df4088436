// CrowdDraw (skinning in the vertex shader while drawing a crowd into an offscreen framebuffer) and the
// CPU-skinned reference picture it is compared with.
#include "cga/gpu/draw.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

#include <glm/gtc/type_ptr.hpp>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include "skin_streams.hpp"

#include "cga/gpu/skinning.hpp"

namespace cga::gpu {

glm::vec3 CrowdGrid::offset(std::size_t i) const {
  const auto c = static_cast<std::size_t>(std::max(columns, 1));
  return spacing * glm::vec3(static_cast<float>(i % c), static_cast<float>(i / c), 0.0f);
}

Camera CrowdGrid::camera() const {
  Camera cam;
  cam.fit_axes = false, cam.fit_box = false;
  cam.direction = {0.0f, 0.0f, -1.0f}, cam.up = {0.0f, 1.0f, 0.0f};
  const std::size_t last = characters > 0 ? characters - 1 : 0;
  const auto c = static_cast<std::size_t>(std::max(columns, 1));
  const glm::vec3 far(spacing * static_cast<float>(std::min(last, c - 1)), spacing * static_cast<float>(last / c), 0.0f);
  cam.box_min = glm::vec3(-reach), cam.box_max = far + glm::vec3(reach);
  cam.margin = 1.02f;
  return cam;
}

namespace {

std::string draw_program(SkinningMethod m) { return "skin_" + shader_method_name(m) + "_draw.vert"; }

ShaderSource embedded(unsigned stage, std::string_view name) {
  return {stage, std::string(shader_path(name)), std::string(shader_text(name))};
}

}  // namespace

CrowdDraw::CrowdDraw(const Context& context, SkinningMethod method, const SkinnedMesh& mesh, const CrowdGrid& grid,
                     int width, int height)
    : context_(&context), method_(method), grid_(grid), width_(width), height_(height) {
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192)
    throw std::invalid_argument("cga::gpu::CrowdDraw: picture size " + std::to_string(width) + "x" +
                                std::to_string(height) + " outside 1..8192");
  if (mesh.indices.empty()) throw std::invalid_argument("cga::gpu::CrowdDraw: mesh '" + mesh.name + "' has no triangles");
  if (!mesh.has_normals()) throw std::invalid_argument("cga::gpu::CrowdDraw: mesh '" + mesh.name + "' has no normals");
  if (grid.characters == 0 || grid.columns <= 0)
    throw std::invalid_argument("cga::gpu::CrowdDraw: no characters or no columns");
  vertex_count_ = mesh.vertex_count();
  index_count_ = mesh.indices.size();
  for (std::uint32_t i : mesh.indices)
    if (i >= vertex_count_)
      throw std::invalid_argument("cga::gpu::CrowdDraw: index " + std::to_string(i) + " >= " +
                                  std::to_string(vertex_count_) + " vertices");

  const ShaderSource stages[] = {embedded(GL_VERTEX_SHADER, draw_program(method)),
                                 embedded(GL_FRAGMENT_SHADER, "render.frag")};
  program_ = context.make_program(stages);
  std::vector<float> p(3 * vertex_count_), n(3 * vertex_count_);
  for (std::size_t v = 0; v < vertex_count_; ++v) {
    p[3 * v] = mesh.px[v], p[3 * v + 1] = mesh.py[v], p[3 * v + 2] = mesh.pz[v];
    n[3 * v] = mesh.nx[v], n[3 * v + 1] = mesh.ny[v], n[3 * v + 2] = mesh.nz[v];
  }
  positions_ = context.make_buffer(std::span<const float>(p));
  normals_ = context.make_buffer(std::span<const float>(n));
  joints_ = context.make_buffer(std::span<const std::array<std::uint16_t, 4>>(mesh.joints));
  weights_ = context.make_buffer(std::span<const std::array<float, 4>>(mesh.weights));
  indices_ = context.make_buffer(std::span<const std::uint32_t>(mesh.indices));

  GLuint vao = 0;
  glCreateVertexArrays(1, &vao);
  vao_ = Object(ObjectKind::vertex_array, vao);
  detail::bind_skin_streams(vao, positions_.get(), normals_.get(), joints_.get(), weights_.get());
  glVertexArrayElementBuffer(vao, indices_.get());

  GLuint rb[2] = {0, 0};
  glCreateRenderbuffers(2, rb);
  colour_rb_ = Object(ObjectKind::renderbuffer, rb[0]);
  depth_rb_ = Object(ObjectKind::renderbuffer, rb[1]);
  glNamedRenderbufferStorage(rb[0], GL_RGBA8, width, height);
  glNamedRenderbufferStorage(rb[1], GL_DEPTH_COMPONENT24, width, height);
  GLuint fbo = 0;
  glCreateFramebuffers(1, &fbo);
  fbo_ = Object(ObjectKind::framebuffer, fbo);
  glNamedFramebufferRenderbuffer(fbo, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, rb[0]);
  glNamedFramebufferRenderbuffer(fbo, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, rb[1]);
  const GLenum status = glCheckNamedFramebufferStatus(fbo, GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("cga::gpu::CrowdDraw: framebuffer incomplete (status " + std::to_string(status) + ")");

  const GLuint prog = program_.get();
  const ViewMatrices m = camera_view(grid.camera(), grid.camera().box_min, grid.camera().box_max, width, height);
  glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_projection"), 1, GL_FALSE,
                            glm::value_ptr(m.view_projection));
  glProgramUniformMatrix3fv(prog, glGetUniformLocation(prog, "u_view_rotation"), 1, GL_FALSE,
                            glm::value_ptr(m.view_rotation));
  glProgramUniform1i(prog, glGetUniformLocation(prog, "u_columns"), grid.columns);
  glProgramUniform1f(prog, glGetUniformLocation(prog, "u_spacing"), grid.spacing);
  const glm::vec3 colour = method_colour(method);
  glProgramUniform3f(prog, glGetUniformLocation(prog, "u_color"), colour.x, colour.y, colour.z);
  context.check("cga::gpu::CrowdDraw setup");
}

CrowdDraw::~CrowdDraw() = default;

std::size_t CrowdDraw::vertices_per_frame() const { return vertex_count_ * grid_.characters; }

void CrowdDraw::set_palettes(std::span<const float> packed, std::size_t bones) {
  const std::size_t want = grid_.characters * bones * packed_palette_floats(method_);
  if (bones == 0 || packed.size() != want)
    throw std::invalid_argument("cga::gpu::CrowdDraw::set_palettes: " + std::to_string(packed.size()) +
                                " floats for " + std::to_string(grid_.characters) + " characters x " +
                                std::to_string(bones) + " bones (want " + std::to_string(want) + ")");
  bones_ = bones;
  palette_ = context_->make_buffer(packed);
  glProgramUniform1i(program_.get(), glGetUniformLocation(program_.get(), "u_bone_count"), static_cast<GLint>(bones));
  context_->check("cga::gpu::CrowdDraw::set_palettes");
}

void CrowdDraw::draw() const {
  if (!palette_.object) throw std::logic_error("cga::gpu::CrowdDraw::draw: set_palettes first");
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  glViewport(0, 0, width_, height_);
  glClearColor(kClearColour[0] / 255.0f, kClearColour[1] / 255.0f, kClearColour[2] / 255.0f, kClearColour[3] / 255.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, palette_.get());
  glUseProgram(program_.get());
  glBindVertexArray(vao_.get());
  glDrawElementsInstanced(GL_TRIANGLES, static_cast<GLsizei>(index_count_), GL_UNSIGNED_INT, nullptr,
                          static_cast<GLsizei>(grid_.characters));
  glBindVertexArray(0);
  glDisable(GL_DEPTH_TEST);
  context_->check("cga::gpu::CrowdDraw::draw");
}

Image CrowdDraw::read_picture() const {
  Image image;
  image.width = width_, image.height = height_;
  std::vector<std::uint8_t> bottom_up(static_cast<std::size_t>(width_) * height_ * 4);
  glBindFramebuffer(GL_FRAMEBUFFER, fbo_.get());
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width_, height_, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  context_->bind_dummy_framebuffer();
  context_->check("cga::gpu::CrowdDraw::read_picture");
  image.rgba.resize(bottom_up.size());
  const std::size_t row = static_cast<std::size_t>(width_) * 4;
  for (int y = 0; y < height_; ++y)
    std::copy_n(&bottom_up[static_cast<std::size_t>(height_ - 1 - y) * row], row, &image.rgba[y * row]);
  return image;
}

Image reference_picture(const Context& context, SkinningMethod method, const SkinnedMesh& mesh,
                        const CrowdGrid& grid, std::span<const CharacterPalette> palettes, int width, int height) {
  if (palettes.size() != grid.characters)
    throw std::invalid_argument("cga::gpu::reference_picture: " + std::to_string(palettes.size()) +
                                " palettes for " + std::to_string(grid.characters) + " characters");
  std::vector<std::vector<float>> positions(grid.characters), normals(grid.characters);
  std::vector<DrawMesh> draws;
  for (std::size_t i = 0; i < grid.characters; ++i) {
    SkinnedOutput out;
    SkinningJob job = make_skinning_job(method, mesh, out);
    job.matrices = palettes[i].matrices, job.dual_quats = palettes[i].dual_quats, job.motors = palettes[i].motors;
    if (!job.Run()) throw std::invalid_argument("cga::gpu::reference_picture: " + job.ValidationError());
    const glm::vec3 o = grid.offset(i);
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      positions[i].insert(positions[i].end(), {out.px[v] + o.x, out.py[v] + o.y, out.pz[v] + o.z});
      normals[i].insert(normals[i].end(), {out.nx[v], out.ny[v], out.nz[v]});
    }
    draws.push_back({positions[i], normals[i], mesh.indices, method_colour(method)});
  }
  return render_meshes(context, draws, grid.camera(), width, height);
}

}  // namespace cga::gpu
