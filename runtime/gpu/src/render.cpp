// Offscreen rendering of skinned meshes (FBO with colour + depth, Lambert shading) and the two pictures
// the demo writes: a posed character per method and the twist-cylinder strip.
#include "cga/gpu/render.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/type_ptr.hpp>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include "cga/gpu/label.hpp"
#include "cga/gpu/palette.hpp"
#include "cga/gpu/skinning.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning_palettes.hpp"

namespace cga::gpu {
namespace {

// Area-weighted vertex normals from the triangles, for meshes loaded without normals.
std::vector<float> triangle_normals(std::span<const float> p, std::span<const std::uint32_t> indices) {
  std::vector<float> n(p.size(), 0.0f);
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    const std::uint32_t i[3] = {indices[t], indices[t + 1], indices[t + 2]};
    glm::vec3 v[3];
    for (int k = 0; k < 3; ++k) v[k] = {p[3 * i[k]], p[3 * i[k] + 1], p[3 * i[k] + 2]};
    const glm::vec3 face = glm::cross(v[1] - v[0], v[2] - v[0]);
    for (int k = 0; k < 3; ++k)
      for (int e = 0; e < 3; ++e) n[3 * i[k] + e] += face[e];
  }
  return n;  // the shader normalizes
}

struct Box {
  glm::vec3 lo{std::numeric_limits<float>::max()}, hi{-std::numeric_limits<float>::max()};
  void add(const glm::vec3& p) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  bool empty() const { return lo.x > hi.x; }
};

ShaderSource embedded(unsigned stage, std::string_view name) {
  return {stage, std::string(shader_path(name)), std::string(shader_text(name))};
}

}  // namespace

std::array<std::uint8_t, 4> Image::pixel(int x, int y) const {
  const std::size_t at = (static_cast<std::size_t>(y) * width + x) * 4;
  return {rgba[at], rgba[at + 1], rgba[at + 2], rgba[at + 3]};
}

std::size_t Image::count_pixels_unlike(std::array<std::uint8_t, 4> colour) const {
  std::size_t n = 0;
  for (std::size_t at = 0; at + 3 < rgba.size(); at += 4)
    if (rgba[at] != colour[0] || rgba[at + 1] != colour[1] || rgba[at + 2] != colour[2] || rgba[at + 3] != colour[3])
      ++n;
  return n;
}

Image side_by_side(std::span<const Image> images, int gap, std::array<std::uint8_t, 4> gap_colour) {
  Image out;
  for (const Image& im : images) {
    out.width += im.width + (out.width > 0 ? gap : 0);
    out.height = std::max(out.height, im.height);
  }
  out.rgba.resize(static_cast<std::size_t>(out.width) * out.height * 4);
  for (std::size_t at = 0; at < out.rgba.size(); at += 4) std::copy(gap_colour.begin(), gap_colour.end(), &out.rgba[at]);
  int x0 = 0;
  for (const Image& im : images) {
    for (int y = 0; y < im.height; ++y)
      std::copy_n(&im.rgba[static_cast<std::size_t>(y) * im.width * 4], static_cast<std::size_t>(im.width) * 4,
                  &out.rgba[(static_cast<std::size_t>(y) * out.width + x0) * 4]);
    x0 += im.width + gap;
  }
  return out;
}

glm::vec3 method_colour(SkinningMethod method) {
  const auto& c = skinning_method_info(method).colour;
  return {c[0], c[1], c[2]};
}

ViewMatrices camera_view(const Camera& camera, glm::vec3 lo, glm::vec3 hi, int width, int height) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("cga::gpu::camera_view: empty picture");
  Box box;
  box.add(lo);
  box.add(hi);
  const glm::vec3 extent = box.hi - box.lo;
  glm::vec3 dir = camera.direction, up = camera.up;
  if (camera.fit_axes) {
    int longest = 0, shortest = 0;
    for (int a = 1; a < 3; ++a) {
      if (extent[a] > extent[longest]) longest = a;
      if (extent[a] < extent[shortest]) shortest = a;
    }
    if (shortest == longest) shortest = (longest + 1) % 3;
    up = glm::vec3(0.0f), dir = glm::vec3(0.0f);
    up[longest] = 1.0f;
    dir[shortest] = -1.0f;
  }
  if (glm::length(glm::cross(dir, up)) < 1e-6f)
    throw std::invalid_argument("cga::gpu::camera_view: camera direction parallel to up");
  const glm::vec3 centre = 0.5f * (box.lo + box.hi);
  const float radius = std::max(0.5f * glm::length(extent), 1e-6f);
  const float distance = 3.0f * radius;
  const glm::mat4 view = glm::lookAt(centre - glm::normalize(dir) * distance, centre, up);
  // Fit the projected box corners, keeping the aspect ratio.
  float hx = 0.0f, hy = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? box.hi.x : box.lo.x, (c & 2) ? box.hi.y : box.lo.y, (c & 4) ? box.hi.z : box.lo.z);
    const glm::vec4 v = view * glm::vec4(corner, 1.0f);
    hx = std::max(hx, std::abs(v.x));
    hy = std::max(hy, std::abs(v.y));
  }
  const float aspect = static_cast<float>(width) / static_cast<float>(height);
  const float half_w = std::max({hx, hy * aspect, 1e-6f}) * camera.margin;
  const float half_h = half_w / aspect;
  const glm::mat4 projection = glm::ortho(-half_w, half_w, -half_h, half_h, distance - 1.5f * radius,
                                          distance + 1.5f * radius);
  return {projection * view, glm::mat3(view)};
}

