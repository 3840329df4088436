// The batch path of CPU skinning (every method's generated SIMD batch kernels, a vector of lanes per step, on
// every instruction set of the build and the CPU; remainders and block edges) against the generated scalar
// loop and against a plain per-vertex reference, for vertex counts around the vector (4, 8, 16) and block
// (256) sizes.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include "cga/runtime/motor.hpp"
#include "cga/runtime/simd_targets.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

namespace {

using namespace cga;

struct Palettes {
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
  MotorPalette motors;
};

Palettes make_palettes(const std::vector<Transform>& xs) {
  Palettes p;
  for (const Transform& x : xs) {
    p.matrices.push_back(to_skinning_matrix(x));
    Transform rigid = x;  // dqs holds no scale: its palette is the rigid part
    rigid.scale = 1.0f;
    p.dual_quats.push_back(to_dual_quat(rigid));
    p.motors.push_back(motor_from_transform(x));
  }
  return p;
}

SkinnedOutput skin(SkinningMethod method, const SkinnedMesh& mesh, const Palettes& pal, bool simd) {
  SkinnedOutput out;
  SkinningJob job = make_skinning_job(method, mesh, out);
  job.matrices = pal.matrices;
  job.dual_quats = pal.dual_quats;
  job.motors = pal.motors;
  job.use_simd = simd;
  REQUIRE(job.Run());
  return out;
}

// p' = sum_k w_k (s R p + t) with GLM, one vertex at a time.
glm::vec3 reference_lbs(const SkinnedMesh& mesh, const std::vector<Transform>& xs, std::size_t i) {
  glm::vec3 sum(0.0f);
  const glm::vec3 p(mesh.px[i], mesh.py[i], mesh.pz[i]);
  for (int k = 0; k < 4; ++k) {
    const Transform& x = xs[mesh.joints[i][k]];
    sum += mesh.weights[i][k] * (x.scale * (x.rotation * p) + x.translation);
  }
  return sum;
}

}  // namespace

TEST_CASE("the batch path and the scalar loop agree at every remainder and block edge", "[skinning][simd]") {
  const std::vector<Transform> rigid = make_random_transforms(24, 41, 2.0f);
  const std::vector<Transform> scaled = make_random_transforms(24, 42, 2.0f, 0.5f);
  const Palettes pal_rigid = make_palettes(rigid);
  const Palettes pal_scaled = make_palettes(scaled);
  const float size = 3.0f * std::exp(0.5f);
  std::vector<std::size_t> counts;
  for (std::size_t n = 1; n <= 17; ++n) counts.push_back(n);
  for (std::size_t n : {255u, 256u, 257u, 263u, 520u, 600u}) counts.push_back(n);
  const std::vector<SimdTarget> targets = simd_targets();
  REQUIRE(!targets.empty());
  for (const std::size_t n : counts) {
    INFO(n << " vertices");
    SkinnedMesh mesh = make_random_skinned_mesh(n, 24, static_cast<std::uint32_t>(1000 + n));
    for (const bool normals : {true, false}) {
      INFO((normals ? "with normals" : "positions only"));
      if (!normals) {
        mesh.nx.clear();
        mesh.ny.clear();
        mesh.nz.clear();
      }
      for (const Palettes* pal : std::array<const Palettes*, 2>{&pal_rigid, &pal_scaled}) {
        for (SkinningMethod method : kAllSkinningMethods) {
          INFO(to_string(method));
          const SkinnedOutput portable = skin(method, mesh, *pal, false);
          for (const SimdTarget& target : targets) {
            INFO(target.name);
            const ScopedSimdTarget pin(target);
            const SkinnedOutput got = skin(method, mesh, *pal, true);
            for (std::size_t i = 0; i < n; ++i) {
              REQUIRE(std::hypot(got.px[i] - portable.px[i], got.py[i] - portable.py[i],
                                 got.pz[i] - portable.pz[i]) <= 1e-5f * size);
              if (normals) {
                REQUIRE(std::hypot(got.nx[i] - portable.nx[i], got.ny[i] - portable.ny[i],
                                   got.nz[i] - portable.nz[i]) <= 1e-5f);
                REQUIRE(std::hypot(got.nx[i], got.ny[i], got.nz[i]) == Approx(1.0f).margin(1e-5));
              }
            }
          }
          if (method == SkinningMethod::lbs || method == SkinningMethod::cga_points) {
            const SkinnedOutput simd = skin(method, mesh, *pal, true);
            const std::vector<Transform>& xs = pal == &pal_rigid ? rigid : scaled;
            for (std::size_t i = 0; i < n; ++i) {
              const glm::vec3 want = reference_lbs(mesh, xs, i);
              REQUIRE(std::hypot(simd.px[i] - want.x, simd.py[i] - want.y, simd.pz[i] - want.z) <= 1e-5f * size);
            }
          }
        }
      }
    }
  }
}

