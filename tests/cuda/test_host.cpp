// cga::cuda's host side without a GPU: a launch with inconsistent arguments throws CudaError naming the
// problem before any CUDA call; bytes per vertex of the layouts the benchmark reports; the prepared palette
// the kernels read (entry b = the method's per-bone kernel on bone b, prepared_entry_floats each); the
// kernels' own code (staging into the shared-memory copies, gathers, generated blends) run on the host
// against the CPU SkinningJob for every method of the table; the shared-memory palette copies (kernels.hpp)
// and the bank model that predicts their wavefronts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
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

TEST_CASE("the kernels read the prepared palette: entry b is bone b's prepared entry (cga::append_packed_palette)") {
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
    INFO(to_string(m));
    // The kernels stage palette_units 16-B units per entry and index entry j at unit j * units.
    const std::size_t floats = palette_floats(m);
    CHECK(floats == prepared_entry_floats(m));
    CHECK(floats == 4 * cuda::detail::palette_units(static_cast<int>(m)));
    std::vector<float> out{42.0f};  // appends after what is there
    append_packed_palette(m, mats, dqs, motors, out);
    REQUIRE(out.size() == 1 + xs.size() * floats);
    CHECK(out[0] == 42.0f);
    for (std::size_t b = 0; b < xs.size(); ++b) {
      // Bone b alone, prepared on its own: the same floats at entry b.
      std::vector<float> one(floats, -1.0f);
      prepare_palette(m, std::span(mats).subspan(b, 1), std::span(dqs).subspan(b, 1), std::span(motors).subspan(b, 1),
                      one);
      for (std::size_t k = 0; k < floats; ++k) CHECK(out[1 + b * floats + k] == one[k]);
    }
  }
}

namespace {

// One crowd run through the kernels' code on the host (cuda::detail::run_on_host), instance i posed by its
// own random palette and, with per-instance inputs, skinning its own random mesh; every instance is compared
// with the CPU SkinningJob on the same mesh and palette. Returns the largest position error relative to the
// CPU result's extent and the largest normal error.
struct Errors {
  double position = 0.0, normal = 0.0;
};

Errors host_run_against_cpu(SkinningMethod method, std::size_t vertices, std::size_t instances, int bones,
                            bool per_instance, bool compact, bool normals, float max_log_scale) {
  const std::size_t meshes = per_instance ? instances : 1;
  std::vector<SkinnedMesh> mesh(meshes);
  std::vector<float> positions, in_normals;
  std::vector<std::array<std::uint16_t, 4>> joints16;
  std::vector<std::array<std::uint8_t, 4>> joints8;
  std::vector<std::array<float, 4>> weights;
  std::vector<std::array<std::uint16_t, 4>> weights16;
  for (std::size_t i = 0; i < meshes; ++i) {
    mesh[i] = make_random_skinned_mesh(vertices, bones, 900u + static_cast<std::uint32_t>(i));
    for (std::size_t v = 0; v < vertices; ++v) {
      positions.insert(positions.end(), {mesh[i].px[v], mesh[i].py[v], mesh[i].pz[v]});
      in_normals.insert(in_normals.end(), {mesh[i].nx[v], mesh[i].ny[v], mesh[i].nz[v]});
      joints16.push_back(mesh[i].joints[v]);
      std::array<std::uint8_t, 4> j8{};
      std::array<std::uint16_t, 4> w16{};
      for (int k = 0; k < 4; ++k) {
        j8[k] = static_cast<std::uint8_t>(mesh[i].joints[v][k]);
        w16[k] = static_cast<std::uint16_t>(std::lround(mesh[i].weights[v][k] * 65535.0f));
        if (compact) mesh[i].weights[v][k] = w16[k] / 65535.0f;  // the CPU reference takes what the GPU reads
      }
      joints8.push_back(j8);
      weights16.push_back(w16);
      weights.push_back(mesh[i].weights[v]);
    }
  }
  std::vector<MatrixPalette> mats(instances);
  std::vector<DualQuatPalette> dqs(instances);
  std::vector<MotorPalette> motors(instances);
  std::vector<float> palettes;
  for (std::size_t i = 0; i < instances; ++i) {
    for (const Transform& x : make_random_transforms(bones, 300u + static_cast<std::uint32_t>(i), 1.0f, max_log_scale)) {
      mats[i].push_back(to_skinning_matrix(x));
      if (skinning_method_info(method).palette == PaletteKind::dual_quats) dqs[i].push_back(to_dual_quat(x));
      motors[i].push_back(motor_from_transform(x));
    }
    append_packed_palette(method, mats[i], dqs[i], motors[i], palettes);
  }
  std::vector<float> out_positions(3 * vertices * instances, NAN), out_normals(3 * vertices * instances, NAN);

  cuda::detail::LaunchArgs d;
  d.method = static_cast<int>(method);
  d.vertex_count = vertices, d.instances = instances, d.bones = static_cast<std::size_t>(bones);
  d.per_instance_inputs = per_instance;
  d.positions = positions.data(), d.normals = normals ? in_normals.data() : nullptr;
  d.joints = compact ? static_cast<const void*>(joints8.data()) : joints16.data(), d.joints_u8 = compact;
  d.weights = compact ? static_cast<const void*>(weights16.data()) : weights.data(), d.weights_unorm16 = compact;
  d.palettes = palettes.data(), d.out_positions = out_positions.data();
  d.out_normals = normals ? out_normals.data() : nullptr;
  const std::string error = cuda::detail::run_on_host(d);
  REQUIRE(error.empty());

  Errors e;
  for (std::size_t i = 0; i < instances; ++i) {
    SkinnedMesh reference = mesh[per_instance ? i : 0];
    if (!normals) reference.nx.clear(), reference.ny.clear(), reference.nz.clear();
    SkinnedOutput cpu;
    SkinningJob job = make_skinning_job(method, reference, cpu);
    job.matrices = mats[i], job.dual_quats = dqs[i], job.motors = motors[i];
    REQUIRE(job.Run());
    float lo = INFINITY, hi = -INFINITY;
    for (std::size_t v = 0; v < vertices; ++v)
      lo = std::min({lo, cpu.px[v], cpu.py[v], cpu.pz[v]}), hi = std::max({hi, cpu.px[v], cpu.py[v], cpu.pz[v]});
    const double extent = hi - lo;
    REQUIRE(extent > 0.5);
    for (std::size_t v = 0; v < vertices; ++v) {
      const float* p = out_positions.data() + 3 * (i * vertices + v);
      const double dp = std::hypot(p[0] - cpu.px[v], p[1] - cpu.py[v], p[2] - cpu.pz[v]) / extent;
      e.position = std::isfinite(dp) ? std::max(e.position, dp) : INFINITY;
      if (normals) {
        const float* n = out_normals.data() + 3 * (i * vertices + v);
        const double dn = std::hypot(n[0] - cpu.nx[v], n[1] - cpu.ny[v], n[2] - cpu.nz[v]);
        e.normal = std::isfinite(dn) ? std::max(e.normal, dn) : INFINITY;
      }
    }
  }
  return e;
}

}  // namespace