double picture_difference(const Image& a, const Image& b, int tolerance) {
  if (a.width != b.width || a.height != b.height || a.rgba.size() != b.rgba.size())
    throw std::invalid_argument("cga::gpu::picture_difference: pictures of different sizes");
  std::size_t covered = 0, differing = 0;
  for (std::size_t at = 0; at + 3 < a.rgba.size(); at += 4) {
    bool blank_a = true, blank_b = true, differs = false;
    for (int c = 0; c < 4; ++c) {
      blank_a = blank_a && a.rgba[at + c] == kClearColour[c];
      blank_b = blank_b && b.rgba[at + c] == kClearColour[c];
      differs = differs || std::abs(int{a.rgba[at + c]} - int{b.rgba[at + c]}) > tolerance;
    }
    if (blank_a && blank_b) continue;
    ++covered;
    if (differs) ++differing;
  }
  return covered ? static_cast<double>(differing) / static_cast<double>(covered) : 0.0;
}

Image render_meshes(const Context& context, std::span<const DrawMesh> meshes, const Camera& camera, int width,
                    int height) {
  if (width <= 0 || height <= 0 || width > 8192 || height > 8192)
    throw std::invalid_argument("cga::gpu::render_meshes: picture size " + std::to_string(width) + "x" +
                                std::to_string(height) + " outside 1..8192");
  Box box;
  if (camera.fit_box) {
    for (const DrawMesh& m : meshes)
      for (std::size_t i = 0; i + 2 < m.positions.size(); i += 3)
        box.add({m.positions[i], m.positions[i + 1], m.positions[i + 2]});
  } else {
    box.add(camera.box_min);
    box.add(camera.box_max);
  }
  if (box.empty()) throw std::invalid_argument("cga::gpu::render_meshes: nothing to draw");

  const ViewMatrices matrices = camera_view(camera, box.lo, box.hi, width, height);
  const glm::mat4& view_projection = matrices.view_projection;
  const glm::mat3& view_rotation = matrices.view_rotation;

  const ShaderSource stages[] = {embedded(GL_VERTEX_SHADER, "render.vert"),
                                 embedded(GL_FRAGMENT_SHADER, "render.frag")};
  const Object program = context.make_program(stages);
  const GLuint prog = program.get();
  glProgramUniformMatrix4fv(prog, glGetUniformLocation(prog, "u_view_projection"), 1, GL_FALSE,
                            glm::value_ptr(view_projection));
  glProgramUniformMatrix3fv(prog, glGetUniformLocation(prog, "u_view_rotation"), 1, GL_FALSE,
                            glm::value_ptr(view_rotation));

  GLuint names[2] = {0, 0};
  glCreateRenderbuffers(2, names);
  const Object colour_rb(ObjectKind::renderbuffer, names[0]), depth_rb(ObjectKind::renderbuffer, names[1]);
  glNamedRenderbufferStorage(colour_rb.get(), GL_RGBA8, width, height);
  glNamedRenderbufferStorage(depth_rb.get(), GL_DEPTH_COMPONENT24, width, height);
  GLuint fbo_name = 0;
  glCreateFramebuffers(1, &fbo_name);
  const Object fbo(ObjectKind::framebuffer, fbo_name);
  glNamedFramebufferRenderbuffer(fbo.get(), GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, colour_rb.get());
  glNamedFramebufferRenderbuffer(fbo.get(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb.get());
  const GLenum status = glCheckNamedFramebufferStatus(fbo.get(), GL_FRAMEBUFFER);
  if (status != GL_FRAMEBUFFER_COMPLETE)
    throw GlError("cga::gpu::render_meshes: framebuffer incomplete (status " + std::to_string(status) + ")");
  glBindFramebuffer(GL_FRAMEBUFFER, fbo.get());
  glViewport(0, 0, width, height);
  glClearColor(kClearColour[0] / 255.0f, kClearColour[1] / 255.0f, kClearColour[2] / 255.0f, kClearColour[3] / 255.0f);
  glClearDepth(1.0);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);

  GLuint vao_name = 0;
  glCreateVertexArrays(1, &vao_name);
  const Object vao(ObjectKind::vertex_array, vao_name);
  for (const DrawMesh& m : meshes) {
    if (m.positions.size() % 3 != 0 || (!m.normals.empty() && m.normals.size() != m.positions.size()))
      throw std::invalid_argument("cga::gpu::render_meshes: positions/normals are not matching xyz triples");
    const std::size_t n = m.positions.size() / 3;
    for (std::uint32_t i : m.indices)
      if (i >= n)
        throw std::invalid_argument("cga::gpu::render_meshes: index " + std::to_string(i) + " >= " +
                                    std::to_string(n) + " vertices");
    if (m.indices.empty()) continue;
    std::vector<float> computed;
    std::span<const float> normals = m.normals;
    if (normals.empty()) {
      computed = triangle_normals(m.positions, m.indices);
      normals = computed;
    }
    const Buffer pos = context.make_buffer(m.positions);
    const Buffer nrm = context.make_buffer(normals);
    const Buffer idx = context.make_buffer(m.indices);
    glVertexArrayVertexBuffer(vao.get(), 0, pos.get(), 0, 3 * sizeof(float));
    glVertexArrayVertexBuffer(vao.get(), 1, nrm.get(), 0, 3 * sizeof(float));
    glVertexArrayElementBuffer(vao.get(), idx.get());
    for (GLuint a = 0; a < 2; ++a) {
      glVertexArrayAttribFormat(vao.get(), a, 3, GL_FLOAT, GL_FALSE, 0);
      glVertexArrayAttribBinding(vao.get(), a, a);
      glEnableVertexArrayAttrib(vao.get(), a);
    }
    glProgramUniform3f(prog, glGetUniformLocation(prog, "u_color"), m.colour.x, m.colour.y, m.colour.z);
    glUseProgram(prog);
    glBindVertexArray(vao.get());
    glDrawElements(GL_TRIANGLES, static_cast<GLsizei>(m.indices.size()), GL_UNSIGNED_INT, nullptr);
    glBindVertexArray(0);
  }
  glFinish();
  Image image;
  image.width = width, image.height = height;
  std::vector<std::uint8_t> bottom_up(static_cast<std::size_t>(width) * height * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, bottom_up.data());
  glDisable(GL_DEPTH_TEST);
  context.bind_dummy_framebuffer();
  context.check("rendering the meshes");
  image.rgba.resize(bottom_up.size());
  const std::size_t row = static_cast<std::size_t>(width) * 4;
  for (int y = 0; y < height; ++y)
    std::copy_n(&bottom_up[static_cast<std::size_t>(height - 1 - y) * row], row, &image.rgba[y * row]);
  return image;
}

