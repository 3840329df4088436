// motor_normalize_fast through the generated kernel motor_normalize (runtime/scripts/motor_normalize.clu)
// against the hand formula it replaces (copied here as the reference), on seeded random exact motors with
// and without scale, on blends of 2-4 nearby motors and on blends scaled by a weight; and the jobs' form of it
// (blocks of 8 joints, nlerp sampling and blending) against the same reference.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"
#include "random_motors.hpp"

using namespace cga;
using cga::test::random_blend;
using cga::test::random_transform;

namespace {

// The former motor_normalize_fast (motor.hpp before motor_normalize.clu), in float.
Motor reference_normalize(const Motor& m) {
  const float* in = m.c.data();
  const float g0 = in[0] + in[7], g1 = in[1] + in[9], g2 = in[2] + in[10], g3 = in[4] + in[11];
  const float h0 = in[0] - in[7], h1 = in[1] - in[9], h2 = in[2] - in[10], h3 = in[4] - in[11];
  const float gg = g0 * g0 + g1 * g1 + g2 * g2 + g3 * g3;
  const float hh = h0 * h0 + h1 * h1 + h2 * h2 + h3 * h3;
  const float ng = std::sqrt(gg), nh = std::sqrt(hh);
  const float inv_g = 1.0f / ng, inv_sum = 1.0f / (ng + nh);
  const float k = (ng - nh) * inv_sum;
  const float e0 = in[3], e1 = in[5], e2 = in[6], e3 = in[8];
  const float ne = (-g3 * e0 + g2 * e1 - g1 * e2 + g0 * e3) * (inv_g * inv_g);
  const float ce = 2.0f * inv_sum;
  const float a0 = g0 * inv_g, a1 = g1 * inv_g, a2 = g2 * inv_g, a3 = g3 * inv_g;
  Motor out;
  float* o = out.c.data();
  o[0] = a0, o[1] = a1, o[2] = a2, o[4] = a3;
  o[7] = k * a0, o[9] = k * a1, o[10] = k * a2, o[11] = k * a3;
  o[3] = ce * (e0 + ne * g3);
  o[5] = ce * (e1 - ne * g2);
  o[6] = ce * (e2 + ne * g1);
  o[8] = ce * (e3 - ne * g0);
  return out;
}

// 1000 inputs: exact motors and blends, every fourth one rigid, half the blends scaled by a weight.
std::vector<Motor> random_inputs(unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> weight(0.3f, 3.0f);
  std::vector<Motor> out;
  for (int n = 0; n < 1000; ++n) {
    const bool scaled = n % 4 != 0;
    if (n % 5 == 0)
      out.push_back(motor_from_transform(random_transform(rng, scaled)));
    else
      out.push_back(random_blend(rng, 2 + n % 3, n % 2 ? weight(rng) : 1.0f, scaled));
  }
  return out;
}

// Largest difference in float ulps of the coefficient's group size: the rotor and b groups are at most 1,
// the einf group at most the translation's size (about 10 here).
float ulps_apart(const Motor& got, const Motor& want) {
  float einf = 1.0f;
  for (int c : {3, 5, 6, 8}) einf = std::max(einf, std::abs(want.c[c]));
  float worst = 0.0f;
  for (int c = 0; c < 12; ++c) {
    const bool e = c == 3 || c == 5 || c == 6 || c == 8;
    worst = std::max(worst, std::abs(got.c[c] - want.c[c]) / ((e ? einf : 1.0f) * 1.1920929e-7f));
  }
  return worst;
}

}  // namespace

TEST_CASE("motor_normalize_fast (generated motor_normalize) equals the former hand formula", "[motor]") {
  const std::vector<Motor> in = random_inputs(21);
  float worst = 0.0f;
  for (std::size_t n = 0; n < in.size(); ++n) {
    INFO("input " << n);
    const Motor want = reference_normalize(in[n]);
    const Motor got = motor_normalize_fast(in[n]);
    const float d = ulps_apart(got, want);
    worst = std::max(worst, d);
    CHECK(d <= 2.0f);  // measured worst: 1.03
    // Rigid in, exactly rigid out (the jobs then take the 8-blade product).
    if (motor_is_rigid(in[n])) CHECK(motor_is_rigid(got));
    // In place.
    Motor same = in[n];
    motor_normalize_fast(same.c.data(), same.c.data());
    CHECK(same.c == got.c);
  }
  WARN("worst difference: " << worst << " ulps");
}

TEST_CASE("the jobs' nlerp normalization (blocks of 8 joints) equals the former hand formula", "[motor]") {
  // One layer of weight 1: the blend is the input itself, normalized by the jobs' vectorized loop (1000 joints:
  // 125 whole blocks), which is built with reassociation and contraction (runtime/CMakeLists.txt).
  const std::vector<Motor> in = random_inputs(22);
  const BlendLayer layer{1.0f, in};
  std::vector<Motor> out(in.size());
  BlendingJob job;
  job.mode = Interpolation::nlerp;
  job.layers = std::span<const BlendLayer>(&layer, 1);
  job.output = out;
  REQUIRE(job.Run());
  float worst = 0.0f;
  for (std::size_t n = 0; n < in.size(); ++n) {
    INFO("joint " << n);
    const float d = ulps_apart(out[n], reference_normalize(in[n]));
    worst = std::max(worst, d);
    CHECK(d <= 4.0f);  // measured worst: 2.2 (the x86-64-v3 clone, with FMA)
  }
  WARN("worst difference: " << worst << " ulps");
}
