// Shared by the cga-bench sources: the registration entry point of each benchmark group, and where the
// inputs live (Debian's assimp test models, the bundled kernel scripts, the cgagen tool of this build).
#pragma once

#include <string>

namespace cga::bench {

// Each group registers its benchmarks and summary figures; main() calls them in the table's order.
void register_skinning_benchmarks();
void register_motor_apply_benchmarks();
void register_pose_benchmarks();
void register_generator_benchmarks();
void register_ik_benchmarks();
void register_motion_benchmarks();

// Paths, overridable by environment variables so an installed or moved build still finds its inputs:
//   CGA_MODELS_DIR  (default: the CGA_MODELS_DIR cache variable, /usr/share/assimp/models)
//   CGAGEN          (default: the cgagen target of this build)
//   CGA_SCRIPTS_DIR (default: runtime/scripts of this source tree)
std::string models_dir();
std::string cgagen_path();
std::string scripts_dir();

// The character of the pose and real-mesh benchmarks (54 joints).
inline constexpr const char* kCharacter = "X/BCN_Epileptic.X";

}  // namespace cga::bench
