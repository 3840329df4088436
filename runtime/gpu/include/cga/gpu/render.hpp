// Pictures on the GL backend: skinned meshes drawn into an offscreen framebuffer (depth test, two-sided
// Lambert shading, orthographic camera fitted to the meshes), read back as RGBA images and written as PNG.
// render_posed_character() draws palettes posed elsewhere (the GPU tests pose them with the GLM baselines
// and the motor jobs); render_method_strip() is what the demo calls (through render_twist_strip() of
// tests/support).
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cga/gpu/context.hpp"
#include "cga/gpu/palette.hpp"
#include "cga/runtime/character.hpp"
#include "cga/runtime/skinning.hpp"

namespace cga::gpu {

// RGBA8, rows top to bottom.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;
  std::array<std::uint8_t, 4> pixel(int x, int y) const;
  // Pixels whose colour differs from `colour` (e.g. the clear colour: 0 means a blank picture).
  std::size_t count_pixels_unlike(std::array<std::uint8_t, 4> colour) const;
};

// Writes a PNG; throws std::runtime_error naming the path on failure.
void write_png(const Image& image, const std::string& path);
// Side by side, top-aligned, with `gap` columns of `gap_colour` between the pictures.
Image side_by_side(std::span<const Image> images, int gap = 4, std::array<std::uint8_t, 4> gap_colour = {0, 0, 0, 255});

// One mesh to draw: positions and normals as xyz triples (normals may be empty: flat-ish shading from a
// constant normal is avoided by computing per-vertex normals from the triangles), triangle indices.
struct DrawMesh {
  std::span<const float> positions;
  std::span<const float> normals;
  std::span<const std::uint32_t> indices;
  glm::vec3 colour{0.8f, 0.8f, 0.8f};
};

struct Camera {
  // Direction the camera looks along and its up vector in model space. When `fit_axes` is set they are
  // chosen from the meshes' bounding box instead: up = its longest axis, looking along its shortest one.
  glm::vec3 direction{0.0f, 0.0f, -1.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  bool fit_axes = true;
  // The box to frame: the meshes' bounding box when fit_box, else [box_min, box_max] (to frame several
  // pictures identically).
  bool fit_box = true;
  glm::vec3 box_min{0.0f}, box_max{0.0f};
  float margin = 1.08f;  // the framed extent times this fills the picture
};

inline constexpr std::array<std::uint8_t, 4> kClearColour{255, 255, 255, 255};

// The matrices a camera gives for the box [lo, hi] in a width x height picture (orthographic, the box's
// corners fitted with camera.margin, axes from the box when camera.fit_axes): what render_meshes and
// CrowdDraw (draw.hpp) draw with, so that their pictures can be compared pixel by pixel.
struct ViewMatrices {
  glm::mat4 view_projection{1.0f};
  glm::mat3 view_rotation{1.0f};
};
ViewMatrices camera_view(const Camera& camera, glm::vec3 lo, glm::vec3 hi, int width, int height);

// The fraction of pixels, among those either picture covers (unlike kClearColour), where a channel differs
// by more than `tolerance`; 0 for two blank pictures. Throws std::invalid_argument on different sizes.
double picture_difference(const Image& a, const Image& b, int tolerance = 24);

// Draws the meshes (model space) into a width x height picture on a white background.
Image render_meshes(const Context& context, std::span<const DrawMesh> meshes, const Camera& camera, int width,
                    int height);

// The colour each method is drawn in (the demo's colours).
glm::vec3 method_colour(SkinningMethod method);

// Every mesh of the character skinned on the GPU (vertex shader + transform feedback) with `method` and its
// palette in `palettes` (one per mesh, in order, in the method's representation). Throws
// std::invalid_argument when the counts differ.
Image render_posed_character(const Context& context, const Character& character,
                             std::span<const MeshPalette> palettes, SkinningMethod method, int width = 512,
                             int height = 512);

// `mesh` skinned on the GPU (vertex shader + transform feedback) with the mesh-space skinning transforms
// `skinning_transforms` (one per palette entry) by each of `methods` (default: the four, in the order lbs,
// dqs, cga-points, cga-motors), side by side, every panel seen by the same `camera` and labelled with its
// method's name (label.hpp).
Image render_method_strip(const Context& context, const SkinnedMesh& mesh,
                          std::span<const Transform> skinning_transforms, const Camera& camera,
                          int panel_width = 256, int height = 384,
                          std::span<const SkinningMethod> methods = kAllSkinningMethods);

}  // namespace cga::gpu
