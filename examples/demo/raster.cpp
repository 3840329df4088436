// The demo's CPU rasterizer (see raster.hpp): edge functions over each triangle's pixel box, a depth test,
// normals interpolated with the barycentric weights and shaded as the GL path's render.frag shades them.
//
// Why interpolated normals and not one face normal per triangle: a twisted quad is not flat, so its two
// triangles would get two different face normals and a twisted surface would show saw-tooth stripes of
// light and dark. Why the edge functions are computed from the edge's endpoints in one fixed order: a pixel
// centre on (or within rounding of) an edge shared by two triangles must be inside at least one of them;
// computed per triangle in its own vertex order, rounding can put it outside both and leave a crack.
#include "raster.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace demo {

Image::Image(int w, int h)
    : width(w), height(h), rgb(std::size_t(w) * h * 3, 255), depth(std::size_t(w) * h, -std::numeric_limits<float>::infinity()) {}

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

View view_like(const cga::gpu::Camera& camera, int x0, int y0, int w, int h) {
  if (camera.fit_axes || camera.fit_box) throw std::invalid_argument("view_like: the camera must have fixed axes and box");
  // glm::lookAt's frame, as render_meshes builds it: right = dir x up, the picture's up = right x dir.
  const glm::vec3 dir = glm::normalize(camera.direction);
  View v;
  v.right = glm::normalize(glm::cross(dir, camera.up));
  v.up = glm::cross(v.right, dir);
  v.toward = -dir;
  const glm::vec3 lo = camera.box_min, hi = camera.box_max, centre = 0.5f * (lo + hi);
  // render_meshes fits the projected box corners, keeping the aspect ratio, times the margin.
  float hx = 0.0f, hy = 0.0f;
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 corner((c & 1) ? hi.x : lo.x, (c & 2) ? hi.y : lo.y, (c & 4) ? hi.z : lo.z);
    hx = std::max(hx, std::abs(glm::dot(corner - centre, v.right)));
    hy = std::max(hy, std::abs(glm::dot(corner - centre, v.up)));
  }
  const float aspect = float(w) / float(h);
  const float half_w = std::max({hx, hy * aspect, 1e-6f}) * camera.margin;
  v.scale = 0.5f * float(w) / half_w;
  v.center = {glm::dot(centre, v.right), glm::dot(centre, v.up)};
  v.pixel_center = {x0 + 0.5f * w, y0 + 0.5f * h};
  return v;
}

namespace {

glm::vec3 project(const View& v, glm::vec3 p) {
  return {v.pixel_center.x + v.scale * (glm::dot(p, v.right) - v.center.x),
          v.pixel_center.y - v.scale * (glm::dot(p, v.up) - v.center.y), glm::dot(p, v.toward)};
}

// Twice the signed area of (a, b, p), computed with a and b in lexicographic order and the sign flipped when
// they were swapped: the edge a-b of one triangle and b-a of its neighbour give exactly opposite values.
float edge(glm::vec2 a, glm::vec2 b, glm::vec2 p) {
  const bool swap = b.x < a.x || (b.x == a.x && b.y < a.y);
  const glm::vec2 u = swap ? b : a, w = swap ? a : b;
  const float e = (w.x - u.x) * (p.y - u.y) - (w.y - u.y) * (p.x - u.x);
  return swap ? -e : e;
}

}  // namespace

void draw_triangles(Image& image, const View& view, std::span<const float> px, std::span<const float> py,
                    std::span<const float> pz, std::span<const std::uint32_t> indices, glm::vec3 color,
                    std::span<const float> nx, std::span<const float> ny, std::span<const float> nz) {
  // render.frag: the light at the eye, a little above and right; 0.2 ambient + 0.8 two-sided Lambert.
  const glm::vec3 light = glm::normalize(0.3f * view.right + 0.5f * view.up + 1.0f * view.toward);
  const std::size_t n = px.size();
  const bool smooth = nx.size() == n && ny.size() == n && nz.size() == n;
  for (std::size_t t = 0; t + 2 < indices.size(); t += 3) {
    if (indices[t] >= n || indices[t + 1] >= n || indices[t + 2] >= n) continue;
    glm::vec3 w[3], s[3], nv[3];
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = indices[t + k];
      w[k] = {px[i], py[i], pz[i]};
      s[k] = project(view, w[k]);
    }
    const glm::vec3 face = glm::cross(w[1] - w[0], w[2] - w[0]);
    for (int k = 0; k < 3; ++k) nv[k] = smooth ? glm::vec3(nx[indices[t + k]], ny[indices[t + k]], nz[indices[t + k]]) : face;
    const glm::vec2 a(s[0]), b(s[1]), c(s[2]);
    const float area = edge(a, b, c);
    if (area == 0.0f || !std::isfinite(area)) continue;
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
        const glm::vec3 nn = l0 * nv[0] + l1 * nv[1] + l2 * nv[2];
        const float len = glm::length(nn);
        const float lambert = len > 0.0f && std::isfinite(len) ? std::abs(glm::dot(nn / len, light)) : 0.0f;
        const float shade = 0.2f + 0.8f * lambert;
        for (int ch = 0; ch < 3; ++ch)
          image.rgb[3 * at + ch] = std::uint8_t(std::clamp(255.0f * shade * color[ch] + 0.5f, 0.0f, 255.0f));
      }
  }
}

cga::gpu::Image to_rgba(const Image& image) {
  cga::gpu::Image out;
  out.width = image.width, out.height = image.height;
  out.rgba.resize(std::size_t(image.width) * image.height * 4);
  for (std::size_t i = 0; i < std::size_t(image.width) * image.height; ++i) {
    std::copy_n(&image.rgb[3 * i], 3, &out.rgba[4 * i]);
    out.rgba[4 * i + 3] = 255;
  }
  return out;
}

}  // namespace demo
