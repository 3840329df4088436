// The demo's pictures: the character in one pose per skinning method, and the twist strip, each drawn twice:
// by the CPU rasterizer from the CPU skinning jobs (raster.hpp) and by OpenGL from the GLSL skinning shaders
// (cga::gpu). Both paths get the same pose, the same camera and the same size, so that a CPU picture and its
// GPU twin compare by eye, and every PNG carries a caption: what it shows, the method, the path and the pose.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cga/gpu/context.hpp"
#include "cga/gpu/render.hpp"
#include "cga/runtime/character.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

namespace demo {

struct PictureSet {
  const cga::Character* character = nullptr;
  std::string pose;  // the caption's pose line (which clips, times, mode and weight)
  // Per method, per mesh of the character: the CPU jobs' positions and normals in that pose.
  std::map<cga::SkinningMethod, std::vector<cga::SkinnedOutput>> cpu;
  // Per method and mesh: that pose's palette packed for the GL shaders (cga::gpu::append_palette).
  std::function<std::vector<float>(cga::SkinningMethod, std::size_t mesh)> gpu_palette;
  // The twist strip: the cylinder, the angle of joint 1 (radians) and the CPU jobs' output per method.
  const cga::TwistCylinder* cylinder = nullptr;
  float twist_angle = 0.0f;
  std::map<cga::SkinningMethod, cga::SkinnedOutput> twisted;
  // Filled by write_cpu_pictures: each picture without its caption, by file name without ".png", for
  // write_gpu_pictures to compare its twin with.
  std::map<std::string, cga::gpu::Image> cpu_drawn;
};

// OUT/character-METHOD.png per method and OUT/twist-strip.png; returns the paths written.
std::vector<std::string> write_cpu_pictures(PictureSet& set, const std::string& out_dir);

// OUT/gpu-character-METHOD.png and OUT/gpu-twist-strip.png, skinned by the vertex shaders (transform
// feedback) and drawn by render_meshes; returns the paths written. Also prints, per picture, how many pixels
// differ from its CPU twin (set.cpu_drawn) by more than 16 of 255 in a channel: the two paths agree.
std::vector<std::string> write_gpu_pictures(const cga::gpu::Context& context, const PictureSet& set,
                                            const std::string& out_dir);

}  // namespace demo
