// Sampling and blending: every interpolation mode reproduces the keys at key times (against GLM's TRS of
// the key), `screw` moves a point along the helix of the screw motion at constant speed (closed form),
// motor decomposition round-trips, and blending's edge weights give the layers back.
#include <catch2/catch.hpp>

#include <cmath>
#include <algorithm>
#include <random>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/io/loader.hpp"
#include "cga/testing/nan_max.hpp"
// The hierarchy's hand-written rigid product, private to the runtime.
#include "../../runtime/src/detail/rigid_mul_simd.hpp"

using namespace cga;
using baseline::kAllPoseModes;
using baseline::PoseMode;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

glm::vec3 glm_apply(const Transform& x, const glm::vec3& p) {
  return x.translation + x.rotation * (x.scale * p);
}

// Where the local pose of a joint in `pose` moves p, whatever the mode's representation.
glm::vec3 pose_apply(PoseMode mode, const baseline::PoseBuffer& pose, std::size_t j, const glm::vec3& p) {
  switch (mode) {
    case PoseMode::paper:
    case PoseMode::nlerp:
    case PoseMode::screw: return motor_transform_point(pose.motors[j], p);
    case PoseMode::glm_matrix: return glm_apply(pose.transforms[j], p);
    case PoseMode::glm_dualquat: {
      const glm::dualquat& q = pose.dual_quats[j];
      return q.real * (pose.scales[j] * p) + baseline::dual_quat_translation(q);
    }
  }
  return {};
}

// The sampling job of the mode's representation (the runtime's motor job or a GLM baseline), as one object.
struct Sampler {
  const Clip* clip;
  float time;
  PoseMode mode;
  baseline::PoseBuffer* pose;
  bool Run() const { return baseline::sample(mode, *clip, time, *pose); }
};
Sampler sampler(const Clip& clip, float t, PoseMode mode, baseline::PoseBuffer& pose) {
  return {&clip, t, mode, &pose};
}
Sampler sampler(const Clip& clip, float t, Interpolation mode, baseline::PoseBuffer& pose) {
  return sampler(clip, t, baseline::to_pose_mode(mode), pose);
}

const glm::vec3 kProbe[3] = {{1.0f, 0.0f, 0.0f}, {0.0f, 1.0f, 0.0f}, {0.3f, -0.7f, 0.5f}};

// A one-joint clip with keys x[i] at times[i].
Clip one_joint_clip(const std::vector<float>& times, const std::vector<Transform>& x) {
  Clip clip;
  clip.name = "test";
  clip.duration = times.back();
  clip.tracks.resize(1);
  for (std::size_t i = 0; i < times.size(); ++i) {
    clip.tracks[0].translations.push_back({times[i], x[i].translation});
    clip.tracks[0].rotations.push_back({times[i], x[i].rotation, rotor_from_quat(x[i].rotation)});
    clip.tracks[0].scales.push_back({times[i], x[i].scale});
  }
  build_joint_keys(clip);
  return clip;
}

}  // namespace

TEST_CASE("motor_from_transform and motor_to_transform round-trip a similarity") {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int n = 0; n < 100; ++n) {
    Transform x;
    x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 5.0f;
    x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    x.scale = std::exp(u(rng));
    const Transform y = motor_to_transform(motor_from_transform(x));
    CHECK(glm::length(y.translation - x.translation) < 1e-4f);
    CHECK(std::abs(std::abs(glm::dot(y.rotation, x.rotation)) - 1.0f) < 1e-5f);
    CHECK(y.scale == Approx(x.scale).epsilon(1e-5));
    // And the motor moves points as GLM's TRS does.
    for (const glm::vec3& p : kProbe)
      CHECK(glm::length(motor_transform_point(motor_from_transform(x), p) - glm_apply(x, p)) < 1e-4f);
  }
}