TEST_CASE("the motor methods skin a palette with every other motor negated to the same vertices", "[skinning][simd]") {
  // M and -M are the same similarity: the blends' sign fix (a select in the scripts) must make the batch
  // kernels blind to the sign. Half of each vertex's pairs need the fix, so a missing or wrong one would
  // misplace most vertices.
  const std::vector<Transform> xs = make_random_transforms(24, 43, 2.0f, 0.5f);
  const Palettes pal = make_palettes(xs);
  Palettes negated = pal;
  for (std::size_t e = 1; e < negated.motors.size(); e += 2)
    for (float& c : negated.motors[e].c) c = -c;
  const SkinnedMesh mesh = make_random_skinned_mesh(600, 24, 4242u);
  const float size = 3.0f * std::exp(0.5f);
  for (SkinningMethod method : kAllSkinningMethods) {
    if (skinning_method_info(method).palette != PaletteKind::motors) continue;
    for (const SimdTarget& target : simd_targets()) {
      CAPTURE(to_string(method), target.name);
      const ScopedSimdTarget pin(target);
      const SkinnedOutput want = skin(method, mesh, pal, true);
      const SkinnedOutput got = skin(method, mesh, negated, true);
      std::size_t bad = 0;
      for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
        bad += !(std::hypot(got.px[i] - want.px[i], got.py[i] - want.py[i], got.pz[i] - want.pz[i]) <= 1e-5f * size &&
                 std::hypot(got.nx[i] - want.nx[i], got.ny[i] - want.ny[i], got.nz[i] - want.nz[i]) <= 1e-5f);
      CHECK(bad == 0);
    }
  }
}

TEST_CASE("pinning an instruction set the build or the CPU lacks is refused", "[skinning][simd]") {
  CHECK_THROWS_WITH(ScopedSimdTarget(SimdTarget{0, "none"}),
                    Catch::Contains("not an instruction set of this build and CPU"));
}

