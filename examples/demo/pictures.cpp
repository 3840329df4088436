// The demo's CPU and GPU pictures (pictures.hpp): one camera per subject, computed once and used by both
// paths (raster.hpp's view_like reproduces render_meshes' framing), and a caption on every PNG.
#include "pictures.hpp"

#include <cmath>
#include <cstdlib>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "cga/gpu/label.hpp"
#include "cga/gpu/render.hpp"
#include "cga/gpu/skinning.hpp"
#include "cga/testing/twist_strip.hpp"
#include "raster.hpp"

namespace demo {
namespace {

using namespace cga;

constexpr int kCharacterWidth = 480, kCharacterHeight = 640;  // portrait: a standing character
constexpr int kStripPanel = 256, kStripHeight = 384;
// Caption rows (at the small scale) of every picture: the CPU and GPU twins get the same band and line up.
constexpr int kCaptionRows = 7;

// The character's camera on both paths: the box around every method's skinned vertices in the pose (so all
// eight pictures share one frame), seen from the front: along -z with y up, or along +y with z up when the
// character stands along z.
gpu::Camera character_camera(const PictureSet& set) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const auto& [method, meshes] : set.cpu)
    for (const SkinnedOutput& o : meshes)
      for (std::size_t v = 0; v < o.px.size(); ++v) {
        const glm::vec3 p(o.px[v], o.py[v], o.pz[v]);
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) lo = glm::min(lo, p), hi = glm::max(hi, p);
      }
  if (lo.x > hi.x) lo = hi = glm::vec3(0.0f);
  gpu::Camera camera;
  camera.fit_axes = false, camera.fit_box = false;
  camera.box_min = lo, camera.box_max = hi;
  const glm::vec3 size = hi - lo;
  if (size.z > size.y) camera.up = {0, 0, 1}, camera.direction = {0, 1, 0};
  else camera.up = {0, 1, 0}, camera.direction = {0, 0, -1};
  return camera;
}

std::string twist_title(const PictureSet& set) {
  return fmt::format("twist strip: joint 1 turned {:.0f} degrees (the candy-wrapper test)",
                     set.twist_angle * 180.0f / std::numbers::pi_v<float>);
}

// Pixels of `gpu` that differ from `cpu` by more than 16 of 255 in some channel, as "N of TOTAL"; "(no CPU
// picture)" or "(size differs)" when they cannot be compared.
std::string differing(const PictureSet& set, const std::string& name, const gpu::Image& gpu) {
  const auto it = set.cpu_drawn.find(name);
  if (it == set.cpu_drawn.end()) return name + " (no CPU picture)";
  const gpu::Image& cpu = it->second;
  if (cpu.width != gpu.width || cpu.height != gpu.height) return name + " (size differs)";
  std::size_t n = 0;
  for (std::size_t at = 0; at + 3 < gpu.rgba.size(); at += 4)
    for (int c = 0; c < 3; ++c)
      if (std::abs(int(gpu.rgba[at + c]) - int(cpu.rgba[at + c])) > 16) {
        ++n;
        break;
      }
  return fmt::format("{} {} of {}", name, n, gpu.rgba.size() / 4);
}

std::string written(const gpu::Image& image, const std::string& path) {
  gpu::write_png(image, path);
  return path;
}

}  // namespace

