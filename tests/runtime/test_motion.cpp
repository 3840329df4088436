// Motion extraction (MotionExtractionJob, apply_root_motion, root_motion_delta) against plain matrix and
// quaternion maths: the track is translate(sel(t − t_ref)) · twist_up(q) · twist_up(q_ref)⁻¹ with the
// quaternion swing-twist twist normalize(w, 0, y, 0) (y-up; likewise x and z), the remaining part is
// track⁻¹ · M (GLM 4x4 matrices), re-application gives M back, accumulated deltas give the track; on random
// keys (fixed seed, scaled and unscaled) and on BCN_Epileptic's root keys; bad input refused.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "cga/io/loader.hpp"
#include "cga/runtime/motion.hpp"
#include "cga/runtime/motor.hpp"

using namespace cga;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

glm::mat4 mat_of(const Transform& x) {
  return glm::translate(glm::mat4(1.0f), x.translation) * glm::mat4_cast(x.rotation) *
         glm::scale(glm::mat4(1.0f), glm::vec3(x.scale));
}

glm::quat twist(const glm::quat& q, MotionAxis up) {
  glm::quat t(q.w, 0.0f, 0.0f, 0.0f);
  if (up == MotionAxis::x) t.x = q.x;
  if (up == MotionAxis::y) t.y = q.y;
  if (up == MotionAxis::z) t.z = q.z;
  const float n = std::sqrt(t.w * t.w + t.x * t.x + t.y * t.y + t.z * t.z);
  return n > 1e-12f ? t * (1.0f / n) : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
}

// Largest distance between where the motor and the matrix put a few probe points, relative to `size`.
float point_error(const Motor& m, const glm::mat4& x, float size) {
  float worst = 0.0f;
  for (glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1),
                      glm::vec3(0.3f, -0.7f, 0.5f)}) {
    p *= size;
    const glm::vec3 want = glm::vec3(x * glm::vec4(p, 1.0f));
    worst = std::max(worst, glm::length(motor_transform_point(m, p) - want) / size);
  }
  return worst;
}

struct Options {
  bool x, y, z, yaw;
  MotionAxis up;
  MotionReference ref;
};

// The expected track of key k as a matrix, from TRS keys with quaternions.
glm::mat4 expected_track(const std::vector<Transform>& keys, std::size_t k, const Options& o) {
  glm::vec3 t = keys[k].translation;
  glm::quat y = o.yaw ? twist(keys[k].rotation, o.up) : glm::quat(1, 0, 0, 0);
  if (o.ref == MotionReference::first_frame) {
    t -= keys[0].translation;
    if (o.yaw) y = y * glm::conjugate(twist(keys[0].rotation, o.up));
  }
  t *= glm::vec3(o.x ? 1.0f : 0.0f, o.y ? 1.0f : 0.0f, o.z ? 1.0f : 0.0f);
  return glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(y);
}

// Runs the job on the keys and checks track, remaining and re-application against the matrices.
void check_keys(const std::vector<Transform>& keys, const Options& o, float size, float tol) {
  std::vector<Motor> root, track(keys.size()), remaining(keys.size());
  for (const Transform& x : keys) root.push_back(motor_from_transform(x));
  MotionExtractionJob job;
  job.root = root;
  job.extract_x = o.x, job.extract_y = o.y, job.extract_z = o.z, job.extract_yaw = o.yaw;
  job.up = o.up;
  job.reference = o.ref;
  job.track = track;
  job.remaining = remaining;
  REQUIRE(job.Run());
  float worst_track = 0.0f, worst_remaining = 0.0f, worst_apply = 0.0f, worst_accumulated = 0.0f;
  Motor accumulated = track[0];
  for (std::size_t k = 0; k < keys.size(); ++k) {
    const glm::mat4 tm = expected_track(keys, k, o), mm = mat_of(keys[k]);
    worst_track = std::max(worst_track, point_error(track[k], tm, size));
    worst_remaining = std::max(worst_remaining, point_error(remaining[k], glm::inverse(tm) * mm, size));
    worst_apply = std::max(worst_apply, point_error(apply_root_motion(track[k], remaining[k]), mm, size));
    if (k > 0) accumulated = motor_normalize_fast(motor_mul(accumulated, root_motion_delta(track[k - 1], track[k])));
    worst_accumulated = std::max(worst_accumulated, point_error(accumulated, tm, size));
    // The track is rigid and turns about `up` only: the two other rotor bivectors and the dilation are 0.
    const int other[3][2] = {{blade::e12, blade::e13}, {blade::e12, blade::e23}, {blade::e13, blade::e23}};
    for (int b : other[static_cast<int>(o.up)]) REQUIRE(track[k].c[b] == 0.0f);
    REQUIRE(motor_is_rigid(track[k]));
  }
  INFO("track " << worst_track << " remaining " << worst_remaining << " apply " << worst_apply << " accumulated "
                << worst_accumulated);
  CHECK(worst_track < tol);
  CHECK(worst_remaining < tol);
  CHECK(worst_apply < tol);
  CHECK(worst_accumulated < 50 * tol);  // a product chain over every key
  if (o.ref == MotionReference::first_frame) CHECK(point_error(track[0], glm::mat4(1.0f), size) < tol);
}

