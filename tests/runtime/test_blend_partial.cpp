// Partial blending (per-joint weights, ozz's BlendingJob joint_weights) in every motor mode: a joint weight of
// 0 takes the other layer exactly, weights that are all 1 give the plain blend, every joint equals a one-joint
// blend with its effective scalar weights, pure translations average like plain vectors, rigid nlerp equals
// dual-quaternion blending computed with GLM, and joints without weight take the rest pose (or are refused).
#include <catch2/catch.hpp>

#include <random>
#include <vector>

#include <glm/gtx/dual_quaternion.hpp>

#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"

using namespace cga;

namespace {

constexpr std::size_t kJoints = 21;  // two blocks of 8 and a remainder

std::vector<Transform> random_pose(std::mt19937& rng, float max_log_scale) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Transform> pose(kJoints);
  for (Transform& x : pose) {
    x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f;
    x.rotation = glm::normalize(glm::quat(u(rng) + 1.5f, u(rng), u(rng), u(rng)));
    x.scale = std::exp(max_log_scale * u(rng));
  }
  return pose;
}

std::vector<Motor> motors_of(const std::vector<Transform>& pose) {
  std::vector<Motor> out;
  for (const Transform& x : pose) out.push_back(motor_from_transform(x));
  return out;
}

float max_diff(const Motor& a, const Motor& b) {
  float d = 0.0f;
  for (int c = 0; c < 12; ++c) d = std::max(d, std::abs(a.c[c] - b.c[c]));
  return d;
}

}  // namespace

TEST_CASE("partial blending: per-joint weights in every motor mode", "[blend][partial]") {
  std::mt19937 rng(1606u);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::vector<Motor> a = motors_of(random_pose(rng, 0.3f)), b = motors_of(random_pose(rng, 0.3f)),
                           c = motors_of(random_pose(rng, 0.3f));
  std::vector<float> wa(kJoints), wb(kJoints), ones(kJoints, 1.0f);
  for (std::size_t j = 0; j < kJoints; ++j) wa[j] = unit(rng), wb[j] = j % 5 == 0 ? 0.0f : unit(rng);
  wa[3] = 0.0f;  // joint 3: layer b only; joints 0, 5, 10, ...: layer a only
  for (Interpolation mode : {Interpolation::paper, Interpolation::nlerp, Interpolation::screw}) {
    INFO(to_string(mode));
    std::vector<Motor> out(kJoints), plain(kJoints), ones_out(kJoints);
    const BlendLayer layers[3] = {{0.6f, a, wa}, {0.4f, b, wb}, {0.0f, c, {}}};
    REQUIRE(BlendingJob{mode, layers, out}.Run());
    // Every joint equals a one-joint blend with its effective weights.
    float worst = 0.0f;
    for (std::size_t j = 0; j < kJoints; ++j) {
      Motor one;
      const BlendLayer single[2] = {{0.6f * wa[j], {&a[j], 1}}, {0.4f * wb[j], {&b[j], 1}}};
      REQUIRE(BlendingJob{mode, single, {&one, 1}}.Run());
      worst = std::max(worst, max_diff(out[j], one));
    }
    CHECK(worst <= 1e-5f);
    // A joint weight of 0 gives the other layer (normalized where the mode normalizes).
    const Motor only_b = mode == Interpolation::paper ? b[3] : motor_normalize_fast(b[3]);
    CHECK(max_diff(out[3], only_b) <= 1e-5f);
    // All joint weights 1 is the plain blend.
    const BlendLayer with_ones[2] = {{0.6f, a, ones}, {0.4f, b, ones}};
    const BlendLayer without[2] = {{0.6f, a, {}}, {0.4f, b, {}}};
    REQUIRE(BlendingJob{mode, with_ones, ones_out}.Run());
    REQUIRE(BlendingJob{mode, without, plain}.Run());
    float worst_plain = 0.0f;
    for (std::size_t j = 0; j < kJoints; ++j) worst_plain = std::max(worst_plain, max_diff(ones_out[j], plain[j]));
    CHECK(worst_plain <= 1e-5f);
  }
}