TEST_CASE("every mode reproduces the keys at key times, and its interpolant at alpha 0 and 1") {
  for (const char* file : {"X/BCN_Epileptic.X", "X/Testwuson.X", "BVH/01_01.bvh"}) {
    const Character ch = load_character(model(file));
    const float size = character_size(ch);
    for (const Clip& clip : ch.clips) {
      baseline::PoseBuffer pose(ch.skeleton.joint_count());
      // Key times of the joint with the most keys, at most 40 of them spread over the clip.
      std::size_t busiest = 0;
      for (std::size_t j = 0; j < clip.keys.size(); ++j)
        if (clip.keys[j].size() > clip.keys[busiest].size()) busiest = j;
      const std::vector<float>& times = clip.keys[busiest].times;
      const std::size_t step = std::max<std::size_t>(1, times.size() / 40);
      for (PoseMode mode : kAllPoseModes) {
        INFO(file << " clip " << clip.name << " mode " << to_string(mode));
        for (std::size_t ti = 0; ti < times.size(); ti += step) {
          REQUIRE(sampler(clip, times[ti], mode, pose).Run());
          for (std::size_t j = 0; j < clip.keys.size(); ++j) {
            const JointKeys& k = clip.keys[j];
            const auto it = std::find(k.times.begin(), k.times.end(), times[ti]);
            if (it == k.times.end()) continue;
            const Transform& key = k.transforms[it - k.times.begin()];
            for (const glm::vec3& p : kProbe) {
              const glm::vec3 q = p * size;
              REQUIRE(glm::length(pose_apply(mode, pose, j, q) - glm_apply(key, q)) < 1e-5f * size * 4.0f);
            }
          }
        }
      }
      // The interpolants themselves at the ends of an interval (not the sampler's exact-key shortcut).
      const JointKeys& k = clip.keys[busiest];
      for (std::size_t i = 0; i + 1 < k.size(); i += step) {
        const Transform& x0 = k.transforms[i];
        const Transform& x1 = k.transforms[i + 1];
        for (const glm::vec3& p : kProbe) {
          const glm::vec3 q = p * size;
          const float tol = 1e-5f * size * 4.0f;
          CHECK(glm::length(motor_transform_point(motor_lerp_paper(k.rigid[i], k.rigid[i + 1], x0.scale, x1.scale, 0.0f), q) - glm_apply(x0, q)) < tol);
          CHECK(glm::length(motor_transform_point(motor_lerp_paper(k.rigid[i], k.rigid[i + 1], x0.scale, x1.scale, 1.0f), q) - glm_apply(x1, q)) < tol);
          CHECK(glm::length(motor_transform_point(motor_screw(x0, x1, 0.0f), q) - glm_apply(x0, q)) < tol);
          CHECK(glm::length(motor_transform_point(motor_screw(x0, x1, 1.0f), q) - glm_apply(x1, q)) < tol);
          CHECK(glm::length(motor_transform_point(motor_normalize(k.motors[i + 1]), q) - glm_apply(x1, q)) < tol);
        }
      }
    }
  }
}

TEST_CASE("screw moves a point along the helix of the screw motion at constant speed") {
  // Second key = first key followed by a screw motion about the line through c with direction u:
  // rotation by theta and a slide d along u. Closed form: x(alpha) = X1(c + R(alpha theta)(p - c) + alpha d u).
  const glm::vec3 u = glm::normalize(glm::vec3(1.0f, 2.0f, 2.0f));
  const glm::vec3 c(0.3f, -0.5f, 1.0f);
  const float theta = 2.0f, d = 0.7f;
  Transform x1;
  x1.translation = glm::vec3(1.0f, 2.0f, -1.0f);
  x1.rotation = glm::angleAxis(0.4f, glm::normalize(glm::vec3(0.0f, 1.0f, 1.0f)));
  const glm::quat r = glm::angleAxis(theta, u);
  Transform rel;  // p -> c + r (p - c) + d u
  rel.rotation = r;
  rel.translation = c - r * c + d * u;
  Transform x2;
  x2.rotation = glm::normalize(x1.rotation * rel.rotation);
  x2.translation = x1.translation + x1.rotation * rel.translation;
  const Clip clip = one_joint_clip({0.0f, 2.0f}, {x1, x2});

  baseline::PoseBuffer pose(1);
  const glm::vec3 p(0.9f, 0.1f, -0.4f);
  std::vector<glm::vec3> path;
  const int steps = 50;
  for (int s = 0; s <= steps; ++s) {
    const float alpha = float(s) / steps;
    REQUIRE(sampler(clip, alpha * 2.0f, Interpolation::screw, pose).Run());
    const glm::vec3 got = motor_transform_point(pose.motors[0], p);
    const glm::vec3 local = c + glm::angleAxis(alpha * theta, u) * (p - c) + alpha * d * u;
    const glm::vec3 expect = x1.translation + x1.rotation * local;
    INFO("alpha " << alpha);
    CHECK(glm::length(got - expect) < 1e-4f);
    path.push_back(got);
  }
  // Constant speed: equal chords for equal steps.
  const float chord = glm::length(path[1] - path[0]);
  for (int s = 1; s < steps; ++s) CHECK(glm::length(path[s + 1] - path[s]) == Approx(chord).epsilon(1e-3));
  // ... which the paper's lerp does not give for this motion (so the check above can fail).
  std::vector<float> lerp_chords;
  glm::vec3 prev{};
  for (int s = 0; s <= steps; ++s) {
    REQUIRE(sampler(clip, 2.0f * float(s) / steps, Interpolation::paper, pose).Run());
    const glm::vec3 got = motor_transform_point(pose.motors[0], p);
    if (s) lerp_chords.push_back(glm::length(got - prev));
    prev = got;
  }
  const auto [lo, hi] = std::minmax_element(lerp_chords.begin(), lerp_chords.end());
  CHECK(*hi > 1.05f * *lo);
}

