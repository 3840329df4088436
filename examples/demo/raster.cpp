// The demo's CPU rasterizer (see raster.hpp): edge functions over each triangle's pixel box, a depth test,
// Lambert shading of the face normal with a fixed light from the viewer's upper left.
#include "raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#define STB_IMAGE_WRITE_STATIC
#define STB_IMAGE_WRITE_IMPLEMENTATION
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmissing-field-initializers"
#pragma GCC diagnostic ignored "-Wunused-function"
#include <stb/stb_image_write.h>
#pragma GCC diagnostic pop

namespace demo {

Image::Image(int w, int h)
    : width(w), height(h), rgb(std::size_t(w) * h * 3, 245), depth(std::size_t(w) * h, -std::numeric_limits<float>::infinity()) {}

View frame_points(std::span<const float> px, std::span<const float> py, std::span<const float> pz, int x0, int y0,
                  int w, int h) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (std::size_t i = 0; i < px.size(); ++i) {
    const glm::vec3 p(px[i], py[i], pz[i]);
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    lo = glm::min(lo, p), hi = glm::max(hi, p);
  }
  if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);
  const glm::vec3 size = hi - lo;
  View v;
  if (size.z > size.y) v.up = {0, 0, 1}, v.toward = {0, -1, 0};  // z-up files: look along +y
  const glm::vec3 mid = 0.5f * (lo + hi);
  v.center = {glm::dot(mid, v.right), glm::dot(mid, v.up)};
  const float extent_r = std::abs(glm::dot(size, v.right)), extent_u = std::abs(glm::dot(size, v.up));
  const float margin = 0.9f;
  v.scale = margin * std::min(w / std::max(extent_r, 1e-6f), h / std::max(extent_u, 1e-6f));
  v.pixel_center = {x0 + 0.5f * w, y0 + 0.5f * h};
  return v;
}

namespace {

glm::vec3 project(const View& v, glm::vec3 p) {
  return {v.pixel_center.x + v.scale * (glm::dot(p, v.right) - v.center.x),
          v.pixel_center.y - v.scale * (glm::dot(p, v.up) - v.center.y), glm::dot(p, v.toward)};
}

float edge(glm::vec2 a, glm::vec2 b, glm::vec2 p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); }

}  // namespace

void draw_triangles(Image& image, const View& view, std::span<const float> px, std::span<const float> py,
                    std::span<const float> pz, std::span<const std::uint32_t> indices, glm::vec3 color) {
  const glm::vec3 light = glm::normalize(-0.4f * view.right + 0.5f * view.up + 0.77f * view.toward);
  const std::size_t n = px.size();
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (indices[t] >= n || indices[t + 1] >= n || indices[t + 2] >= n) continue;
    glm::vec3 w[3], s[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = indices[t + k];
      w[k] = {px[i], py[i], pz[i]};
      s[k] = project(view, w[k]);
    }
    const glm::vec3 normal = glm::cross(w[1] - w[0], w[2] - w[0]);
    const float len = glm::length(normal);
    if (!(len > 0.0f) || !std::isfinite(len)) continue;
    const float shade = 0.25f + 0.75f * std::abs(glm::dot(normal / len, light));  // two-sided
    const glm::vec2 a(s[0]), b(s[1]), c(s[2]);
    const float area = edge(a, b, c);
    if (area == 0.0f) continue;
    const int xmin = std::max(0, int(std::floor(std::min({a.x, b.x, c.x}))));
    const int xmax = std::min(image.width - 1, int(std::ceil(std::max({a.x, b.x, c.x}))));
    const int ymin = std::max(0, int(std::floor(std::min({a.y, b.y, c.y}))));
    const int ymax = std::min(image.height - 1, int(std::ceil(std::max({a.y, b.y, c.y}))));
    for (int y = ymin; y <= ymax; ++y)
      for (int x = xmin; x <= xmax; ++x) {
        const glm::vec2 p(x + 0.5f, y + 0.5f);
        const float l0 = edge(b, c, p) / area, l1 = edge(c, a, p) / area, l2 = edge(a, b, p) / area;
        if (l0 < 0.0f || l1 < 0.0f || l2 < 0.0f) continue;
        const float z = l0 * s[0].z + l1 * s[1].z + l2 * s[2].z;
        const std::size_t at = std::size_t(y) * image.width + x;
        if (z <= image.depth[at]) continue;
        image.depth[at] = z;
        for (int ch = 0; ch < 3; ++ch)
          image.rgb[3 * at + ch] = std::uint8_t(std::clamp(255.0f * shade * color[ch], 0.0f, 255.0f));
      }
  }
}

void write_png(const Image& image, const std::string& path) {
  if (!stbi_write_png(path.c_str(), image.width, image.height, 3, image.rgb.data(), image.width * 3))
    throw std::runtime_error("cannot write " + path);
}

}  // namespace demo
