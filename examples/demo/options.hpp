// cga-demo's command line: what to load, which clips/modes/methods to run and where pictures go.
#pragma once

#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "cga/baselines/pose_mode.hpp"
#include "cga/runtime/skinning.hpp"

namespace demo {

// Bad usage (unknown option, missing or malformed value): the program prints it with the usage and exits 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Options {
  std::string model;                      // --model FILE
  std::vector<std::string> clips;         // --clip NAME (0, 1 or 2 of them)
  std::vector<cga::SkinningMethod> methods = {cga::kAllSkinningMethods.begin(), cga::kAllSkinningMethods.end()};
  // --mode NAME,...: the motor modes and the GLM baselines they are compared with (paper, nlerp, screw,
  // glm-matrix, glm-dualquat).
  std::vector<cga::baseline::PoseMode> modes = {cga::baseline::kAllPoseModes.begin(),
                                                cga::baseline::kAllPoseModes.end()};
  std::string out_dir = "out";            // --out DIR
  bool pictures = true;                   // --no-pictures
  std::string web_dir;                    // --web DIR: also write the interactive page (empty: none)
  int frames = 60;                        // --frames N: poses along the cross-fade
  bool help = false;
};

// Throws UsageError. `default_model` is used when --model is absent.
Options parse_options(int argc, const char* const* argv, const std::string& default_model);

// The --help text.
std::string usage_text(const std::string& default_model);

}  // namespace demo