Image render_posed_character(const Context& context, const Character& character,
                             std::span<const MeshPalette> palettes, SkinningMethod method, int width, int height) {
  if (palettes.size() != character.meshes.size())
    throw std::invalid_argument("cga::gpu::render_posed_character: " + std::to_string(palettes.size()) +
                                " palettes for " + std::to_string(character.meshes.size()) + " meshes");
  Skinner skinner(context, method);
  std::vector<SkinnedVertices> skinned;
  for (std::size_t m = 0; m < character.meshes.size(); ++m) {
    const SkinnedMesh& mesh = character.meshes[m];
    std::vector<float> packed;
    append_palette(method, palettes[m].matrices, palettes[m].dual_quats, palettes[m].motors, packed);
    skinner.set_mesh(mesh);
    skinned.push_back(skinner.run(SkinPath::vertex_feedback, packed, mesh.joint_remap.size(), 1, true));
  }
  std::vector<DrawMesh> draws;
  for (std::size_t m = 0; m < character.meshes.size(); ++m)
    draws.push_back({skinned[m].positions, skinned[m].normals, character.meshes[m].indices, method_colour(method)});
  return render_meshes(context, draws, Camera{}, width, height);
}

Image render_method_strip(const Context& context, const SkinnedMesh& mesh,
                          std::span<const Transform> skinning_transforms, const Camera& camera, int panel_width,
                          int height, std::span<const SkinningMethod> methods) {
  MeshPalette palette;
  for (const Transform& x : skinning_transforms) {
    palette.matrices.push_back(to_skinning_matrix(x));
    palette.dual_quats.push_back(to_dual_quat(x));
    palette.motors.push_back(motor_from_transform(x));
  }
  std::vector<Image> panels;
  for (SkinningMethod method : methods) {
    Skinner skinner(context, method);
    skinner.set_mesh(mesh);
    std::vector<float> packed;
    append_palette(method, palette.matrices, palette.dual_quats, palette.motors, packed);
    const SkinnedVertices v = skinner.run(SkinPath::vertex_feedback, packed, skinning_transforms.size(), 1, true);
    const DrawMesh draw{v.positions, v.normals, mesh.indices, method_colour(method)};
    panels.push_back(render_meshes(context, std::span<const DrawMesh>(&draw, 1), camera, panel_width, height));
    draw_label(panels.back(), 0, 0, std::string(to_string(method)));
  }
  return side_by_side(panels);
}

}  // namespace cga::gpu