TEST_CASE("the kernels' code on the host equals the CPU SkinningJob for every method and layout") {
  // 64 bones: 8 palette copies for every method; 200: 2 copies for 3-unit entries, 4 for 2-unit ones.
  for (const int bones : {64, 200})
    for (SkinningMethod m : kAllSkinningMethods)
      for (const bool compact : {false, true})
        for (const bool normals : {false, true})
          for (const bool per_instance : {true, false}) {
            // Dual quaternions hold no scale; the other palettes are also checked with scaled bones.
            std::vector<float> max_log_scales{0.0f};
            if (skinning_method_info(m).palette != PaletteKind::dual_quats) max_log_scales.push_back(0.3f);
            for (const float max_log_scale : max_log_scales) {
              INFO(to_string(m) << ", " << bones << " bones (" << palette_layout(m, bones).copies << " copies), "
                                << (compact ? "compact" : "standard") << (normals ? ", normals" : "")
                                << (per_instance ? ", per-instance meshes" : ", one shared mesh")
                                << ", max log scale " << max_log_scale);
              const Errors e = host_run_against_cpu(m, 300, 3, bones, per_instance, compact, normals, max_log_scale);
              CHECK(e.position <= 1e-5);
              CHECK(e.normal <= 1e-5);
            }
          }
}

TEST_CASE("the kernels' host run rejects a method outside the table") {
  cuda::detail::LaunchArgs d;
  d.method = static_cast<int>(kSkinningMethodCount);
  CHECK_THAT(cuda::detail::run_on_host(d), Catch::Contains("unknown method"));
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
          // The kernels add a thread's copy once: the slot is the unit's slot in copy 0 plus the copy's offset.
          CHECK(s == cuda::detail::palette_slot(u, 0, shift) + cuda::detail::palette_slot(0, c, shift));
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
  // (Every method whose 64-bone palette fits 8 copies; a larger entry gets fewer copies, see below.)
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
    CHECK(coherent_one >= 4.0);
    CHECK(coherent_one < 5.0);
    if (copies.copies == 8) {
      CHECK(random_copies == 4.0);  // one wavefront per quarter warp: the 128-bit minimum
      CHECK(coherent_copies == 4.0);
    } else {
      // An entry too large for 8 copies of 64 bones in the shared budget (cga-log's 4 vec4s: 4 copies) still
      // gains from its copies on random joints.
      INFO(copies.copies << " copies");
      CHECK(copies.copies >= 4);
      CHECK(random_copies < random_one);
    }
  }
  // One warp, all lanes on one joint: a broadcast, one wavefront per quarter warp in either layout.
  const std::vector<std::array<std::uint16_t, 4>> same(32, {5, 5, 5, 5});
  CHECK(modelled_palette_wavefronts(palette_layout(SkinningMethod::lbs, 64), SkinningMethod::lbs, same) == 4.0);
  CHECK(modelled_palette_wavefronts(PaletteLayout{1, 3072}, SkinningMethod::lbs, same) == 4.0);
}
