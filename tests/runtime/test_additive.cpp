// Additive layers (AdditiveBlendingJob, make_additive_delta) against plain matrix and quaternion maths: at
// weight 1 the base moved by M_ref⁻¹ M (GLM 4x4 matrices); weight 0 the base; at weight w the rotation of
// screw is the quaternion slerp(1, q_Δ, w) and that of nlerp the quaternion nlerp; the nlerp weighting's
// angle error against w·θ is measured (the accuracy comparison of the two weightings); bad input refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cga/runtime/additive.hpp"
#include "cga/runtime/motor.hpp"

using namespace cga;

namespace {

constexpr std::size_t kJoints = 40;

std::vector<Transform> random_pose(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<Transform> pose(kJoints);
  for (Transform& x : pose) {
    x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f;
    x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
  }
  return pose;
}

std::vector<Motor> motors_of(const std::vector<Transform>& pose) {
  std::vector<Motor> out;
  for (const Transform& x : pose) out.push_back(motor_from_transform(x));
  return out;
}

glm::mat4 mat_of(const Transform& x) {
  return glm::translate(glm::mat4(1.0f), x.translation) * glm::mat4_cast(x.rotation);
}

float quat_distance(const glm::quat& a, const glm::quat& b) { return 1.0f - std::abs(glm::dot(a, b)); }

}  // namespace

TEST_CASE("additive layers against matrix and quaternion maths", "[additive]") {
  std::mt19937 rng(1616u);
  const std::vector<Transform> ref = random_pose(rng), clip = random_pose(rng), base = random_pose(rng);
  const std::vector<Motor> ref_m = motors_of(ref), clip_m = motors_of(clip), base_m = motors_of(base);
  std::vector<Motor> delta(kJoints), out(kJoints);
  REQUIRE(make_additive_delta(ref_m, clip_m, delta));
  const glm::vec3 probe(0.4f, -0.3f, 0.8f);
  for (Interpolation mode : {Interpolation::screw, Interpolation::nlerp}) {
    INFO(to_string(mode));
    for (float w : {0.0f, 0.25f, 0.5f, 0.8f, 1.0f}) {
      INFO("weight " << w);
      const AdditiveLayer layers[1] = {{w, delta}};
      REQUIRE(AdditiveBlendingJob{mode, base_m, layers, out}.Run());
      float worst_point = 0.0f, worst_rotation = 0.0f;
      for (std::size_t j = 0; j < kJoints; ++j) {
        const glm::quat qd = glm::conjugate(ref[j].rotation) * clip[j].rotation;
        if (w == 1.0f || w == 0.0f) {
          const glm::mat4 want = w == 1.0f ? mat_of(base[j]) * glm::inverse(mat_of(ref[j])) * mat_of(clip[j])
                                           : mat_of(base[j]);
          worst_point = std::max(worst_point, glm::length(motor_transform_point(out[j], probe) -
                                                          glm::vec3(want * glm::vec4(probe, 1.0f))));
        }
        glm::quat part;
        if (mode == Interpolation::screw) {
          part = glm::slerp(glm::quat(1, 0, 0, 0), qd.w < 0.0f ? -qd : qd, w);
        } else {
          const glm::quat s = qd.w < 0.0f ? -qd : qd;
          part = glm::normalize(glm::quat(1, 0, 0, 0) * (1.0f - w) + s * w);
        }
        worst_rotation =
            std::max(worst_rotation, quat_distance(motor_to_transform(out[j]).rotation, base[j].rotation * part));
      }
      CHECK(worst_point <= 1e-5f * 4.0f);
      CHECK(worst_rotation <= 1e-6f);
    }
  }
}

TEST_CASE("additive weighting: nlerp's angle against the screw's exact w * theta", "[additive]") {
  // Δ(w)'s rotation angle for a delta turning by theta: screw gives w * theta; nlerp gives
  // 2 atan(w sin(theta/2) / (1 - w + w cos(theta/2))). Measured on the motors, not on the formula.
  float worst_screw = 0.0f, worst_nlerp_90 = 0.0f, worst_nlerp_180 = 0.0f;
  for (int t = 1; t <= 35; ++t) {
    const float theta = t * 5.0f * 3.14159265f / 180.0f;  // 5 .. 175 degrees
    Transform x;
    x.rotation = glm::angleAxis(theta, glm::normalize(glm::vec3(1.0f, 2.0f, 3.0f)));
    x.translation = glm::vec3(0.5f, 0.0f, 0.0f);
    const Motor d = motor_from_transform(x), identity;
    for (float w : {0.1f, 0.25f, 0.5f, 0.75f, 0.9f}) {
      for (Interpolation mode : {Interpolation::screw, Interpolation::nlerp}) {
        Motor out;
        const AdditiveLayer layers[1] = {{w, {&d, 1}}};
        REQUIRE(AdditiveBlendingJob{mode, {&identity, 1}, layers, {&out, 1}}.Run());
        const float angle = 2.0f * std::acos(std::min(1.0f, std::abs(motor_to_transform(out).rotation.w)));
        const float err = std::abs(angle - w * theta) / theta;
        if (mode == Interpolation::screw) worst_screw = std::max(worst_screw, err);
        else if (theta <= 3.14159265f / 2.0f + 1e-4f) worst_nlerp_90 = std::max(worst_nlerp_90, err);
        else worst_nlerp_180 = std::max(worst_nlerp_180, err);
      }
    }
  }
  INFO("relative angle error: screw " << worst_screw << "; nlerp up to 90 degrees " << worst_nlerp_90
                                       << ", 95 to 175 degrees " << worst_nlerp_180);
  CHECK(worst_screw <= 1e-4f);
  CHECK(worst_nlerp_90 > 1e-3f);  // the lerp is not angle-exact...
  CHECK(worst_nlerp_90 < 0.1f);   // ...but within 10 % of theta for deltas up to 90 degrees
  CHECK(worst_nlerp_180 > worst_nlerp_90);
}

TEST_CASE("additive layers refuse bad input", "[additive][bad-input]") {
  std::vector<Motor> base(3), delta(2), out(3);
  const AdditiveLayer short_layer[1] = {{0.5f, delta}};
  CHECK_FALSE((AdditiveBlendingJob{Interpolation::screw, base, short_layer, out}.Validate()));
  const std::vector<Motor> ok(3);
  for (float w : {-0.1f, 1.5f, std::numeric_limits<float>::quiet_NaN()}) {
    const AdditiveLayer l[1] = {{w, ok}};
    CHECK_FALSE((AdditiveBlendingJob{Interpolation::nlerp, base, l, out}.Validate()));
  }
  const AdditiveLayer l[1] = {{0.5f, ok}};
  CHECK_FALSE((AdditiveBlendingJob{Interpolation::paper, base, l, out}.Validate()));
  CHECK_FALSE(make_additive_delta(delta, base, out));  // reference shorter than the pose
}