TEST_CASE("partial blending against plain vector and dual-quaternion maths", "[blend][partial]") {
  std::mt19937 rng(1607u);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), unit(0.0f, 1.0f);
  std::vector<float> wa(kJoints), wb(kJoints);
  for (std::size_t j = 0; j < kJoints; ++j) wa[j] = unit(rng) + 0.01f, wb[j] = unit(rng);
  SECTION("paper mode on translations: the joint moves to the weighted mean of the translations") {
    std::vector<Transform> ta(kJoints), tb(kJoints);
    for (std::size_t j = 0; j < kJoints; ++j)
      ta[j].translation = glm::vec3(u(rng), u(rng), u(rng)), tb[j].translation = glm::vec3(u(rng), u(rng), u(rng));
    const std::vector<Motor> a = motors_of(ta), b = motors_of(tb);
    std::vector<Motor> out(kJoints);
    const BlendLayer layers[2] = {{0.3f, a, wa}, {0.7f, b, wb}};
    REQUIRE(BlendingJob{Interpolation::paper, layers, out}.Run());
    for (std::size_t j = 0; j < kJoints; ++j) {
      const float x = 0.3f * wa[j], y = 0.7f * wb[j];
      const glm::vec3 want = (x * ta[j].translation + y * tb[j].translation) / (x + y);
      CHECK(glm::length(motor_transform_point(out[j], glm::vec3(0.0f)) - want) <= 1e-5f);
    }
  }
  SECTION("nlerp on rigid motors is dual-quaternion linear blending (GLM) with the same weights") {
    const std::vector<Transform> ta = random_pose(rng, 0.0f), tb = random_pose(rng, 0.0f);
    const std::vector<Motor> a = motors_of(ta), b = motors_of(tb);
    std::vector<Motor> out(kJoints);
    const BlendLayer layers[2] = {{0.5f, a, wa}, {0.5f, b, wb}};
    REQUIRE(BlendingJob{Interpolation::nlerp, layers, out}.Run());
    for (std::size_t j = 0; j < kJoints; ++j) {
      const glm::dualquat qa(ta[j].rotation, ta[j].translation), qb(tb[j].rotation, tb[j].translation);
      const float x = 0.5f * wa[j], y = 0.5f * wb[j];
      glm::dualquat sum = qa * (x / (x + y)) + qb * ((glm::dot(qa.real, qb.real) < 0.0f ? -y : y) / (x + y));
      const float n = glm::length(sum.real);
      sum = glm::dualquat(sum.real / n, sum.dual / n);
      const glm::vec3 p(0.3f, -0.2f, 0.5f);
      const glm::quat t = (sum.dual * glm::conjugate(sum.real)) * 2.0f;
      const glm::vec3 want = sum.real * p + glm::vec3(t.x, t.y, t.z);
      CHECK(glm::length(motor_transform_point(out[j], p) - want) <= 1e-5f);
    }
  }
}

TEST_CASE("partial blending: joints without weight take the rest pose, or the job is refused", "[blend][partial][bad-input]") {
  std::mt19937 rng(1608u);
  const std::vector<Motor> a = motors_of(random_pose(rng, 0.0f)), rest = motors_of(random_pose(rng, 0.0f));
  std::vector<float> w(kJoints, 1.0f);
  w[7] = 0.0f;
  std::vector<Motor> out(kJoints);
  const BlendLayer layers[1] = {{1.0f, a, w}};
  BlendingJob job{Interpolation::nlerp, layers, out};
  CHECK_FALSE(job.Validate());  // joint 7 has no weight and there is no rest pose
  job.rest_pose = rest;
  REQUIRE(job.Run());
  CHECK(max_diff(out[7], rest[7]) == 0.0f);
  CHECK(max_diff(out[6], motor_normalize_fast(a[6])) <= 1e-6f);
  // Bad joint weights: negative, NaN, too few.
  for (float bad : {-0.5f, std::numeric_limits<float>::quiet_NaN()}) {
    std::vector<float> v(kJoints, 1.0f);
    v[2] = bad;
    const BlendLayer l[1] = {{1.0f, a, v}};
    CHECK_FALSE((BlendingJob{Interpolation::paper, l, out}.Validate()));
  }
  const std::vector<float> short_w(kJoints - 1, 1.0f);
  const BlendLayer l[1] = {{1.0f, a, short_w}};
  CHECK_FALSE((BlendingJob{Interpolation::paper, l, out}.Validate()));
}