TEST_CASE("large meshes skin as the scalar loop, aligned outputs or not", "[skinning][simd]") {
  // 2^17 + 13 vertices: many blocks, the prefetches ahead reaching past the arrays, and a remainder.
  const std::size_t n = (std::size_t{1} << 17) + 13;
  const SkinnedMesh mesh = make_random_skinned_mesh(n, 64, 71);
  const Palettes pal = make_palettes(make_random_transforms(64, 72, 2.0f, 0.3f));
  const float size = 3.0f * std::exp(0.3f);
  for (SkinningMethod method : kAllSkinningMethods) {
    INFO(to_string(method));
    const SkinnedOutput portable = skin(method, mesh, pal, false);
    for (const std::size_t offset : {0u, 1u}) {
      INFO("outputs offset by " << offset << " floats from the allocation");  // 1: not 16-byte aligned
      std::vector<float> buf(6 * (n + 1), -7.0f);
      SkinnedOutput unused;
      SkinningJob job = make_skinning_job(method, mesh, unused);
      job.matrices = pal.matrices;
      job.dual_quats = pal.dual_quats;
      job.motors = pal.motors;
      std::span<float>* outs[6] = {&job.out_px, &job.out_py, &job.out_pz, &job.out_nx, &job.out_ny, &job.out_nz};
      for (int k = 0; k < 6; ++k) *outs[k] = std::span<float>(buf.data() + k * (n + 1) + offset, n);
      REQUIRE(job.Run());
      double worst_p = 0.0, worst_n = 0.0;
      for (std::size_t i = 0; i < n; ++i) {
        worst_p = std::max<double>(worst_p, std::hypot(job.out_px[i] - portable.px[i], job.out_py[i] - portable.py[i],
                                                       job.out_pz[i] - portable.pz[i]));
        worst_n = std::max<double>(worst_n, std::hypot(job.out_nx[i] - portable.nx[i], job.out_ny[i] - portable.ny[i],
                                                       job.out_nz[i] - portable.nz[i]));
      }
      REQUIRE(worst_p <= 1e-5 * size);
      REQUIRE(worst_n <= 1e-5);
      if (offset == 0)
        for (int k = 0; k < 6; ++k) REQUIRE(buf[k * (n + 1) + n] == -7.0f);  // nothing written past the end
    }
  }
}

TEST_CASE("the batch path leaves outputs past the vertex count alone", "[skinning][simd]") {
  const Palettes pal = make_palettes(make_random_transforms(8, 51, 1.0f));
  const SkinnedMesh mesh = make_random_skinned_mesh(13, 8, 52);
  for (SkinningMethod method : kAllSkinningMethods) {
    INFO(to_string(method));
    // Outputs are views into longer arrays whose tails hold a sentinel.
    std::vector<float> buf(6 * 24, -7.0f);
    SkinnedOutput unused;
    SkinningJob job = make_skinning_job(method, mesh, unused);
    job.matrices = pal.matrices;
    job.dual_quats = pal.dual_quats;
    job.motors = pal.motors;
    float* base = buf.data();
    job.out_px = {base, 13};
    job.out_py = {base + 24, 13};
    job.out_pz = {base + 48, 13};
    job.out_nx = {base + 72, 13};
    job.out_ny = {base + 96, 13};
    job.out_nz = {base + 120, 13};
    REQUIRE(job.Run());
    for (int s = 0; s < 6; ++s)
      for (std::size_t i = 13; i < 24; ++i) REQUIRE(buf[24 * s + i] == -7.0f);
  }
}

TEST_CASE("Run refuses a bad joint index or weight in any block, on the batch path and the scalar loop", "[skinning][simd]") {
  // The check runs inside each block function (integer max reductions over the block's joints and weight
  // exponents): a bad value at a block's first or last vertex, in any slot, in the first, a middle or the
  // last (partial) block must stop Run(); blocks before it may be written.
  const Palettes pal = make_palettes(make_random_transforms(24, 61, 1.0f));
  const SkinnedMesh good = make_random_skinned_mesh(700, 24, 62);
  const float inf = std::numeric_limits<float>::infinity();
  for (SkinningMethod method : kAllSkinningMethods)
    for (const bool simd : {true, false}) {
      INFO(to_string(method) << (simd ? " simd" : " portable"));
      SkinnedOutput out;
      SkinningJob job = make_skinning_job(method, good, out);
      job.matrices = pal.matrices;
      job.dual_quats = pal.dual_quats;
      job.motors = pal.motors;
      job.use_simd = simd;
      REQUIRE(job.Run());
      for (std::size_t i : {0u, 7u, 255u, 256u, 300u, 511u, 512u, 699u})
        for (int k = 0; k < 4; ++k) {
          INFO("vertex " << i << " slot " << k);
          for (std::uint16_t joint : {std::uint16_t{24}, std::uint16_t{255}, std::uint16_t{65535}}) {
            SkinnedMesh bad = good;
            bad.joints[i][k] = joint;
            job.joints = bad.joints;
            job.weights = good.weights;
            CHECK_FALSE(job.Run());
          }
          for (float w : {std::numeric_limits<float>::quiet_NaN(), -std::numeric_limits<float>::quiet_NaN(), inf, -inf}) {
            SkinnedMesh bad = good;
            bad.weights[i][k] = w;
            job.joints = good.joints;
            job.weights = bad.weights;
            CHECK_FALSE(job.Run());
          }
          // The largest finite weight and the largest valid joint index pass Run() (Validate() rejects the
          // weight: its sum is not 1).
          SkinnedMesh edge = good;
          edge.weights[i][k] = std::numeric_limits<float>::max();
          edge.joints[i][k] = 23;
          job.joints = edge.joints;
          job.weights = edge.weights;
          CHECK(job.Run());
        }
    }
}

