// cga::cuda's host side without a GPU: a launch with inconsistent arguments throws CudaError naming the
// problem before any CUDA call; bytes per vertex of the layouts the benchmark reports; palettes packed in
// the layout the kernels read (lbs row-major 3x4, dqs real xyzw + dual xyzw, cga motors' 12 blades); the
// shared-memory palette copies (kernels.hpp) and the bank model that predicts their wavefronts.
#include <catch2/catch.hpp>

#include <string>
#include <vector>

#include "cga/cuda/crowd_skinning.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "kernels.hpp"

using namespace cga;
using namespace cga::cuda;

namespace {

// Arguments that pass every check (the pointers are never dereferenced by the checks).
CrowdArgs valid_args() {
  static float f[16];
  static unsigned short j[16];
  CrowdArgs a;
  a.vertex_count = 4, a.instances = 2, a.bones = 3;
  a.positions = f, a.joints = j, a.weights = f, a.palettes = f, a.out_positions = f;
  return a;
}

std::string error_of(const CrowdArgs& a) {
  try {
    launch_crowd_skinning(a);
  } catch (const CudaError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST_CASE("a crowd launch with inconsistent arguments throws before touching the device") {
  CrowdArgs a = valid_args();
  a.bones = 0;
  CHECK_THAT(error_of(a), Catch::Contains("0 bones per instance"));
  a.bones = kMaxBones + 1;
  CHECK_THAT(error_of(a), Catch::Contains("257 bones per instance"));
  a = valid_args();
  a.vertex_count = std::size_t{1} << 33;
  CHECK_THAT(error_of(a), Catch::Contains("2^32"));
  for (int which = 0; which < 5; ++which) {
    a = valid_args();
    if (which == 0) a.positions = nullptr;
    if (which == 1) a.joints = nullptr;
    if (which == 2) a.weights = nullptr;
    if (which == 3) a.palettes = nullptr;
    if (which == 4) a.out_positions = nullptr;
    CHECK_THAT(error_of(a), Catch::Contains("null"));
  }
  a = valid_args();
  a.normals = a.positions;
  CHECK_THAT(error_of(a), Catch::Contains("normals without output normals"));
  // Nothing to do is not an error and launches nothing.
  a = valid_args();
  a.instances = 0;
  CHECK(error_of(a).empty());
}

TEST_CASE("bytes per vertex of the standard and compact layouts") {
  CrowdArgs a = valid_args();
  CHECK(bytes_per_vertex(a) == 48);  // 12 position in + 8 joints + 16 weights + 12 position out
  a.joint_format = JointFormat::u8x4, a.weight_format = WeightFormat::unorm16x4;
  CHECK(bytes_per_vertex(a) == 36);
  a.normals = a.positions;
  CHECK(bytes_per_vertex(a) == 60);  // + 12 normal in + 12 normal out
}

TEST_CASE("palettes are packed in the layout the kernels read (cga::append_packed_palette)") {
  const std::vector<Transform> xs = make_random_transforms(5, 77u, 1.0f);
  std::vector<glm::mat3x4> mats;
  std::vector<glm::dualquat> dqs;
  std::vector<Motor> motors;
  for (const Transform& x : xs) {
    mats.push_back(to_skinning_matrix(x));
    dqs.push_back(to_dual_quat(x));
    motors.push_back(motor_from_transform(x));
  }
  for (SkinningMethod m : kAllSkinningMethods) {
    std::vector<float> out{42.0f};  // appends after what is there
    append_packed_palette(m, mats, dqs, motors, out);
    REQUIRE(out.size() == 1 + xs.size() * palette_floats(m));
    CHECK(out[0] == 42.0f);
    for (std::size_t b = 0; b < xs.size(); ++b) {
      const float* e = out.data() + 1 + b * palette_floats(m);
      if (m == SkinningMethod::lbs) {
        for (int r = 0; r < 3; ++r)
          for (int c = 0; c < 4; ++c) CHECK(e[4 * r + c] == mats[b][r][c]);
      } else if (m == SkinningMethod::dqs) {
        const glm::dualquat& q = dqs[b];
        const float want[8] = {q.real.x, q.real.y, q.real.z, q.real.w, q.dual.x, q.dual.y, q.dual.z, q.dual.w};
        for (int k = 0; k < 8; ++k) CHECK(e[k] == want[k]);
      } else {
        for (int k = 0; k < 12; ++k) CHECK(e[k] == motors[b].c[k]);
      }
    }
  }
}

TEST_CASE("the shared palette copies: every (unit, copy) has its own slot, each copy in its own bank groups") {
  for (const std::size_t bones : {std::size_t{1}, std::size_t{3}, std::size_t{64}, std::size_t{100}, kMaxBones})
    for (SkinningMethod m : kAllSkinningMethods) {
      const PaletteLayout layout = palette_layout(m, bones);
      INFO(to_string(m) << ", " << bones << " bones: " << layout.copies << " copies, " << layout.shared_bytes << " B");
      CHECK(layout.shared_bytes <= cuda::detail::kPaletteSharedBudget);
      unsigned shift = 0;
      while ((1u << shift) < layout.copies) ++shift;
      const unsigned units = cuda::detail::palette_units(static_cast<int>(m));
      const unsigned total = static_cast<unsigned>(bones) * units;
      CHECK(std::size_t(cuda::detail::palette_slots(total, shift)) * 16 == layout.shared_bytes);
      std::vector<int> used(layout.shared_bytes / 16, 0);
      for (unsigned u = 0; u < total; ++u)
        for (unsigned c = 0; c < layout.copies; ++c) {
          const unsigned s = cuda::detail::palette_slot(u, c, shift);
          REQUIRE(s < used.size());
          CHECK(used[s]++ == 0);
          CHECK(cuda::detail::palette_unit_of_slot(s, shift) == u);  // what the staging loop stores there
          // Copy c lives in bank groups [c * 8 / copies, (c + 1) * 8 / copies).
          CHECK(s % 8 / (8 / layout.copies) == c);
        }
    }
  CHECK(palette_layout(SkinningMethod::lbs, 64).copies == 8);   // 3 KiB x 8 = 24 KiB
  CHECK(palette_layout(SkinningMethod::dqs, 64).copies == 8);   // 2 KiB x 8
  CHECK(palette_layout(SkinningMethod::lbs, 128).copies == 4);  // 6 KiB x 4
  CHECK(palette_layout(SkinningMethod::lbs, kMaxBones).copies == 2);
}

TEST_CASE("modelled wavefronts of the palette reads: 8 copies take the minimum on random joints") {
  const SkinnedMesh random = make_random_skinned_mesh(4096, 64, 1234u);
  const SkinnedMesh coherent = make_coherent_skinned_mesh(4096, 64, 1234u);
  for (SkinningMethod m : kAllSkinningMethods) {
    const PaletteLayout copies = palette_layout(m, 64), one{1, 64 * palette_floats(m) * 4};
    const double random_one = modelled_palette_wavefronts(one, m, random.joints);
    const double random_copies = modelled_palette_wavefronts(copies, m, random.joints);
    const double coherent_one = modelled_palette_wavefronts(one, m, coherent.joints);
    const double coherent_copies = modelled_palette_wavefronts(copies, m, coherent.joints);
    INFO(to_string(m) << ": random " << random_one << " -> " << random_copies << ", coherent " << coherent_one
                      << " -> " << coherent_copies);
    CHECK(random_one > 8.0);        // Nsight Compute on an H200, lbs: 9.3
    CHECK(random_copies == 4.0);    // one wavefront per quarter warp: the 128-bit minimum
    CHECK(coherent_one >= 4.0);
    CHECK(coherent_one < 5.0);
    CHECK(coherent_copies == 4.0);
  }
  // One warp, all lanes on one joint: a broadcast, one wavefront per quarter warp in either layout.
  const std::vector<std::array<std::uint16_t, 4>> same(32, {5, 5, 5, 5});
  CHECK(modelled_palette_wavefronts(palette_layout(SkinningMethod::lbs, 64), SkinningMethod::lbs, same) == 4.0);
  CHECK(modelled_palette_wavefronts(PaletteLayout{1, 3072}, SkinningMethod::lbs, same) == 4.0);
}
