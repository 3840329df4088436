// The SIMD skinning paths (the hand-written loops, 8 vertices per step, and every method's generated batch
// kernels, a vector of lanes per step; remainders and block edges) against the portable loop and against a
// plain per-vertex reference, for vertex counts around the step (8, 16) and block (256) sizes.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

#include <catch2/catch.hpp>

#include "cga/runtime/motor.hpp"
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

SkinnedOutput skin(SkinningMethod method, const SkinnedMesh& mesh, const Palettes& pal, bool simd,
                   bool avx512 = true, bool hand_loops = true) {
  SkinnedOutput out;
  SkinningJob job = make_skinning_job(method, mesh, out);
  job.matrices = pal.matrices;
  job.dual_quats = pal.dual_quats;
  job.motors = pal.motors;
  job.use_simd = simd;
  job.use_avx512 = avx512;
  job.use_hand_loops = hand_loops;
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

TEST_CASE("SIMD and portable skinning loops agree at every remainder and block edge", "[skinning][simd]") {
  const std::vector<Transform> rigid = make_random_transforms(24, 41, 2.0f);
  const std::vector<Transform> scaled = make_random_transforms(24, 42, 2.0f, 0.5f);
  const Palettes pal_rigid = make_palettes(rigid);
  const Palettes pal_scaled = make_palettes(scaled);
  const float size = 3.0f * std::exp(0.5f);
  std::vector<std::size_t> counts;
  for (std::size_t n = 1; n <= 17; ++n) counts.push_back(n);
  // 600 >= 24^2: cga-motors takes its pair-sign table (SkinningJob::Run) there.
  for (std::size_t n : {255u, 256u, 257u, 263u, 520u, 600u}) counts.push_back(n);
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
          const SkinnedOutput simd = skin(method, mesh, *pal, true);
          // The widest loops the CPU has, the AVX2 ones (the same on a CPU without AVX-512), and the batch
          // kernels (what every method without a hand-written loop runs).
          for (const int path : {0, 1, 2}) {
            INFO((path == 0 ? "widest SIMD loops" : path == 1 ? "AVX2 loops" : "batch kernels"));
            const SkinnedOutput got = path == 0   ? simd
                                      : path == 1 ? skin(method, mesh, *pal, true, false)
                                                  : skin(method, mesh, *pal, true, true, false);
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

TEST_CASE("cga-motors' pair-sign table gives the bits of the per-vertex rotor dot products", "[skinning][simd]") {
  // Run() builds the table when palette^2 <= vertex count: 600 vertices with 24 joints do (576), their first
  // 560 do not. 560 is 70 groups of 8 and 35 of 16, so both runs cut those vertices into the same SIMD groups
  // on AVX2 and on AVX-512 (a partial group takes the scalar tail, whose rounding differs). Every other motor is negated (the same similarity), so
  // half the pairs need the sign fix and a wrong table would misplace those vertices.
  const std::vector<Transform> xs = make_random_transforms(24, 43, 2.0f, 0.5f);
  Palettes pal = make_palettes(xs);
  for (std::size_t e = 1; e < pal.motors.size(); e += 2)
    for (float& c : pal.motors[e].c) c = -c;
  const SkinnedMesh mesh = make_random_skinned_mesh(600, 24, 4242u);
  SkinnedMesh head = mesh;
  constexpr std::size_t kHead = 560;
  for (auto* v : {&head.px, &head.py, &head.pz, &head.nx, &head.ny, &head.nz}) v->resize(kHead);
  head.joints.resize(kHead);
  head.weights.resize(kHead);
  for (const bool avx512 : {true, false}) {
    const SkinnedOutput with_table = skin(SkinningMethod::cga_motors, mesh, pal, true, avx512);
    const SkinnedOutput without = skin(SkinningMethod::cga_motors, head, pal, true, avx512);
    const SkinnedOutput portable = skin(SkinningMethod::cga_motors, mesh, pal, false);
    std::size_t differ = 0;
    for (std::size_t i = 0; i < kHead; ++i)
      differ += with_table.px[i] != without.px[i] || with_table.py[i] != without.py[i] ||
                with_table.pz[i] != without.pz[i] || with_table.nx[i] != without.nx[i] ||
                with_table.ny[i] != without.ny[i] || with_table.nz[i] != without.nz[i];
    CHECK(differ == 0);
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i)
      REQUIRE(std::hypot(with_table.px[i] - portable.px[i], with_table.py[i] - portable.py[i],
                         with_table.pz[i] - portable.pz[i]) <= 1e-5f * 3.0f * std::exp(0.5f));
  }
}

TEST_CASE("large meshes (prefetching) skin as the portable loops, aligned outputs or not", "[skinning][simd]") {
  // 2^17 + 13 vertices: past the size from which the SIMD loops prefetch their inputs, with a remainder.
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
      job.use_hand_loops = offset == 0;  // the batch kernels of every method too
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

TEST_CASE("the SIMD loops leave outputs past the vertex count alone", "[skinning][simd]") {
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

TEST_CASE("Run refuses a bad joint index or weight in any block, on the SIMD and the portable loops", "[skinning][simd]") {
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

TEST_CASE("a zero normal skins to 0 and a huge or tiny one to a unit vector on every loop", "[skinning][simd]") {
  // The SIMD loops renormalize from a reciprocal square root estimate (avx2.cpp, inv_length8) where the
  // portable ones divide by the square root: both must give 0, not NaN, for a zero normal, and a unit vector
  // for normals far from unit length. 1000 vertices: whole groups of 8 in several blocks, and a tail.
  const std::vector<Transform> xs = make_random_transforms(24, 43, 2.0f, 0.5f);
  const Palettes pal = make_palettes(xs);
  SkinnedMesh mesh = make_random_skinned_mesh(1000, 24, 44u);
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const float scale = i % 3 == 0 ? 0.0f : i % 3 == 1 ? 1e15f : 1e-12f;
    mesh.nx[i] *= scale, mesh.ny[i] *= scale, mesh.nz[i] *= scale;
  }
  for (SkinningMethod method : kAllSkinningMethods)
    for (const bool simd : {false, true})
      for (const bool avx512 : {false, true}) {
        CAPTURE(to_string(method), simd, avx512);
        const SkinnedOutput got = skin(method, mesh, pal, simd, avx512);
        std::size_t bad = 0;
        for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
          const float len = std::hypot(got.nx[i], got.ny[i], got.nz[i]);
          bad += i % 3 == 0 ? !(got.nx[i] == 0.0f && got.ny[i] == 0.0f && got.nz[i] == 0.0f)
                            : !(std::abs(len - 1.0f) <= 1e-5f);
        }
        CHECK(bad == 0);
      }
}

TEST_CASE("SIMD normals agree with the portable loops within 1e-6 and are unit within 1e-6", "[skinning][simd]") {
  // The bound docs/skinning.md states for the reciprocal square root step of the SIMD renormalization
  // (avx2.cpp, inv_length8), on the methods that renormalize a blended linear part.
  const std::vector<Transform> xs = make_random_transforms(24, 45, 2.0f, 0.5f);
  const Palettes pal = make_palettes(xs);
  const SkinnedMesh mesh = make_random_skinned_mesh(1000, 24, 46u);
  for (SkinningMethod method : {SkinningMethod::lbs, SkinningMethod::cga_points, SkinningMethod::cga_motors}) {
    CAPTURE(to_string(method));
    const SkinnedOutput portable = skin(method, mesh, pal, false);
    const SkinnedOutput simd = skin(method, mesh, pal, true, false);
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
