// A small CPU z-buffer rasterizer for the demo's pictures: triangles seen by an orthographic camera, shaded
// like the GL path's render.frag (two-sided Lambert, headlight a little above the eye, normals interpolated
// across each triangle), written as PNG. It exists so that the demo draws the posed meshes on any machine;
// the GL path (cga::gpu) renders the same meshes with shaders, framed the same way (view_like()).
#pragma once

#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cga/gpu/render.hpp"

namespace demo {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;      // row-major, top row first
  std::vector<float> depth;           // larger is nearer
  Image(int w, int h);
};

// The orthographic view of a box: `right` and `up` are the picture's axes, depth is toward the viewer.
// A box is framed into a viewport rectangle of the image with a margin, keeping the aspect ratio.
struct View {
  glm::vec3 right{1, 0, 0}, up{0, 1, 0}, toward{0, 0, 1};
  glm::vec2 center{0, 0};  // box centre in (right, up) coordinates
  float scale = 1.0f;      // pixels per unit
  glm::vec2 pixel_center{0, 0};
};

// Frames the points (px, py, pz) in the viewport [x0, x0+w) x [y0, y0+h) (pixels), looking at the side that
// shows the largest area: the picture's vertical is the box's longest of y and z ("up" in most files).
View frame_points(std::span<const float> px, std::span<const float> py, std::span<const float> pz, int x0, int y0,
                  int w, int h);

// The view cga::gpu::render_meshes uses for `camera` (its fixed axes and box; fit_axes and fit_box must be
// off) in the viewport [x0, x0+w) x [y0, y0+h): the same pixels on both paths.
View view_like(const cga::gpu::Camera& camera, int x0, int y0, int w, int h);

// Draws triangles (index triples into the vertex arrays) in `color` (0..1 per channel). With normals (nx, ny,
// nz as long as px) they are interpolated across each triangle; without, each triangle gets its face normal.
void draw_triangles(Image& image, const View& view, std::span<const float> px, std::span<const float> py,
                    std::span<const float> pz, std::span<const std::uint32_t> indices, glm::vec3 color,
                    std::span<const float> nx = {}, std::span<const float> ny = {}, std::span<const float> nz = {});

// The picture as the GL path's image type (RGBA), for its captions (cga/gpu/label.hpp) and PNG writer.
cga::gpu::Image to_rgba(const Image& image);

}  // namespace demo
