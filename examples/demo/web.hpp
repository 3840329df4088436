// cga-demo --web DIR: writes the interactive page (DIR/index.html, everything embedded) that skins the
// character and the twist strip on the GPU in the browser with every method of the skinning method table,
// with the shaders assembled from cgagen's WGSL and GLSL ES blends (web/). See docs/web.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cga/runtime/character.hpp"
#include "cga/runtime/types.hpp"

namespace demo {

struct WebInput {
  const cga::Character* character = nullptr;
  std::string model;              // shown in the page
  std::string fade_description;   // what the time and cross-fade sliders play
  float size = 1.0f;              // character_size(): deviations are reported relative to it
  std::vector<cga::Interpolation> modes;  // the motor modes the page offers (paper, nlerp, screw)
  int times = 20;                 // time slider steps over the clips
  int weights = 5;                // cross-fade slider steps over [0, 1]
  // The per-mesh motor palettes of `mode` at clip step u in [0, 1] (times along both clips) with weight w on
  // the second clip: the demo's pose pipeline (sample 2 clips, cross-fade, hierarchy, palette).
  std::function<std::vector<cga::MotorPalette>(cga::Interpolation mode, float u, float w)> pose;
  // What the time slider's step u in [0, 1] shows (the clip times), next to the slider; may be empty.
  std::function<std::string(float u)> time_label;
};

// Writes DIR/index.html (created if missing). Returns a one-line summary (sizes). Throws std::runtime_error.
std::string write_web_page(const WebInput& in, const std::string& dir);

}  // namespace demo