TEST_CASE("screw interpolates the scale geometrically, paper linearly in the dilator") {
  Transform a, b;
  a.scale = 1.0f;
  b.scale = 4.0f;
  const Clip clip = one_joint_clip({0.0f, 1.0f}, {a, b});
  baseline::PoseBuffer pose(1);
  REQUIRE(sampler(clip, 0.5f, Interpolation::screw, pose).Run());
  CHECK(motor_to_transform(pose.motors[0]).scale == Approx(2.0f).epsilon(1e-5));
  REQUIRE(sampler(clip, 0.5f, Interpolation::nlerp, pose).Run());
  const float nlerp_scale = motor_to_transform(pose.motors[0]).scale;
  CHECK(nlerp_scale > 1.0f);
  CHECK(nlerp_scale < 4.0f);
  // The point at distance 1 along x lands at the mode's scale. The paper lerps the dilators
  // D = 1 + k einf^e0, k = (1-s)/(1+s): k = 0 (s = 1) and -3/5 (s = 4) give k = -3/10 halfway, the scale
  // (1-k)/(1+k) = 13/7 (not the arithmetic 5/2 or the geometric 2).
  REQUIRE(sampler(clip, 0.5f, Interpolation::paper, pose).Run());
  const float paper_scale = glm::length(motor_transform_point(pose.motors[0], {1.0f, 0.0f, 0.0f}));
  CHECK(paper_scale == Approx(13.0 / 7.0).epsilon(1e-6));
}

TEST_CASE("time is clamped to the clip") {
  Transform a, b;
  b.translation = glm::vec3(1.0f, 0.0f, 0.0f);
  const Clip clip = one_joint_clip({0.0f, 1.0f}, {a, b});
  baseline::PoseBuffer pose(1);
  for (PoseMode mode : kAllPoseModes) {
    REQUIRE(sampler(clip, 5.0f, mode, pose).Run());
    CHECK(glm::length(pose_apply(mode, pose, 0, glm::vec3(0.0f)) - b.translation) < 1e-6f);
    REQUIRE(sampler(clip, -5.0f, mode, pose).Run());
    CHECK(glm::length(pose_apply(mode, pose, 0, glm::vec3(0.0f)) - a.translation) < 1e-6f);
  }
  SamplingJob bad{&clip, 0.0f, Interpolation::paper, {}};
  CHECK_FALSE(bad.Validate());
  CHECK_FALSE(bad.Run());
  // A mode outside the enum (an integer cast to Interpolation) is refused, not taken for one of the modes.
  CHECK_FALSE(SamplingJob{&clip, 0.0f, static_cast<Interpolation>(kAllInterpolations.size()), pose.motors}.Validate());
}

