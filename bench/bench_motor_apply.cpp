// Applying one motor to 1 M points (SoA floats), in ns/point:
//   transform_point  the generated sandwich kernel M X ~M per point, then the division by the point weight
//   transform_point_staged  the same script staged (M uniform): the generated prepare once per
//                    motor (cga::motor_prepare_points: 13 values over the weight), then the generated
//                    per-point body (9 mul + 9 add) per point
//   glm mat3x4       the baseline: the same transform as a GLM 3x4 matrix built from TRS, dot products per point
// All three loops are compiled alike (this file at -O3 without errno/trapping math, see CMakeLists.txt, and
// built twice: x86-64-v3 and the portable default, picked at run time), so only the per-point work differs.
#include <cstdint>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "summary.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_BENCH_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define CGA_BENCH_CLONES
#endif

namespace cga::bench {

namespace {

constexpr std::size_t kPoints = 1u << 20;

struct Points {
  std::vector<float> x, y, z;
  explicit Points(std::size_t n, std::uint32_t seed = 0) : x(n), y(n), z(n) {
    if (seed == 0) return;
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (std::size_t i = 0; i < n; ++i) {
      x[i] = u(rng);
      y[i] = u(rng);
      z[i] = u(rng);
    }
  }
};

// A similarity with every motor blade group nonzero (rotation, translation, scale 1.25).
Transform the_transform() {
  Transform t;
  t.translation = {0.3f, -1.2f, 2.5f};
  t.rotation = glm::normalize(glm::quat(0.8f, 0.3f, -0.4f, 0.2f));
  t.scale = 1.25f;
  return t;
}

struct Io {
  const float* px;
  const float* py;
  const float* pz;
  float* ox;
  float* oy;
  float* oz;
  std::size_t n;
};

// Each loop copies its pointers and count into locals, and says with `#pragma GCC ivdep` that the streams
// do not overlap: without the pragma GCC 12 vectorizes none of these loops (not even with the restrict
// locals; -fopt-info-vec reports "no vectype for stmt" on the first load).
#define CGA_BENCH_UNPACK(io)                                                                      \
  const float* __restrict px = (io).px;                                                           \
  const float* __restrict py = (io).py;                                                           \
  const float* __restrict pz = (io).pz;                                                           \
  float* __restrict ox = (io).ox;                                                                 \
  float* __restrict oy = (io).oy;                                                                 \
  float* __restrict oz = (io).oz;                                                                 \
  const std::size_t n = (io).n

inline __attribute__((always_inline)) void transform_point_loop(const Motor& motor, const Io& io) {
  CGA_BENCH_UNPACK(io);
  float m[12];  // a local copy: the compiler may hoist the motor-only products, as it would for any caller
  for (int e = 0; e < 12; ++e) m[e] = motor.c[e];
#pragma GCC ivdep
  for (std::size_t i = 0; i < n; ++i) {
    float p[4];
    kernels::transform_point(m, px[i], py[i], pz[i], p);
    const float inv = 1.0f / p[3];
    ox[i] = p[0] * inv;
    oy[i] = p[1] * inv;
    oz[i] = p[2] * inv;
  }
}

// The generated per-element body of the staged transform_point on every point (the prepared values are
// normalized by the weight, so its output is the Euclidean point; its w slot is 1 and unused).
inline __attribute__((always_inline)) void staged_loop(const PreparedPointTransform& prepared, const Io& io) {
  CGA_BENCH_UNPACK(io);
  float m[13];
  for (int e = 0; e < 13; ++e) m[e] = prepared[e];
#pragma GCC ivdep
  for (std::size_t i = 0; i < n; ++i) {
    float p[4];
    kernels::transform_point_staged(m, px[i], py[i], pz[i], p);
    ox[i] = p[0];
    oy[i] = p[1];
    oz[i] = p[2];
  }
}

inline __attribute__((always_inline)) void glm_loop(const glm::mat3x4& matrix, const Io& io) {
  CGA_BENCH_UNPACK(io);
  const glm::mat3x4 m = matrix;
#pragma GCC ivdep
  for (std::size_t i = 0; i < n; ++i) {
    const glm::vec4 p(px[i], py[i], pz[i], 1.0f);
    ox[i] = glm::dot(m[0], p);
    oy[i] = glm::dot(m[1], p);
    oz[i] = glm::dot(m[2], p);
  }
}

// The clones are thin wrappers around the always-inlined loops; flatten also inlines the generated
// transform_point kernel, which GCC otherwise calls out of line (too big for its inliner at -O1 size).
CGA_BENCH_CLONES __attribute__((flatten)) void apply_transform_point(const Motor& motor, const Io& io) {
  transform_point_loop(motor, io);
}
CGA_BENCH_CLONES __attribute__((flatten)) void apply_staged(const PreparedPointTransform& prepared, const Io& io) {
  staged_loop(prepared, io);
}
CGA_BENCH_CLONES __attribute__((flatten)) void apply_glm(const glm::mat3x4& matrix, const Io& io) {
  glm_loop(matrix, io);
}

enum class Variant { transform_point, staged, glm };

void bm_apply(benchmark::State& state, Variant variant) {
  static const Points in(kPoints, 99);
  Points out(kPoints);
  const Io io{in.x.data(), in.y.data(), in.z.data(), out.x.data(), out.y.data(), out.z.data(), kPoints};
  const Transform xf = the_transform();
  // The motor's construction is outside the per-point work in every variant.
  const Motor m = variant != Variant::glm ? motor_from_transform(xf) : Motor{};
  for (auto _ : state) {
    switch (variant) {
      case Variant::transform_point: apply_transform_point(m, io); break;
      case Variant::staged: {
        const PreparedPointTransform prepared = motor_prepare_points(m);  // once per motor, inside the timed loop
        apply_staged(prepared, io);
        break;
      }
      case Variant::glm: {
        const glm::mat3x4 rows = to_skinning_matrix(xf);  // once per transform, inside the timed loop
        apply_glm(rows, io);
        break;
      }
    }
    benchmark::DoNotOptimize(out.x.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(kPoints));
}

}  // namespace

void register_motor_apply_benchmarks() {
  const std::string section = "One motor applied to 1 M points";
  const std::string baseline = "motor_apply/glm_mat3x4";
  struct V {
    Variant v;
    const char* name;
    const char* label;
    std::optional<Target> target;
  };
  const V variants[] = {
      {Variant::transform_point, "motor_apply/transform_point", "generated transform_point per point", std::nullopt},
      {Variant::staged, "motor_apply/transform_point_staged",
       "generated staged transform_point: prepare once + body per point", Target{2.0, "<= 2 ns/point"}},
      {Variant::glm, "motor_apply/glm_mat3x4", "GLM mat3x4 per point (baseline)", std::nullopt},
  };
  for (const V& v : variants) {
    benchmark::RegisterBenchmark(v.name, bm_apply, v.v)->Unit(benchmark::kMicrosecond);
    add_figure({v.name, section, v.label, Metric::ns_per_item, baseline, "glm mat3x4", v.target, {}});
  }
}

}  // namespace cga::bench
