// SkinningJob on strided streams (ozz's in_positions_stride): an interleaved vertex buffer (position, normal
// and a texture coordinate per vertex, 8 floats) skinned in place of the packed streams gives bit-identical
// results to the packed run with every method, on the scalar loop and every instruction set of the batch
// path, including a partial last block, with x y z as triples and with x, y, z apart, and so
// does a 48-byte engine vertex with its joints and weights interleaved too; the size rules for strided spans
// are checked with clear errors.
#include <catch2/catch.hpp>

#include <array>
#include <cstring>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "cga/runtime/simd_targets.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;

namespace {

constexpr std::size_t kStride = 8;  // x y z nx ny nz u v, or x nx y ny z nz u v

struct Interleaved {
  std::vector<float> in, out;
  // Float offsets of px py pz nx ny nz in a vertex.
  std::array<std::size_t, 6> at;
};

Interleaved interleave(const SkinnedMesh& mesh, bool triples) {
  Interleaved b;
  b.at = triples ? std::array<std::size_t, 6>{0, 1, 2, 3, 4, 5} : std::array<std::size_t, 6>{0, 2, 4, 1, 3, 5};
  const std::size_t n = mesh.vertex_count();
  b.in.assign(kStride * n, 0.0f);
  b.out.assign(kStride * n, -7.0f);  // the u v slots must keep this
  for (std::size_t i = 0; i < n; ++i) {
    float* v = b.in.data() + kStride * i;
    v[b.at[0]] = mesh.px[i], v[b.at[1]] = mesh.py[i], v[b.at[2]] = mesh.pz[i];
    v[b.at[3]] = mesh.nx[i], v[b.at[4]] = mesh.ny[i], v[b.at[5]] = mesh.nz[i];
    v[6] = 0.25f, v[7] = 0.75f;
  }
  return b;
}

// The job over the interleaved buffers: attribute k at buf + b.at[k], stride 8.
SkinningJob strided_job(SkinningMethod method, const SkinnedMesh& mesh, Interleaved& b, bool normals) {
  SkinningJob job;
  job.method = method;
  const std::span<const float> in(b.in);
  const std::span<float> out(b.out);
  const auto& at = b.at;
  job.in_px = in.subspan(at[0]), job.in_py = in.subspan(at[1]), job.in_pz = in.subspan(at[2]);
  job.out_px = out.subspan(at[0]), job.out_py = out.subspan(at[1]), job.out_pz = out.subspan(at[2]);
  if (normals) {
    job.in_nx = in.subspan(at[3]), job.in_ny = in.subspan(at[4]), job.in_nz = in.subspan(at[5]);
    job.out_nx = out.subspan(at[3]), job.out_ny = out.subspan(at[4]), job.out_nz = out.subspan(at[5]);
  }
  job.in_positions_stride = job.in_normals_stride = kStride;
  job.out_positions_stride = job.out_normals_stride = kStride;
  job.joints = mesh.joints;
  job.weights = mesh.weights;
  return job;
}

// Path 0: the scalar loop; path k > 0: the batch path pinned to the k-th instruction set of simd_targets().
struct Pin {
  std::string name = "scalar loop";
  std::optional<ScopedSimdTarget> scope;
  explicit Pin(int path) {
    if (path == 0) return;
    const SimdTarget t = simd_targets()[static_cast<std::size_t>(path - 1)];
    name = t.name;
    scope.emplace(t);
  }
};

void set_palette(SkinningJob& job, const MatrixPalette& m, const DualQuatPalette& d, const MotorPalette& q) {
  job.matrices = m, job.dual_quats = d, job.motors = q;
}

}  // namespace

TEST_CASE("an interleaved vertex buffer skins exactly as the packed streams do", "[skinning][strided]") {
  // 1003 vertices: three whole blocks of 256 and a partial one, whose last 3 vertices are no whole vector of
  // 4, 8 or 16 lanes; 503: one whole block and a partial one.
  const std::size_t count = GENERATE(1003u, 503u);
  const bool triples = GENERATE(true, false);
  const SkinnedMesh mesh = make_random_skinned_mesh(count, 24, 77u);
  const RandomPalettes pal = make_random_palettes(24, 1, 5u);
  for (SkinningMethod method : kAllSkinningMethods)
    for (bool normals : {false, true})
      for (int path = 0; path <= static_cast<int>(simd_targets().size()); ++path) {
        const Pin pin(path);
        CAPTURE(to_string(method), normals, pin.name, triples);
        SkinnedOutput packed;
        SkinningJob a = make_skinning_job(method, mesh, packed);
        if (!normals) a.in_nx = a.in_ny = a.in_nz = {}, a.out_nx = a.out_ny = a.out_nz = {};
        set_palette(a, pal.matrices[0], pal.dual_quats[0], pal.motors[0]);
        a.use_simd = path > 0;
        REQUIRE(a.ValidationError() == "");
        REQUIRE(a.Run());

        Interleaved buf = interleave(mesh, triples);
        SkinningJob b = strided_job(method, mesh, buf, normals);
        set_palette(b, pal.matrices[0], pal.dual_quats[0], pal.motors[0]);
        b.use_simd = a.use_simd;
        REQUIRE(b.vertex_count() == mesh.vertex_count());
        REQUIRE(b.ValidationError() == "");
        REQUIRE(b.Run());

        std::size_t mismatches = 0;
        for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
          const float* v = buf.out.data() + kStride * i;
          const auto& at = buf.at;
          const float got[6] = {v[at[0]], v[at[1]], v[at[2]], v[at[3]], v[at[4]], v[at[5]]};
          const float want[3] = {packed.px[i], packed.py[i], packed.pz[i]};
          mismatches += std::memcmp(got, want, sizeof want) != 0;
          if (normals) {
            const float nwant[3] = {packed.nx[i], packed.ny[i], packed.nz[i]};
            mismatches += std::memcmp(got + 3, nwant, sizeof nwant) != 0;
          } else {
            mismatches += got[3] != -7.0f || got[4] != -7.0f || got[5] != -7.0f;
          }
          mismatches += v[6] != -7.0f || v[7] != -7.0f;  // other attributes untouched
        }
        CHECK(mismatches == 0);
      }
}