TEST_CASE("blending: edge weights give a layer back, equal poses give the pose") {
  const Character ch = load_character(model("X/Testwuson.X"));
  const Clip& run = *ch.find_clip("Wuson_Run");
  const Clip& walk = *ch.find_clip("Wuson_Walk");
  const std::size_t n = ch.skeleton.joint_count();
  const float size = character_size(ch);
  for (PoseMode mode : kAllPoseModes) {
    INFO("mode " << to_string(mode));
    baseline::PoseBuffer a(n), b(n), out(n);
    REQUIRE(sampler(run, 0.3f, mode, a).Run());
    REQUIRE(sampler(walk, 1.1f, mode, b).Run());
    auto layer = [](const baseline::PoseBuffer& p, float w) { return baseline::PoseLayer{w, &p}; };
    for (float alpha : {0.0f, 1.0f, 0.5f}) {
      const baseline::PoseLayer layers[2] = {layer(a, 1.0f - alpha), layer(b, alpha)};
      REQUIRE(baseline::blend(mode, layers, out));
      for (std::size_t j = 0; j < n; ++j)
        for (const glm::vec3& p : kProbe) {
          const glm::vec3 q = p * size;
          const glm::vec3 got = pose_apply(mode, out, j, q);
          if (alpha == 0.0f) REQUIRE(glm::length(got - pose_apply(mode, a, j, q)) < 1e-5f * size * 4.0f);
          if (alpha == 1.0f) REQUIRE(glm::length(got - pose_apply(mode, b, j, q)) < 1e-5f * size * 4.0f);
          if (alpha == 0.5f) {
            // Halfway stays near the two (no mode overshoots by more than the distance between them).
            const glm::vec3 pa = pose_apply(mode, a, j, q), pb = pose_apply(mode, b, j, q);
            REQUIRE(glm::length(got - 0.5f * (pa + pb)) <= glm::length(pa - pb) + 1e-4f * size);
          }
        }
    }
    // Three equal layers blend to the same pose.
    const baseline::PoseLayer same[3] = {layer(a, 0.2f), layer(a, 0.5f), layer(a, 0.3f)};
    REQUIRE(baseline::blend(mode, same, out));
    for (std::size_t j = 0; j < n; ++j)
      REQUIRE(glm::length(pose_apply(mode, out, j, kProbe[2] * size) - pose_apply(mode, a, j, kProbe[2] * size)) <
              1e-5f * size * 4.0f);
    const baseline::PoseLayer none[1] = {layer(a, 0.0f)};
    CHECK_FALSE(baseline::blend(mode, none, out));
  }
}

// ------------------------------------------------------------------------------------------ fast paths
// The pose jobs' fast paths (per-interval keys, closed-form normalization, rigid and SIMD products) against
// the straightforward computations they replace.

namespace {

Transform random_transform(std::mt19937& rng, bool scaled) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  Transform x;
  x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 3.0f;
  x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
  x.scale = scaled ? std::exp(u(rng)) : 1.0f;
  return x;
}

float max_diff(const Motor& a, const Motor& b) {
  float d = 0.0f;
  for (int c = 0; c < 12; ++c) d = testing::nan_max(d, std::abs(a.c[c] - b.c[c]));
  return d;
}

// The sampler's result computed the slow way: binary search in the joint's own keys, then the mode's
// interpolant through the wrappers of motor.hpp (the code before the per-interval keys).
Motor reference_sample(const JointKeys& k, float t, Interpolation mode) {
  if (k.size() == 1 || t <= k.times[0]) return k.motors[0];
  if (t >= k.times.back()) return k.motors.back();
  const std::size_t i = std::upper_bound(k.times.begin(), k.times.end(), t) - k.times.begin() - 1;
  const float a = (t - k.times[i]) / (k.times[i + 1] - k.times[i]);
  if (mode == Interpolation::paper)
    return motor_lerp_paper(k.rigid[i], k.rigid[i + 1], k.transforms[i].scale, k.transforms[i + 1].scale, a);
  const Motor& x = k.motors[i];
  const Motor& y = k.motors[i + 1];
  const float b = motor_rotor_dot(x, y) < 0.0f ? -a : a;
  Motor m;
  for (int c = 0; c < 12; ++c) m.c[c] = (1.0f - a) * x.c[c] + b * y.c[c];
  return motor_normalize(m);
}

}  // namespace

TEST_CASE("motor_normalize_fast equals motor_normalize (the TRS round trip) on blends of motors") {
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int n = 0; n < 500; ++n) {
    const bool scaled = n % 2 == 1;
    const Motor x = motor_from_transform(random_transform(rng, scaled));
    const Motor y = motor_from_transform(random_transform(rng, scaled));
    const float a = u(rng);
    const float b = motor_rotor_dot(x, y) < 0.0f ? -a : a;
    Motor m;
    for (int c = 0; c < 12; ++c) m.c[c] = (1.0f - a) * x.c[c] + b * y.c[c];
    const Motor want = motor_normalize(m);
    const Motor got = motor_normalize_fast(m);
    INFO("n " << n << " alpha " << a);
    REQUIRE(max_diff(got, want) < 1e-4f * (1.0f + std::abs(want.c[3]) + std::abs(want.c[5]) + std::abs(want.c[6])));
    // Rigid in, exactly rigid out (the jobs then take the 8-blade product).
    if (!scaled) REQUIRE(motor_is_rigid(got));
  }
}

