// The draw path (CrowdDraw: skinning in the vertex shader while drawing) on whatever EGL gives: for every
// method its picture matches the same characters skinned on the CPU and drawn by render_meshes, and the
// comparison catches a wrong pose (each character drawn with another character's palette).
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "cga/gpu/draw.hpp"
#include "cga/runtime/packed_palette.hpp"
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;
using namespace cga::gpu;

TEST_CASE("crowd drawn with the skinning vertex shader matches the CPU-skinned picture, every method") {
  Context ctx;
  const SkinnedMesh mesh = make_coherent_skinned_mesh(600, 16, 99u);
  const RandomPalettes poses = make_random_palettes(16, 4, 321u);
  CrowdGrid grid;
  grid.characters = 4, grid.columns = 2;
  std::vector<CharacterPalette> right, shifted;
  for (std::size_t i = 0; i < 4; ++i) {
    right.push_back({poses.matrices[i], poses.dual_quats[i], poses.motors[i]});
    const std::size_t o = (i + 1) % 4;
    shifted.push_back({poses.matrices[o], poses.dual_quats[o], poses.motors[o]});
  }
  for (SkinningMethod method : kAllSkinningMethods) {
    INFO(to_string(method));
    CrowdDraw crowd(ctx, method, mesh, grid, 200, 160);
    CHECK(crowd.vertices_per_frame() == 4 * mesh.vertex_count());
    crowd.set_palettes(cycled_packed_palettes(method, poses.matrices, poses.dual_quats, poses.motors, 4), 16);
    crowd.draw();
    const Image gpu = crowd.read_picture();
    const std::size_t covered = gpu.count_pixels_unlike(kClearColour);
    CHECK(covered > 500);
    const Image cpu = reference_picture(ctx, method, mesh, grid, right, 200, 160);
    CHECK(picture_difference(gpu, cpu) <= 0.01);
    // Another pose per character: many pixels change, so the check above can fail.
    const Image wrong = reference_picture(ctx, method, mesh, grid, shifted, 200, 160);
    CHECK(picture_difference(gpu, wrong) > 0.2);
  }
}

TEST_CASE("CrowdDraw rejects what it cannot draw, with the reason") {
  Context ctx;
  SkinnedMesh no_triangles = make_random_skinned_mesh(64, 8, 1u);
  no_triangles.indices.clear();
  CrowdGrid grid;
  CHECK_THROWS_WITH(CrowdDraw(ctx, SkinningMethod::lbs, no_triangles, grid, 64, 64),
                    Catch::Contains("has no triangles"));
  const SkinnedMesh mesh = make_coherent_skinned_mesh(64, 8, 1u);
  CHECK_THROWS_WITH(CrowdDraw(ctx, SkinningMethod::lbs, mesh, grid, 0, 64), Catch::Contains("outside 1..8192"));
  CrowdDraw crowd(ctx, SkinningMethod::dqs, mesh, grid, 32, 32);
  CHECK_THROWS_WITH(crowd.draw(), Catch::Contains("set_palettes first"));
  const std::vector<float> short_palette(8 * 7, 0.0f);
  CHECK_THROWS_WITH(crowd.set_palettes(short_palette, 8), Catch::Contains("want 64"));
  const Image a{2, 1, std::vector<std::uint8_t>(8, 255)}, b{1, 1, std::vector<std::uint8_t>(4, 255)};
  CHECK_THROWS_AS(picture_difference(a, b), std::invalid_argument);
  CHECK(picture_difference(a, a) == 0.0);
}
