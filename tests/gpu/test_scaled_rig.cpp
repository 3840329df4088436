// Scaled rigs on the GL paths: on rigs whose joints carry scales 100 and 0.01 (the synthetic centimetre
// rig of tests/runtime/scaled_rig.hpp and huesitos.fbx), every method on the vertex shader + transform
// feedback path and on the compute path is within 1e-5 of the character's size of the double-precision
// reference of the same method. The shaders compute the motor's matrix in split form for this: in blade
// form they are 1e-4 (cga-points) to 6e-4 (cga-motors) of the size away on huesitos.fbx.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cstdio>
#include <string>

#include "../runtime/scaled_rig.hpp"
#include "cga/io/loader.hpp"
#include "cga/testing/key_times.hpp"
#include "cga/gpu/skinning.hpp"

using namespace cga;
using namespace cga::gpu;

namespace {

void check_gl_paths(const Context& ctx, const Character& ch) {
  const double size = character_size(ch);
  const Clip& clip = ch.clips.at(0);
  const std::vector<float> times = cga::testing::key_times(clip);
  for (SkinningMethod method : kAllSkinningMethods)
    for (Interpolation mode : {Interpolation::paper, Interpolation::nlerp}) {
      if (method != SkinningMethod::cga_points && method != SkinningMethod::cga_motors && mode != Interpolation::paper)
        continue;
      Skinner skinner(ctx, method);
      double worst[2] = {0.0, 0.0};
      for (float t : times)
        for (std::size_t m = 0; m < ch.meshes.size(); ++m) {
          const SkinnedMesh& mesh = ch.meshes[m];
          const test::Palettes pal = test::job_palettes(ch, m, clip, t, test::pipeline_mode(method, mode));
          std::vector<float> packed;
          append_palette(method, pal.matrices, pal.dual_quats, pal.motors, packed);
          skinner.set_mesh(mesh);
          const auto ref = test::double_palette(ch, mesh, clip, t);
          REQUIRE(ref.size() == mesh.joint_remap.size());
          for (int path = 0; path < 2; ++path) {
            const SkinnedVertices out = skinner.run(kAllSkinPaths[path], packed, mesh.joint_remap.size(), 1, false);
            for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
              const glm::dvec3 r = test::double_skin(method, ref, mesh, v);
              const glm::dvec3 g(out.positions[3 * v], out.positions[3 * v + 1], out.positions[3 * v + 2]);
              worst[path] = std::max(worst[path], glm::length(g - r));
            }
          }
        }
      for (int path = 0; path < 2; ++path) {
        const double d = worst[path] / size;
        std::printf("%s: %-10s %-5s %-15s %.3g of the size\n", ch.path.c_str(), std::string(to_string(method)).c_str(),
                    std::string(to_string(mode)).c_str(), std::string(to_string(kAllSkinPaths[path])).c_str(), d);
        INFO(ch.path << ": " << to_string(method) << " (" << to_string(mode) << ", " << to_string(kAllSkinPaths[path])
                     << ") is " << d << " of the size from the double reference");
        CHECK(d < 1e-5);
      }
    }
}

}  // namespace

TEST_CASE("GL paths on a rig with joint scales 100 and 0.01: every method within 1e-5 of the size") {
  Context ctx;
  check_gl_paths(ctx, test::make_centimetre_rig());
}

TEST_CASE("GL paths on huesitos.fbx (armature scale 100): every method within 1e-5 of the size") {
  Context ctx;
  check_gl_paths(ctx, load_character(std::string(CGA_MODELS_DIR) + "/FBX/huesitos.fbx"));
}