TEST_CASE("the rigid motor products (generated 8-blade kernel and the hierarchy's SIMD form) equal motor_mul") {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (int n = 0; n < 500; ++n) {
    // Exact rigid motors, and arbitrary coefficients on the 8 rigid blades (blends are not versors).
    Motor a = motor_from_transform(random_transform(rng, false));
    Motor b = motor_from_transform(random_transform(rng, false));
    if (n % 2) {
      for (int c : {0, 1, 2, 3, 4, 5, 6, 8}) a.c[c] = u(rng), b.c[c] = u(rng);
    }
    REQUIRE(motor_is_rigid(a));
    const Motor want = motor_mul(a, b);
    Motor got, simd;
    motor_mul_rigid(a, b, got);
    detail::motor_mul_rigid_simd(a, b, simd);
    REQUIRE(max_diff(got, want) < 1e-5f * 10.0f);
    REQUIRE(max_diff(simd, want) < 1e-5f * 10.0f);
    REQUIRE(motor_is_rigid(simd));
  }
  // A dilation is not rigid.
  Transform s;
  s.scale = 2.0f;
  CHECK_FALSE(motor_is_rigid(motor_from_transform(s)));
}

TEST_CASE("per-interval sampling equals a binary search in each joint's own keys") {
  // Testwuson has joints with one key next to joints with 30 or 109; 01_01 has 2752 keys per joint.
  std::mt19937 rng(13);
  for (const char* file : {"X/Testwuson.X", "BVH/01_01.bvh", "X/BCN_Epileptic.X"}) {
    const Character ch = load_character(model(file));
    for (const Clip& clip : ch.clips) {
      REQUIRE(clip.intervals.joints == clip.keys.size());
      std::uniform_real_distribution<float> u(-0.1f * clip.duration - 0.1f, 1.1f * clip.duration + 0.1f);
      baseline::PoseBuffer pose(ch.skeleton.joint_count());
      std::vector<float> times = {0.0f, clip.duration, clip.intervals.times.front(), clip.intervals.times.back()};
      for (int s = 0; s < 60; ++s) times.push_back(u(rng));
      for (std::size_t s = 0; s < clip.intervals.times.size(); s += 7) times.push_back(clip.intervals.times[s]);
      for (Interpolation mode : {Interpolation::paper, Interpolation::nlerp}) {
        for (float t : times) {
          INFO(file << " clip " << clip.name << " mode " << to_string(mode) << " t " << t);
          REQUIRE(sampler(clip, t, mode, pose).Run());
          const float tc = std::clamp(t, 0.0f, clip.duration);
          for (std::size_t j = 0; j < clip.keys.size(); ++j) {
            const Motor want = reference_sample(clip.keys[j], tc, mode);
            REQUIRE(max_diff(pose.motors[j], want) < 2e-5f * (1.0f + std::abs(want.c[3]) + std::abs(want.c[5]) +
                                                              std::abs(want.c[6]) + std::abs(want.c[8])));
          }
        }
      }
    }
  }
}