std::vector<Transform> random_keys(std::mt19937& rng, std::size_t n, bool scaled) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f), s(0.5f, 2.0f);
  std::vector<Transform> keys(n);
  for (Transform& x : keys) {
    x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 3.0f;
    x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    if (x.rotation.w < 0.0f) x.rotation = -x.rotation;
    x.scale = scaled ? s(rng) : 1.0f;
  }
  return keys;
}

}  // namespace

TEST_CASE("motion extraction against matrix and quaternion maths", "[motion]") {
  std::mt19937 rng(1617u);
  for (bool scaled : {false, true}) {
    const std::vector<Transform> keys = random_keys(rng, 500, scaled);
    for (MotionAxis up : {MotionAxis::x, MotionAxis::y, MotionAxis::z})
      for (MotionReference ref : {MotionReference::absolute, MotionReference::first_frame})
        for (int mask = 0; mask < 16; ++mask) {
          const Options o{(mask & 1) != 0, (mask & 2) != 0, (mask & 4) != 0, (mask & 8) != 0, up, ref};
          INFO("scaled " << scaled << " up " << static_cast<int>(up) << " ref " << static_cast<int>(ref)
                         << " mask " << mask);
          check_keys(keys, o, 3.0f, 2e-5f);
        }
  }
}

TEST_CASE("motion extraction: the remaining root keeps no ground motion and no yaw", "[motion]") {
  std::mt19937 rng(1618u);
  const std::vector<Transform> keys = random_keys(rng, 200, false);
  std::vector<Motor> root, track(keys.size()), remaining(keys.size());
  for (const Transform& x : keys) root.push_back(motor_from_transform(x));
  MotionExtractionJob job;
  job.root = root;
  job.reference = MotionReference::absolute;
  job.track = track;
  job.remaining = remaining;
  REQUIRE(job.Run());
  for (std::size_t k = 0; k < keys.size(); ++k) {
    // Translation left: only the height (the yaw about y keeps it); rotation left: no twist about y.
    const glm::vec3 t = motor_transform_point(remaining[k], glm::vec3(0.0f));
    CHECK(std::abs(t.x) < 1e-5f);
    CHECK(std::abs(t.z) < 1e-5f);
    CHECK(std::abs(t.y - keys[k].translation.y) < 1e-5f);
    const glm::quat q = quat_from_rotor(remaining[k].c[0], remaining[k].c[1], remaining[k].c[2], remaining[k].c[4]);
    CHECK(std::abs(twist(q, MotionAxis::y).y) < 1e-5f);
  }
}

TEST_CASE("motion extraction on BCN_Epileptic's root keys, in place", "[motion]") {
  const Character ch = load_character(model("X/BCN_Epileptic.X"));
  const JointKeys& keys = ch.clips.at(0).keys.at(0);
  REQUIRE(keys.motors.size() > 10);
  float size = 0.0f;
  for (const Transform& x : keys.transforms) size = std::max(size, glm::length(x.translation));
  size = std::max(size, 1.0f);
  check_keys(keys.transforms, {true, false, true, true, MotionAxis::y, MotionReference::first_frame}, size, 2e-5f);
  // remaining may alias root.
  std::vector<Motor> root = keys.motors, track(root.size());
  MotionExtractionJob job;
  job.root = root;
  job.track = track;
  job.remaining = root;
  REQUIRE(job.Run());
  for (std::size_t k = 0; k < root.size(); ++k)
    CHECK(point_error(apply_root_motion(track[k], root[k]), mat_of(keys.transforms[k]), size) < 2e-5f);
}

TEST_CASE("motion extraction refuses bad input", "[motion]") {
  std::vector<Motor> root(4), track(4), remaining(4);
  const Motor sentinel = motor_from_transform({glm::vec3(7.0f), glm::quat(1, 0, 0, 0), 1.0f});
  MotionExtractionJob job;
  job.root = root;
  job.track = track;
  job.remaining = remaining;
  REQUIRE(job.Validate());
  auto refused = [&](MotionExtractionJob j) {
    std::fill(track.begin(), track.end(), sentinel);
    CHECK_FALSE(j.Validate());
    CHECK_FALSE(j.Run());
    CHECK(track[0].c == sentinel.c);  // outputs untouched
  };
  MotionExtractionJob j = job;
  j.root = {};
  j.track = {};
  j.remaining = {};
  refused(j);  // empty
  j = job;
  j.track = std::span<Motor>(track).first(3);
  refused(j);  // size mismatch
  j = job;
  j.remaining = std::span<Motor>(remaining).first(3);
  refused(j);
  root[2].c[3] = std::nanf("");
  refused(job);  // non-finite
  root[2] = Motor();
  root[1].c.fill(0.0f);
  refused(job);  // no rotor part
  root[1] = Motor();
  j = job;
  j.up = static_cast<MotionAxis>(5);
  refused(j);
}
