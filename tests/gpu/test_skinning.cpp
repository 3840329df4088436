// GPU skinning (vertex shader + transform feedback, and compute) against the CPU SkinningJob, for every
// method: on random meshes and palettes with several instances, on key frames of the real characters
// BCN_Epileptic.X and Testwuson.X (within 1e-4 of the character's size), and on the twist cylinder
// (LBS's candy-wrapper collapse, which the motor blend avoids).
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <string>

#include "cga/gpu/palette.hpp"
#include "cga/gpu/skinning.hpp"
#include "cga/io/loader.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/character_poser.hpp"
#include "cga/testing/key_times.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "cga/testing/nan_max.hpp"

using namespace cga;
using namespace cga::gpu;
using cga::testing::CharacterPoser;
using cga::testing::key_times;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

// Largest distance between the GPU's instance `instance` and the CPU result (positions), and the largest
// angle-ish difference |n_gpu - n_cpu| of the normals where both are finite.
struct Deviation {
  float position = 0.0f;
  float normal = 0.0f;
  std::size_t nonfinite = 0;
};

Deviation compare(const SkinnedVertices& gpu, std::size_t instance, const SkinnedOutput& cpu, bool normals) {
  Deviation d;
  const std::size_t n = cpu.px.size();
  const std::size_t base = 3 * instance * n;
  for (std::size_t v = 0; v < n; ++v) {
    const float g[3] = {gpu.positions[base + 3 * v], gpu.positions[base + 3 * v + 1], gpu.positions[base + 3 * v + 2]};
    const float c[3] = {cpu.px[v], cpu.py[v], cpu.pz[v]};
    float dist2 = 0.0f;
    for (int e = 0; e < 3; ++e) dist2 += (g[e] - c[e]) * (g[e] - c[e]);
    if (!std::isfinite(dist2)) ++d.nonfinite;
    else d.position = std::max(d.position, std::sqrt(dist2));
    if (normals) {
      const float gn[3] = {gpu.normals[base + 3 * v], gpu.normals[base + 3 * v + 1], gpu.normals[base + 3 * v + 2]};
      const float cn[3] = {cpu.nx[v], cpu.ny[v], cpu.nz[v]};
      if (std::isfinite(cn[0] + cn[1] + cn[2])) {
        float nd2 = 0.0f;
        for (int e = 0; e < 3; ++e) nd2 += (gn[e] - cn[e]) * (gn[e] - cn[e]);
        if (!std::isfinite(nd2)) ++d.nonfinite;
        else d.normal = std::max(d.normal, std::sqrt(nd2));
      }
    }
  }
  return d;
}

MeshPalette palette_from_transforms(const std::vector<Transform>& xs, SkinningMethod method) {
  MeshPalette p;
  for (const Transform& x : xs) {
    switch (skinning_method_info(method).palette) {
      case PaletteKind::matrices: p.matrices.push_back(to_skinning_matrix(x)); break;
      case PaletteKind::dual_quats: p.dual_quats.push_back(to_dual_quat(x)); break;
      case PaletteKind::motors: p.motors.push_back(motor_from_transform(x)); break;
    }
  }
  return p;
}

void append(SkinningMethod method, const MeshPalette& p, std::vector<float>& packed) {
  append_palette(method, p.matrices, p.dual_quats, p.motors, packed);
}

}  // namespace

TEST_CASE("GPU skinning equals the CPU job on random meshes, several instances, every method and path") {
  Context ctx;
  constexpr int kJoints = 24;
  constexpr std::size_t kInstances = 3;
  const SkinnedMesh mesh = make_random_skinned_mesh(2000, kJoints, 7u, 2.0f);
  for (SkinningMethod method : kAllSkinningMethods) {
    Skinner skinner(ctx, method);
    skinner.set_mesh(mesh);
    // dqs cannot carry a scale; the other methods get scaled bones too.
    const float log_scale = method == SkinningMethod::dqs ? 0.0f : 0.3f;
    std::vector<MeshPalette> palettes;
    std::vector<float> packed;
    for (std::size_t i = 0; i < kInstances; ++i) {
      palettes.push_back(palette_from_transforms(
          make_random_transforms(kJoints, 100u + static_cast<std::uint32_t>(i), 3.0f, log_scale), method));
      append(method, palettes.back(), packed);
    }
    for (SkinPath path : kAllSkinPaths) {
      const SkinnedVertices gpu = skinner.run(path, packed, kJoints, kInstances, true);
      REQUIRE(gpu.positions.size() == 3 * mesh.vertex_count() * kInstances);
      REQUIRE(gpu.normals.size() == gpu.positions.size());
      for (std::size_t i = 0; i < kInstances; ++i) {
        const SkinnedOutput cpu = skin_on_cpu(mesh, method, palettes[i]);
        const Deviation d = compare(gpu, i, cpu, true);
        INFO(to_string(method) << " " << to_string(path) << " instance " << i << ": position " << d.position
                               << ", normal " << d.normal);
        CHECK(d.nonfinite == 0);
        CHECK(d.position < 1e-4f * 10.0f);  // scene size ~ 10 (extent 2, translations 3, scale e^0.3)
        CHECK(d.normal < 1e-3f);
      }
    }
  }
}