TEST_CASE("joints whose keys start late or end early hold them while other joints move") {
  Clip clip;
  clip.name = "staggered";
  clip.duration = 3.0f;
  clip.tracks.resize(2);
  Transform a, b, c;
  b.translation = glm::vec3(1.0f, 0.0f, 0.0f);
  c.translation = glm::vec3(0.0f, 2.0f, 0.0f);
  c.rotation = glm::angleAxis(1.0f, glm::vec3(0.0f, 0.0f, 1.0f));
  for (auto [t, x] : {std::pair{0.0f, a}, std::pair{1.0f, b}, std::pair{3.0f, c}}) {
    clip.tracks[0].translations.push_back({t, x.translation});
    clip.tracks[0].rotations.push_back({t, x.rotation, rotor_from_quat(x.rotation)});
    clip.tracks[0].scales.push_back({t, x.scale});
  }
  for (auto [t, x] : {std::pair{1.5f, c}, std::pair{2.0f, b}}) {
    clip.tracks[1].translations.push_back({t, x.translation});
    clip.tracks[1].rotations.push_back({t, x.rotation, rotor_from_quat(x.rotation)});
    clip.tracks[1].scales.push_back({t, x.scale});
  }
  build_joint_keys(clip);
  REQUIRE(clip.intervals.times == std::vector<float>{0.0f, 1.0f, 1.5f, 2.0f, 3.0f});
  baseline::PoseBuffer pose(2);
  for (PoseMode mode : kAllPoseModes)
    for (float t : {0.0f, 0.5f, 1.0f, 1.25f, 1.5f, 1.75f, 2.0f, 2.5f, 3.0f}) {
      INFO(to_string(mode) << " t " << t);
      REQUIRE(sampler(clip, t, mode, pose).Run());
      // Joint 1 holds c before 1.5 and b after 2; in between it moves from c to b.
      const glm::vec3 p = pose_apply(mode, pose, 1, glm::vec3(0.0f));
      if (t <= 1.5f) CHECK(glm::length(p - c.translation) < 1e-5f);
      if (t >= 2.0f) CHECK(glm::length(p - b.translation) < 1e-5f);
      if (t > 1.5f && t < 2.0f) CHECK(glm::length(p - c.translation) > 1e-3f);
      // Joint 0 passes through b at 1 on its way from a to c.
      const glm::vec3 q = pose_apply(mode, pose, 0, glm::vec3(0.0f));
      if (t == 1.0f) CHECK(glm::length(q - b.translation) < 1e-5f);
      if (t == 0.5f) CHECK(glm::length(q - 0.5f * b.translation) < 1e-5f);
    }
}

TEST_CASE("motor_screw on motors equals motor_screw on the transforms") {
  std::mt19937 rng(14);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int n = 0; n < 300; ++n) {
    const bool scaled = n % 3 == 0;
    const Transform x = random_transform(rng, scaled), y = random_transform(rng, scaled);
    const float a = u(rng);
    const Motor want = motor_screw(x, y, a);
    const Motor got = motor_screw(motor_from_transform(x), motor_from_transform(y), a);
    INFO("n " << n << " alpha " << a);
    for (const glm::vec3& p : kProbe)
      REQUIRE(glm::length(motor_transform_point(got, p) - motor_transform_point(want, p)) < 1e-4f);
  }
}

TEST_CASE("nlerp and paper blending of many joints (blocks of 8 and remainders) equal the per-joint formulas") {
  // 1..21 joints, 1..3 layers with random weights; motors with scales and random signs (antipodal layers).
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> w01(0.05f, 1.0f);
  for (std::size_t n = 1; n <= 21; ++n)
    for (std::size_t layers_n = 1; layers_n <= 3; ++layers_n) {
      INFO(n << " joints, " << layers_n << " layers");
      std::vector<std::vector<Motor>> poses(layers_n, std::vector<Motor>(n));
      std::vector<float> weights(layers_n);
      for (std::size_t l = 0; l < layers_n; ++l) {
        weights[l] = w01(rng);
        for (Motor& m : poses[l]) {
          m = motor_from_transform(random_transform(rng, true));
          if (w01(rng) < 0.4f)
            for (float& c : m.c) c = -c;
        }
      }
      std::vector<BlendLayer> layers;
      for (std::size_t l = 0; l < layers_n; ++l) layers.push_back(BlendLayer{weights[l], poses[l]});
      float total = 0.0f;
      for (float w : weights) total += w;
      for (Interpolation mode : {Interpolation::nlerp, Interpolation::paper}) {
        std::vector<Motor> out(n);
        BlendingJob job;
        job.mode = mode, job.layers = layers, job.output = out;
        REQUIRE(job.Run());
        for (std::size_t j = 0; j < n; ++j) {
          Motor want;
          for (std::size_t l = 0; l < layers_n; ++l) {
            const float s = mode == Interpolation::nlerp && l > 0 && motor_rotor_dot(poses[0][j], poses[l][j]) < 0.0f
                                ? -1.0f
                                : 1.0f;
            for (int c = 0; c < 12; ++c) want.c[c] = (l == 0 ? 0.0f : want.c[c]) + s * weights[l] / total * poses[l][j].c[c];
          }
          if (mode == Interpolation::nlerp) want = motor_normalize_fast(want);
          INFO("joint " << j << " mode " << to_string(mode));
          REQUIRE(max_diff(out[j], want) < 1e-4f);
        }
      }
    }
}