TEST_CASE("strided spans must cover the vertex count at their stride", "[skinning][strided][bad-input]") {
  const SkinnedMesh mesh = make_random_skinned_mesh(10, 4, 3u);
  const RandomPalettes pal = make_random_palettes(4, 1, 1u);
  Interleaved buf = interleave(mesh, true);
  SkinningJob job = strided_job(SkinningMethod::cga_motors, mesh, buf, true);
  set_palette(job, pal.matrices[0], pal.dual_quats[0], pal.motors[0]);
  REQUIRE(job.Validate());

  SECTION("a zero stride") {
    job.in_positions_stride = 0;
    CHECK_THAT(job.ValidationError(), Catch::Contains("stride is 0"));
    CHECK_FALSE(job.Run());
  }
  SECTION("an input span one float short") {
    job.in_pz = job.in_pz.first(9 * kStride);  // needs 9 * 8 + 1
    CHECK_THAT(job.ValidationError(), Catch::Contains("input positions must cover 10 vertices at stride 8"));
    CHECK_FALSE(job.Run());
  }
  SECTION("an output normal span too short") {
    job.out_nz = job.out_nz.first(5);
    CHECK_THAT(job.ValidationError(), Catch::Contains("output normals must cover 10 vertices"));
    CHECK_FALSE(job.Run());
  }
  SECTION("the shortest valid spans") {
    job.in_px = job.in_px.first(9 * kStride + 1);
    job.out_nz = job.out_nz.first(9 * kStride + 1);
    CHECK(job.ValidationError() == "");
    CHECK(job.Run());
  }
  SECTION("a NaN weight stops a strided run too") {
    std::vector<std::array<float, 4>> w = mesh.weights;
    w[7][1] = std::numeric_limits<float>::quiet_NaN();
    job.weights = w;
    CHECK_THAT(job.ValidationError(), Catch::Contains("vertex 7 influence 1"));
    CHECK_FALSE(job.Run());
  }
}

TEST_CASE("skin data interleaved with the vertex (48 bytes) skins exactly as the packed streams do",
          "[skinning][strided]") {
  const SkinnedMesh mesh = make_random_skinned_mesh(1003, 24, 78u);
  const RandomPalettes pal = make_random_palettes(24, 1, 6u);
  const std::size_t n = mesh.vertex_count();
  const std::vector<EngineVertex> in = make_engine_vertices(mesh);
  for (SkinningMethod method : kAllSkinningMethods)
    for (int path = 0; path <= static_cast<int>(simd_targets().size()); ++path) {
      const Pin pin(path);
      CAPTURE(to_string(method), pin.name);
      SkinnedOutput packed;
      SkinningJob a = make_skinning_job(method, mesh, packed);
      set_palette(a, pal.matrices[0], pal.dual_quats[0], pal.motors[0]);
      a.use_simd = path > 0;
      REQUIRE(a.Run());

      std::vector<float> out(6 * n, -7.0f);
      SkinningJob b = make_engine_vertex_job(method, in, out, true);
      REQUIRE(b.weights.size() == (n - 1) * 3 + 1);  // the shortest spans the size rules allow
      REQUIRE(b.joints.size() == (n - 1) * 6 + 1);
      set_palette(b, pal.matrices[0], pal.dual_quats[0], pal.motors[0]);
      b.use_simd = a.use_simd;
      REQUIRE(b.vertex_count() == n);
      REQUIRE(b.ValidationError() == "");
      REQUIRE(b.Run());
      std::size_t mismatches = 0;
      for (std::size_t i = 0; i < n; ++i) {
        const float want[6] = {packed.px[i], packed.py[i], packed.pz[i], packed.nx[i], packed.ny[i], packed.nz[i]};
        mismatches += std::memcmp(out.data() + 6 * i, want, sizeof want) != 0;
      }
      CHECK(mismatches == 0);

      if (method == SkinningMethod::lbs) {  // on every path
        INFO("a weight span one quadruple short, a bad joint and a NaN weight are refused with the vertex");
        SkinningJob c = b;
        c.weights = c.weights.first(c.weights.size() - 1);
        CHECK_THAT(c.ValidationError(), Catch::Contains("weight quadruples for 1003 vertices at stride 3"));
        CHECK_FALSE(c.Run());
        std::vector<EngineVertex> bad = in;
        bad[613].j[2] = 24;
        bad[987].w[1] = std::numeric_limits<float>::quiet_NaN();
        c = b;
        c.joints = {&bad.front().j, b.joints.size()};
        CHECK_THAT(c.ValidationError(), Catch::Contains("vertex 613 influence 2: joint 24 is outside"));
        CHECK_FALSE(c.Run());
        c.joints = b.joints;
        c.weights = {&bad.front().w, b.weights.size()};
        CHECK_THAT(c.ValidationError(), Catch::Contains("vertex 987 influence 1"));
        CHECK_FALSE(c.Run());
      }
    }
}