TEST_CASE("positions only: no normals are written or returned") {
  Context ctx;
  const SkinnedMesh mesh = make_random_skinned_mesh(300, 8, 3u);
  Skinner skinner(ctx, SkinningMethod::cga_motors);
  skinner.set_mesh(mesh);
  std::vector<float> packed;
  append(SkinningMethod::cga_motors,
         palette_from_transforms(make_random_transforms(8, 5u), SkinningMethod::cga_motors), packed);
  for (SkinPath path : kAllSkinPaths) {
    const SkinnedVertices v = skinner.run(path, packed, 8, 1, false);
    CHECK(v.positions.size() == 3 * mesh.vertex_count());
    CHECK(v.normals.empty());
  }
}

TEST_CASE("the skinner refuses palettes of the wrong size and joints outside the palette") {
  Context ctx;
  const SkinnedMesh mesh = make_random_skinned_mesh(100, 10, 1u);
  Skinner skinner(ctx, SkinningMethod::lbs);
  skinner.set_mesh(mesh);
  std::vector<float> packed;
  append(SkinningMethod::lbs, palette_from_transforms(make_random_transforms(10, 2u), SkinningMethod::lbs), packed);
  CHECK_THROWS_AS(skinner.run(SkinPath::compute, packed, 10, 2, false), std::invalid_argument);  // 1 palette, 2 instances
  std::vector<float> short_palette(packed.begin(), packed.begin() + 12 * 5);
  CHECK_THROWS_AS(skinner.run(SkinPath::compute, short_palette, 5, 1, false), std::invalid_argument);
  CHECK_NOTHROW(skinner.run(SkinPath::compute, packed, 10, 1, false));
}

TEST_CASE("GPU skinning of the real characters' key frames equals the CPU job within 1e-4 of their size") {
  Context ctx;
  for (const char* file : {"X/BCN_Epileptic.X", "X/Testwuson.X"}) {
    const Character ch = load_character(model(file));
    REQUIRE(!ch.meshes.empty());
    REQUIRE(!ch.clips.empty());
    const float tolerance = 1e-4f * character_size(ch);
    CharacterPoser poser(ch);
    for (SkinningMethod method : kAllSkinningMethods) {
      Skinner skinner(ctx, method);
      for (const Clip& clip : ch.clips) {
        const std::vector<float> times = key_times(clip);
        // Every key frame is one instance of the crowd: one draw / one dispatch per mesh.
        std::vector<std::vector<MeshPalette>> poses;
        for (float t : times) poses.push_back(poser.pose(clip, t, method));
        for (std::size_t m = 0; m < ch.meshes.size(); ++m) {
          const SkinnedMesh& mesh = ch.meshes[m];
          std::vector<float> packed;
          for (const auto& pose : poses) append(method, pose[m], packed);
          skinner.set_mesh(mesh);
          for (SkinPath path : kAllSkinPaths) {
            const SkinnedVertices gpu = skinner.run(path, packed, mesh.joint_remap.size(), times.size(), true);
            Deviation worst;
            for (std::size_t f = 0; f < times.size(); ++f) {
              const Deviation d = compare(gpu, f, skin_on_cpu(mesh, method, poses[f][m]), mesh.has_normals());
              worst.position = std::max(worst.position, d.position);
              worst.normal = std::max(worst.normal, d.normal);
              worst.nonfinite += d.nonfinite;
            }
            INFO(file << " mesh '" << mesh.name << "' clip '" << clip.name << "' " << to_string(method) << " "
                      << to_string(path) << ": " << times.size() << " key frames, "
                      << mesh.vertex_count() << " vertices, worst position " << worst.position << " (tolerance "
                      << tolerance << "), worst normal " << worst.normal);
            CHECK(worst.nonfinite == 0);
            CHECK(worst.position <= tolerance);
            CHECK(worst.normal < 1e-3f);
          }
        }
      }
    }
  }
}

TEST_CASE("twist cylinder at 180 degrees on the GPU: lbs and cga-points collapse, dqs, cga-motors and cga-log keep the radius") {
  Context ctx;
  const TwistCylinder cyl = make_twist_cylinder();
  const std::vector<Transform> bones = twist_cylinder_skinning_transforms(cyl.spec, 3.14159265f);
  for (SkinningMethod method : kAllSkinningMethods) {
    Skinner skinner(ctx, method);
    skinner.set_mesh(cyl.mesh);
    std::vector<float> packed;
    append(method, palette_from_transforms(bones, method), packed);
    for (SkinPath path : kAllSkinPaths) {
      const SkinnedVertices v = skinner.run(path, packed, bones.size(), 1, false);
      float min_r = 1e9f, max_r = 0.0f;
      for (std::uint32_t i : cyl.middle_ring) {
        const float r = std::hypot(v.positions[3 * i], v.positions[3 * i + 1]);
        min_r = testing::nan_min(min_r, r), max_r = testing::nan_max(max_r, r);
      }
      INFO(to_string(method) << " " << to_string(path) << ": middle ring radius in [" << min_r << ", " << max_r << "]");
      if (method == SkinningMethod::lbs || method == SkinningMethod::cga_points) {
        CHECK(max_r < 0.01f * cyl.spec.radius);  // the candy wrapper: the ring shrinks to the axis
      } else {
        CHECK(min_r > 0.999f * cyl.spec.radius);
        CHECK(max_r < 1.001f * cyl.spec.radius);
      }
    }
  }
}