std::vector<std::string> write_cpu_pictures(PictureSet& set, const std::string& out_dir) {
  const std::string path_line = "CPU: skinned by the CPU SkinningJob, drawn by the demo's rasterizer";
  std::vector<std::string> out;
  const gpu::Camera camera = character_camera(set);
  for (const auto& [method, meshes] : set.cpu) {
    Image img(kCharacterWidth, kCharacterHeight);
    const View view = view_like(camera, 0, 0, img.width, img.height);
    for (std::size_t m = 0; m < meshes.size(); ++m)
      draw_triangles(img, view, meshes[m].px, meshes[m].py, meshes[m].pz, set.character->meshes[m].indices,
                     gpu::method_colour(method), meshes[m].nx, meshes[m].ny, meshes[m].nz);
    const std::string lines[] = {std::string(to_string(method)), std::string(skinning_method_info(method).caption),
                                 path_line, set.pose};
    const gpu::Image& kept = set.cpu_drawn[fmt::format("character-{}", to_string(method))] = to_rgba(img);
    out.push_back(written(gpu::with_caption(kept, lines, kCaptionRows),
                          fmt::format("{}/character-{}.png", out_dir, to_string(method))));
  }
  if (set.cylinder && !set.twisted.empty()) {
    const gpu::Camera strip_camera = gpu::twist_strip_camera(set.cylinder->spec);
    std::vector<gpu::Image> panels;
    for (const auto& [method, o] : set.twisted) {
      Image img(kStripPanel, kStripHeight);
      draw_triangles(img, view_like(strip_camera, 0, 0, img.width, img.height), o.px, o.py, o.pz,
                     set.cylinder->mesh.indices, gpu::method_colour(method), o.nx, o.ny, o.nz);
      panels.push_back(to_rgba(img));
      gpu::draw_label(panels.back(), 0, 0, std::string(to_string(method)));
    }
    const std::string lines[] = {twist_title(set), path_line};
    const gpu::Image& kept = set.cpu_drawn["twist-strip"] = gpu::side_by_side(panels);
    out.push_back(written(gpu::with_caption(kept, lines, kCaptionRows), out_dir + "/twist-strip.png"));
  }
  return out;
}

std::vector<std::string> write_gpu_pictures(const gpu::Context& context, const PictureSet& set,
                                            const std::string& out_dir) {
  const std::string path_line = "GPU: skinned by the GLSL vertex shader (transform feedback), drawn by OpenGL (" +
                                context.renderer() + ")";
  std::vector<std::string> out;
  const gpu::Camera camera = character_camera(set);
  std::vector<std::string> compared;
  for (const auto& [method, meshes] : set.cpu) {
    gpu::Skinner skinner(context, method);
    std::vector<gpu::SkinnedVertices> skinned;
    for (std::size_t m = 0; m < set.character->meshes.size(); ++m) {
      const std::vector<float> packed = set.gpu_palette(method, m);
      skinner.set_mesh(set.character->meshes[m]);
      skinned.push_back(skinner.run(gpu::SkinPath::vertex_feedback, packed, packed.size() / gpu::palette_floats(method),
                                    1, true));
    }
    std::vector<gpu::DrawMesh> draws;
    for (std::size_t m = 0; m < skinned.size(); ++m)
      draws.push_back({skinned[m].positions, skinned[m].normals, set.character->meshes[m].indices,
                       gpu::method_colour(method)});
    const gpu::Image img = gpu::render_meshes(context, draws, camera, kCharacterWidth, kCharacterHeight);
    compared.push_back(differing(set, fmt::format("character-{}", to_string(method)), img));
    const std::string lines[] = {std::string(to_string(method)), std::string(skinning_method_info(method).caption),
                                 path_line, set.pose};
    out.push_back(written(gpu::with_caption(img, lines, kCaptionRows),
                          fmt::format("{}/gpu-character-{}.png", out_dir, to_string(method))));
  }
  if (set.cylinder && !set.twisted.empty()) {
    std::vector<SkinningMethod> methods;
    for (const auto& [method, o] : set.twisted) methods.push_back(method);
    const gpu::Image strip = gpu::render_twist_strip(context, set.twist_angle, kStripPanel, kStripHeight, methods);
    compared.push_back(differing(set, "twist-strip", strip));
    const std::string lines[] = {twist_title(set), path_line};
    out.push_back(written(gpu::with_caption(strip, lines, kCaptionRows), out_dir + "/gpu-twist-strip.png"));
  }
  fmt::print("pictures, GPU against CPU: pixels that differ by more than 16/255: {}\n", fmt::join(compared, ", "));
  return out;
}

}  // namespace demo
