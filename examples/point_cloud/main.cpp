// The point-cloud example: one motor applied to N points (default 10 M; argv[1] sets N), by the generated
// scalar kernel in a loop and by its generated SIMD batch kernel, which runs the best instruction set of the
// CPU (Highway's run-time dispatch). Both are checked against plain vector maths; the best of 5 runs of
// each is printed.
// Exit 0 when every point of both agrees to 1e-4 of the cloud's size.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <random>
#include <vector>

// The batch kernel with run-time dispatch: this file is Highway's per-target include of the generated header.
#define CGAGEN_SIMD_DISPATCH
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)  // see the header
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "move_points.simd.hpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include "move_points.simd.hpp"
#include "move_points.hpp"

#include <hwy/targets.h>

namespace {

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  const std::size_t n = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 10'000'000;
  const float a = 0.7f, tx = 1.5f, ty = -2.0f, tz = 0.25f;
  std::vector<float> x(n), y(n), z(n);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-10.0f, 10.0f);
  for (std::size_t i = 0; i < n; ++i) x[i] = u(rng), y[i] = u(rng), z[i] = u(rng);

  // Once per cloud: the motor's prepared values, by each header's own (scalar) prepare function.
  float prepared[cga::kernels::move_points_prepare_prepared_blades.size()];
  cga::kernels::move_points_prepare(a, tx, ty, tz, prepared);
  float prepared_batch[cga::kernels::simd::move_points_prepare_prepared_blades.size()];
  cga::kernels::simd::move_points_prepare(a, tx, ty, tz, prepared_batch);

  // Each way runs 5 times into arrays already written once; the fastest run counts.
  auto best_of_5 = [](auto&& run) {
    double best = 1e30;
    for (int r = 0; r < 5; ++r) {
      const auto t0 = std::chrono::steady_clock::now();
      run();
      best = std::min(best, seconds_since(t0));
    }
    return best;
  };

  // Scalar: one call per point, outputs stored as three arrays.
  std::vector<float> sx(n), sy(n), sz(n);
  const double scalar_s = best_of_5([&] {
    for (std::size_t i = 0; i < n; ++i) {
      float p[3];
      cga::kernels::move_points(prepared, x[i], y[i], z[i], p);
      sx[i] = p[0], sy[i] = p[1], sz[i] = p[2];
    }
  });

  // Batch: the prepared values broadcast (stride 0), the coordinates as arrays, the output blades as arrays.
  namespace ks = cga::kernels::simd;
  std::vector<float> bx(n), by(n), bz(n);
  float* const out[3] = {bx.data(), by.data(), bz.data()};
  const double batch_s = best_of_5([&] {
    ks::move_points_batch(n, ks::In{prepared_batch, 0, 1}, ks::In{x.data()}, ks::In{y.data()}, ks::In{z.data()},
                          ks::Out{nullptr, 1, 1, out});
  });

  // Plain vector maths: rotate by a about z, then translate.
  double worst = 0.0;
  const double c = std::cos(double{a}), s = std::sin(double{a});
  for (std::size_t i = 0; i < n; ++i) {
    const double ex = c * x[i] - s * y[i] + tx, ey = s * x[i] + c * y[i] + ty, ez = z[i] + double{tz};
    for (const double d : {sx[i] - ex, sy[i] - ey, sz[i] - ez, bx[i] - ex, by[i] - ey, bz[i] - ez})
      worst = std::max(worst, std::fabs(d));
  }
  // The instruction set the dispatch took: the best one compiled and supported (Highway's lowest bit).
  const std::int64_t usable = hwy::SupportedTargets() & HWY_TARGETS;
  std::printf("%zu points, batch kernel on %s\n", n, hwy::TargetName(usable & -usable));
  std::printf("scalar kernel in a loop: %.1f ms (%.0f M points/s)\n", 1e3 * scalar_s, n / scalar_s * 1e-6);
  std::printf("batch kernel:            %.1f ms (%.0f M points/s), %.2fx the scalar loop\n", 1e3 * batch_s,
              n / batch_s * 1e-6, scalar_s / batch_s);
  std::printf("largest difference from vector maths: %.3g (cloud size 10)\n", worst);
  return worst <= 1e-4 * 10 ? 0 : 1;
}