TEST_CASE("a zero normal skins to 0 and a huge or tiny one to a unit vector on every path", "[skinning][simd]") {
  // The batch path renormalizes from a reciprocal square root estimate and one Newton step on x86 (batch.cpp,
  // inv_length) where the scalar loop divides by the square root: both must give 0, not NaN, for a zero
  // normal, and a unit vector for normals far from unit length. 1000 vertices: whole vectors in several
  // blocks, and a tail.
  const std::vector<Transform> xs = make_random_transforms(24, 43, 2.0f, 0.5f);
  const Palettes pal = make_palettes(xs);
  SkinnedMesh mesh = make_random_skinned_mesh(1000, 24, 44u);
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const float scale = i % 3 == 0 ? 0.0f : i % 3 == 1 ? 1e15f : 1e-12f;
    mesh.nx[i] *= scale, mesh.ny[i] *= scale, mesh.nz[i] *= scale;
  }
  const auto check = [&](SkinningMethod method, bool simd) {
    const SkinnedOutput got = skin(method, mesh, pal, simd);
    std::size_t bad = 0;
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      const float len = std::hypot(got.nx[i], got.ny[i], got.nz[i]);
      bad += i % 3 == 0 ? !(got.nx[i] == 0.0f && got.ny[i] == 0.0f && got.nz[i] == 0.0f)
                        : !(std::abs(len - 1.0f) <= 1e-5f);
    }
    CHECK(bad == 0);
  };
  for (SkinningMethod method : kAllSkinningMethods) {
    CAPTURE(to_string(method));
    check(method, false);
    for (const SimdTarget& target : simd_targets()) {
      CAPTURE(target.name);
      const ScopedSimdTarget pin(target);
      check(method, true);
    }
  }
}

TEST_CASE("batch normals agree with the scalar loop within 1e-6 and are unit within 1e-6", "[skinning][simd]") {
  // The bound docs/skinning.md states for the reciprocal square root step of the batch renormalization
  // (batch.cpp, inv_length), on every method and instruction set.
  const std::vector<Transform> xs = make_random_transforms(24, 45, 2.0f, 0.5f);
  const Palettes pal = make_palettes(xs);
  const SkinnedMesh mesh = make_random_skinned_mesh(1000, 24, 46u);
  for (SkinningMethod method : kAllSkinningMethods) {
    const SkinnedOutput portable = skin(method, mesh, pal, false);
    for (const SimdTarget& target : simd_targets()) {
      CAPTURE(to_string(method), target.name);
      const ScopedSimdTarget pin(target);
      const SkinnedOutput simd = skin(method, mesh, pal, true);
      double worst_diff = 0.0, worst_unit = 0.0;
      for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
        worst_diff = std::max<double>(worst_diff, std::hypot(simd.nx[i] - portable.nx[i], simd.ny[i] - portable.ny[i],
                                                             simd.nz[i] - portable.nz[i]));
        worst_unit = std::max<double>(worst_unit, std::abs(std::hypot(simd.nx[i], simd.ny[i], simd.nz[i]) - 1.0f));
      }
      CAPTURE(worst_diff, worst_unit);
      CHECK(worst_diff <= 1e-6);
      CHECK(worst_unit <= 1e-6);
    }
  }
}
