// Crowd drawing with skinning in the vertex shader (the path a renderer uses: no transform feedback, no
// compute pass): N characters of one skinned mesh, each with its own palette, placed on a grid and drawn in
// one instanced, depth-tested draw into an offscreen framebuffer (colour RGBA8 + depth 24), shaded as
// render_meshes shades. cga-draw-bench times it; reference_picture() draws the same characters skinned on
// the CPU (SkinningJob) through render_meshes with the same camera, to compare pictures.
#pragma once

#include <cstddef>
#include <span>

#include <glm/glm.hpp>

#include "cga/gpu/context.hpp"
#include "cga/gpu/render.hpp"
#include "cga/runtime/skinning.hpp"

namespace cga::gpu {

// Where the characters stand: character i at spacing * (i % columns, i / columns, 0), each inside a cube of
// half size `reach` around its place (rest positions within [-1, 1]^3 moved by rigid transforms with
// translations in [-1, 1]^3 stay within |p| <= 2 sqrt(3) < 3.5).
struct CrowdGrid {
  std::size_t characters = 1;
  int columns = 1;
  float spacing = 7.0f;
  float reach = 3.5f;
  glm::vec3 offset(std::size_t i) const;
  // The camera (looking down -z, y up) and the box it frames: every character's cube.
  Camera camera() const;
};

class CrowdDraw {
 public:
  // `mesh` needs triangle indices and normals; throws std::invalid_argument naming what is missing, and
  // on a picture size outside 1..8192.
  CrowdDraw(const Context& context, SkinningMethod method, const SkinnedMesh& mesh, const CrowdGrid& grid,
            int width, int height);
  ~CrowdDraw();
  CrowdDraw(const CrowdDraw&) = delete;
  CrowdDraw& operator=(const CrowdDraw&) = delete;

  // Palettes of every character in the append_palette layout: grid.characters * bones entries.
  void set_palettes(std::span<const float> packed, std::size_t bones);
  // Clears and draws every character (queued; nothing waits).
  void draw() const;
  // Waits for the GPU and reads the picture back (rows top to bottom).
  Image read_picture() const;
  std::size_t vertices_per_frame() const;

 private:
  const Context* context_;
  SkinningMethod method_;
  CrowdGrid grid_;
  int width_, height_;
  std::size_t vertex_count_ = 0, index_count_ = 0, bones_ = 0;
  Object program_, vao_, fbo_, colour_rb_, depth_rb_;
  Buffer positions_, normals_, joints_, weights_, indices_, palette_;
};

// The characters skinned on the CPU (SkinningJob of `method`, palette p for character p) and drawn with
// render_meshes through grid.camera(): the picture CrowdDraw must give. `palettes[i]` holds character i's
// palette in each method's form.
struct CharacterPalette {
  std::span<const glm::mat3x4> matrices;
  std::span<const glm::dualquat> dual_quats;
  std::span<const Motor> motors;
};
Image reference_picture(const Context& context, SkinningMethod method, const SkinnedMesh& mesh,
                        const CrowdGrid& grid, std::span<const CharacterPalette> palettes, int width, int height);

}  // namespace cga::gpu
