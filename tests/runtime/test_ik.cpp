// TwoBoneIKJob and AimIKJob (runtime/scripts/ik_two_bone.clu, ik_aim.clu) against plain vector/quaternion
// maths (cga/testing/ik_reference.hpp) on 10,000 random chains each (fixed seeds): the corrections are applied
// to a local pose and the model pose recomputed by LocalToModelJob, then reach (1e-5 of the chain length),
// bone lengths, the pole side, clamping of unreachable targets, weight, soften and twist are checked; and
// the degenerate cases (zero-length bones, target on the root, pole on the chain axis, target on the aiming
// joint) give finite, defined results.
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "cga/runtime/ik.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/testing/ik_reference.hpp"

using namespace cga;

namespace {

struct Rng {
  std::mt19937 gen;
  explicit Rng(std::uint32_t seed) : gen(seed) {}
  float uniform(float lo, float hi) { return std::uniform_real_distribution<float>(lo, hi)(gen); }
  glm::vec3 direction() {
    for (;;) {
      const glm::vec3 v(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      const float n = glm::length(v);
      if (n > 0.1f && n <= 1.0f) return v / n;
    }
  }
  glm::quat rotation() {
    for (;;) {
      const glm::quat q(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
      const float n = glm::length(q);
      if (n > 0.1f && n <= 1.0f) return q / n;
    }
  }
};

// A three-joint chain (start <- mid <- end) as local motors, with its model pose.
struct Chain {
  Skeleton skeleton;
  std::vector<Motor> local, model;

  Chain(const Transform& root, const Transform& mid, const Transform& end) : local(3), model(3) {
    skeleton.names = {"start", "mid", "end"};
    skeleton.parents = {-1, 0, 1};
    skeleton.rest_local = {root, mid, end};
    local = {motor_from_transform(root), motor_from_transform(mid), motor_from_transform(end)};
    update();
  }
  void update() { REQUIRE(LocalToModelJob{&skeleton, local, model}.Run()); }
  glm::vec3 position(int j) const { return motor_transform_point(model[j], glm::vec3(0.0f)); }
  glm::quat rotation(int j) const {
    return glm::normalize(quat_from_rotor(model[j].c[0], model[j].c[1], model[j].c[2], model[j].c[4]));
  }
};

Chain random_chain(Rng& rng, float l1, float l2) {
  Transform root, mid, end;
  root.translation = glm::vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
  root.rotation = rng.rotation();
  mid.translation = l1 * rng.direction();
  mid.rotation = rng.rotation();
  end.translation = l2 * rng.direction();
  end.rotation = rng.rotation();
  return Chain(root, mid, end);
}

struct Solved {
  bool ok = false, reached = false;
  Motor start, mid;
};

Solved solve(Chain& chain, const glm::vec3& target, const glm::vec3& pole, float weight = 1.0f, float soften = 1.0f,
             float twist = 0.0f) {
  Solved r;
  TwoBoneIKJob job;
  job.start_joint = &chain.model[0], job.mid_joint = &chain.model[1], job.end_joint = &chain.model[2];
  job.target = target, job.pole_vector = pole, job.weight = weight, job.soften = soften, job.twist_angle = twist;
  job.start_joint_correction = &r.start, job.mid_joint_correction = &r.mid, job.reached = &r.reached;
  // The same solve with the positions handed in (motor_transform_point's): the job reads the same numbers off
  // the motors, so both give the same corrections bit for bit.
  const glm::vec3 given[3] = {chain.position(0), chain.position(1), chain.position(2)};
  Solved g;
  TwoBoneIKJob with_positions = job;
  with_positions.positions = given;
  with_positions.start_joint_correction = &g.start, with_positions.mid_joint_correction = &g.mid;
  with_positions.reached = &g.reached;
  REQUIRE(with_positions.Run() == job.Validate());
  r.ok = job.Run();
  if (r.ok) {
    REQUIRE(g.start.c == r.start.c);
    REQUIRE(g.mid.c == r.mid.c);
    REQUIRE(g.reached == r.reached);
  }
  if (r.ok) {
    apply_ik_correction(chain.local[0], r.start);
    apply_ik_correction(chain.local[1], r.mid);
    chain.update();
  }
  return r;
}

bool finite(const Motor& m) {
  for (float c : m.c)
    if (!std::isfinite(c)) return false;
  return true;
}

}  // namespace

TEST_CASE("two-bone IK on 10,000 random chains: reach, bone lengths, pole side, clamping, reference", "[ik]") {
  Rng rng(20261124u);
  float worst_reach = 0, worst_length = 0, worst_clamp = 0, worst_elbow = 0, worst_start = 0;
  int reachable = 0, unreachable = 0, wrong_side = 0, not_reached_flag = 0, reached_flag_wrong = 0;
  for (int i = 0; i < 10000; ++i) {
    const float l1 = rng.uniform(0.2f, 2.0f), l2 = rng.uniform(0.2f, 2.0f), len = l1 + l2;
    Chain chain = random_chain(rng, l1, l2);
    const glm::vec3 s = chain.position(0), m = chain.position(1), e = chain.position(2);
    const glm::quat qs = chain.rotation(0), qm = chain.rotation(1);
    const float r = rng.uniform(0.0f, 1.3f) * len;
    const glm::vec3 u = rng.direction(), target = s + r * u, pole = rng.direction();
    const testing::TwoBoneReference ref = testing::two_bone_reference(s, m, e, qs, qm, target, pole);
    const Solved got = solve(chain, target, pole);
    REQUIRE(got.ok);
    const glm::vec3 s2 = chain.position(0), m2 = chain.position(1), e2 = chain.position(2);
    worst_start = std::max(worst_start, glm::length(s2 - s) / len);
    worst_length = std::max({worst_length, std::abs(glm::length(m2 - s2) - l1) / len,
                             std::abs(glm::length(e2 - m2) - l2) / len});
    // Against the law-of-cosines elbow (near full extension both are sensitive to rounding: h = sqrt(l1^2 - x^2)).
    worst_elbow = std::max(worst_elbow, glm::length((m2 - s) - ref.elbow) / len);
    // The pole side: the elbow's offset from the axis points along the pole's component off the axis.
    const glm::vec3 pp = pole - glm::dot(pole, u) * u;
    const glm::vec3 off = (m2 - s) - glm::dot(m2 - s, u) * u;
    if (glm::dot(off, pp) < -1e-5f * len) ++wrong_side;
    const float margin = 1e-3f * len;
    if (r > std::abs(l1 - l2) + margin && r < len - margin) {
      ++reachable;
      worst_reach = std::max(worst_reach, glm::length(e2 - target) / len);
      not_reached_flag += !got.reached;
    } else if (r < std::abs(l1 - l2) - margin || r > len + margin) {
      ++unreachable;
      // Clamped: the end on the ray from the start through the target, at the nearest reachable distance.
      const float dc = std::clamp(r, std::abs(l1 - l2), len);
      worst_clamp = std::max(worst_clamp, glm::length(e2 - (s + dc * u)) / len);
      reached_flag_wrong += got.reached;
    }
  }
  INFO("reachable " << reachable << ", unreachable " << unreachable << "; worst relative errors: reach "
                    << worst_reach << ", clamped end " << worst_clamp << ", bone length " << worst_length
                    << ", start moved " << worst_start << ", elbow vs law of cosines " << worst_elbow);
  CHECK(reachable > 5000);
  CHECK(unreachable > 1000);
  CHECK(worst_reach <= 1e-5f);
  // Clamped ends are a chain at full extension or folded flat, composed from float motors 2 units from the origin:
  // measured 1.3e-5 at worst (chains of length 0.4); reachable targets are reached to 2.2e-6.
  CHECK(worst_clamp <= 2e-5f);
  CHECK(worst_length <= 1e-5f);
  CHECK(worst_start <= 1e-5f);
  CHECK(worst_elbow <= 1e-3f);
  CHECK(wrong_side == 0);
  CHECK(not_reached_flag == 0);
  CHECK(reached_flag_wrong == 0);
}

TEST_CASE("two-bone IK corrections equal the quaternion reference's", "[ik]") {
  Rng rng(7u);
  float worst = 0;
  int skipped = 0;
  for (int i = 0; i < 2000; ++i) {
    Chain chain = random_chain(rng, rng.uniform(0.5f, 1.5f), rng.uniform(0.5f, 1.5f));
    const glm::vec3 s = chain.position(0), m = chain.position(1), e = chain.position(2);
    // Well inside the reachable range, so both elbows are well conditioned.
    const float l1 = glm::length(m - s), l2 = glm::length(e - m);
    const float r = std::abs(l1 - l2) + rng.uniform(0.2f, 0.8f) * (l1 + l2 - std::abs(l1 - l2));
    const glm::vec3 target = s + r * rng.direction(), pole = rng.direction();
    const testing::TwoBoneReference ref =
        testing::two_bone_reference(s, m, e, chain.rotation(0), chain.rotation(1), target, pole);
    // Near a half turn the shortest arc's axis is ill-conditioned in both solvers: such chains are skipped.
    const glm::vec3 elbow = ref.elbow, v1 = m - s;
    const glm::quat a = glm::rotation(glm::normalize(v1), glm::normalize(elbow));
    if (glm::dot(glm::normalize(v1), glm::normalize(elbow)) < -0.99f ||
        glm::dot(glm::normalize(a * (e - m)), glm::normalize(ref.reach - elbow)) < -0.99f) {
      ++skipped;
      continue;
    }
    const Solved got = solve(chain, target, pole);
    REQUIRE(got.ok);
    for (const auto& [motor, q] : {std::pair{got.start, ref.start_correction}, std::pair{got.mid, ref.mid_correction}}) {
      const glm::quat g = quat_from_rotor(motor.c[0], motor.c[1], motor.c[2], motor.c[4]);
      worst = std::max(worst, 1.0f - std::abs(glm::dot(g, q)));
    }
  }
  INFO("worst 1 - |<q_job, q_reference>| " << worst << ", " << skipped << " of 2000 chains skipped (a turn > 172 degrees)");
  CHECK(skipped < 100);
  CHECK(worst <= 1e-5f);
}

// The i-th of n random chains of test `seed` with a random target direction and pole.
struct Case {
  float len;
  Chain chain;
  glm::vec3 s, e, u, pole;
};
Case random_case(Rng& rng) {
  const float l1 = rng.uniform(0.5f, 1.5f), l2 = rng.uniform(0.5f, 1.5f);
  Chain chain = random_chain(rng, l1, l2);
  const glm::vec3 s = chain.position(0), e = chain.position(2);
  return {l1 + l2, chain, s, e, rng.direction(), rng.direction()};
}

TEST_CASE("two-bone IK: weight 0 keeps the pose, weight 1/2 lands between", "[ik]") {
  Rng rng(99u);
  for (int i = 0; i < 200; ++i) {
    const Case k = random_case(rng);
    const glm::vec3 target = k.s + 0.7f * k.len * k.u;
    Chain c0 = k.chain, c1 = k.chain, ch = k.chain;
    const Solved w0 = solve(c0, target, k.pole, 0.0f);
    CHECK(glm::length(c0.position(2) - k.e) <= 1e-5f * k.len);
    CHECK_FALSE(w0.reached);
    solve(c1, target, k.pole, 1.0f);
    const Solved half = solve(ch, target, k.pole, 0.5f);
    CHECK_FALSE(half.reached);
    CHECK(glm::length(ch.position(2) - c1.position(2)) > 1e-4f * k.len);
  }
}

TEST_CASE("two-bone IK: soften approaches full extension smoothly and never straightens the chain", "[ik]") {
  Rng rng(98u);
  for (int i = 0; i < 200; ++i) {
    const Case k = random_case(rng);
    float previous = 0.0f;
    for (float f : {0.5f, 0.8f, 0.9f, 1.0f, 1.1f, 1.5f, 3.0f}) {
      Chain c = k.chain;
      const Solved r = solve(c, k.s + f * k.len * k.u, k.pole, 1.0f, 0.8f);
      const float reach = glm::length(c.position(2) - k.s);
      INFO("chain " << i << " target at " << f << " x length");
      if (f <= 0.8f && f * k.len >= std::abs(glm::length(k.chain.position(1) - k.s) -
                                            glm::length(k.e - k.chain.position(1))))
        CHECK(reach == Approx(f * k.len).epsilon(1e-4));
      if (f > 0.8f) {
        CHECK(reach < std::min(f, 1.0f) * k.len);
        CHECK_FALSE(r.reached);
      }
      CHECK(reach < k.len);
      CHECK(reach >= previous - 1e-5f * k.len);  // monotone (to rounding: far targets all land near full reach)
      previous = reach;
    }
  }
}

TEST_CASE("two-bone IK: twist turns the solved chain about the start-target axis, the end still reaches", "[ik]") {
  Rng rng(97u);
  for (int i = 0; i < 200; ++i) {
    const Case k = random_case(rng);
    const float l1 = glm::length(k.chain.position(1) - k.s), l2 = glm::length(k.e - k.chain.position(1));
    const float r = std::abs(l1 - l2) + 0.5f * (k.len - std::abs(l1 - l2));
    const glm::vec3 target = k.s + r * k.u;
    Chain a = k.chain, b = k.chain;
    solve(a, target, k.pole, 1.0f, 1.0f, 0.0f);
    const Solved got = solve(b, target, k.pole, 1.0f, 1.0f, 1.0f);
    CHECK(got.reached);
    CHECK(glm::length(b.position(2) - target) <= 1e-5f * k.len);
    const glm::vec3 want = k.s + glm::angleAxis(1.0f, k.u) * (a.position(1) - k.s);
    CHECK(glm::length(b.position(1) - want) <= 1e-5f * k.len);
  }
}

TEST_CASE("two-bone IK degenerate cases give defined results, not NaN", "[ik][bad-input]") {
  Rng rng(5u);
  const glm::vec3 pole(0.0f, 0.0f, 1.0f);
  SECTION("zero-length first bone: the second bone aims at the target") {
    Chain c = random_chain(rng, 0.0f, 1.0f);
    const glm::vec3 s = c.position(0), target = s + glm::vec3(0.3f, 0.4f, 0.0f);
    const Solved r = solve(c, target, pole);
    REQUIRE(r.ok);
    CHECK(finite(r.start));
    CHECK(finite(r.mid));
    CHECK(glm::length(glm::normalize(c.position(2) - s) - glm::vec3(0.6f, 0.8f, 0.0f)) <= 1e-5f);
    CHECK_FALSE(r.reached);
  }
  SECTION("zero-length second bone: the first bone aims at the target") {
    Chain c = random_chain(rng, 1.0f, 0.0f);
    const glm::vec3 s = c.position(0), target = s + glm::vec3(0.0f, 1.0f, 0.0f);
    const Solved r = solve(c, target, pole);
    CHECK(finite(r.start));
    CHECK(glm::length(c.position(2) - target) <= 1e-5f);
    CHECK(r.reached);
  }
  SECTION("both bones of length zero: nothing moves") {
    Chain c = random_chain(rng, 0.0f, 0.0f);
    const Solved r = solve(c, c.position(0) + glm::vec3(1, 0, 0), pole);
    CHECK(finite(r.start));
    CHECK(finite(r.mid));
    CHECK_FALSE(r.reached);
  }
  SECTION("target on the start joint: the end comes as close as the bones allow (|l1 - l2|)") {
    Chain c = random_chain(rng, 1.0f, 0.6f);
    const glm::vec3 s = c.position(0);
    const Solved r = solve(c, s, pole);
    CHECK(finite(r.start));
    CHECK(finite(r.mid));
    CHECK(glm::length(c.position(2) - s) == Approx(0.4f).epsilon(1e-4));
    CHECK_FALSE(r.reached);
  }
  SECTION("pole along the chain axis, or zero: the current bend direction is kept, the target reached") {
    for (const glm::vec3 p : {glm::vec3(0.0f), glm::vec3(1.0f, 0.0f, 0.0f)}) {
      Chain c = random_chain(rng, 1.0f, 1.0f);
      const glm::vec3 s = c.position(0), target = s + glm::vec3(1.2f, 0.0f, 0.0f);
      const glm::vec3 bend = c.position(1) - s - glm::dot(c.position(1) - s, glm::vec3(1, 0, 0)) * glm::vec3(1, 0, 0);
      const Solved r = solve(c, target, p);
      CHECK(finite(r.start));
      CHECK(glm::length(c.position(2) - target) <= 1e-5f);
      CHECK(glm::dot(c.position(1) - s, bend) >= 0.0f);
    }
  }
  SECTION("a straight chain with the pole on its axis still bends (any perpendicular)") {
    Transform root, mid, end;
    mid.translation = glm::vec3(1, 0, 0), end.translation = glm::vec3(1, 0, 0);
    Chain c(root, mid, end);
    const Solved r = solve(c, glm::vec3(1.5f, 0, 0), glm::vec3(1, 0, 0));
    CHECK(finite(r.start));
    CHECK(glm::length(c.position(2) - glm::vec3(1.5f, 0, 0)) <= 1e-5f);
  }
  SECTION("bad input is refused") {
    Chain c = random_chain(rng, 1.0f, 1.0f);
    Motor a, b;
    TwoBoneIKJob job;
    job.start_joint = &c.model[0], job.mid_joint = &c.model[1], job.end_joint = &c.model[2];
    job.start_joint_correction = &a, job.mid_joint_correction = &b;
    CHECK(job.Validate());
    job.target.x = std::numeric_limits<float>::quiet_NaN();
    CHECK_FALSE(job.Run());
    job.target = glm::vec3(0.0f), job.weight = 1.5f;
    CHECK_FALSE(job.Validate());
    job.weight = 1.0f, job.soften = -0.1f;
    CHECK_FALSE(job.Validate());
    job.soften = 1.0f, job.mid_joint = nullptr;
    CHECK_FALSE(job.Validate());
    job.mid_joint = &c.model[1];
    glm::vec3 given[3] = {c.position(0), c.position(1), c.position(2)};
    job.positions = given;
    CHECK(job.Validate());
    given[1].y = std::numeric_limits<float>::infinity();
    CHECK_FALSE(job.Validate());
    CHECK_FALSE(job.Run());
  }
}

TEST_CASE("aim IK on 10,000 random joints: forward at the target, up toward the pole, reference", "[ik]") {
  Rng rng(4242u);
  float worst_aim = 0, worst_up = 0, worst_ref = 0, worst_moved = 0;
  int near_half_turn = 0;
  for (int i = 0; i < 10000; ++i) {
    Transform x;
    x.translation = glm::vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    x.rotation = rng.rotation();
    x.scale = rng.uniform(0.5f, 2.0f);
    Motor local = motor_from_transform(x);
    const glm::vec3 forward = rng.direction();
    const glm::vec3 up = glm::normalize(glm::cross(forward, rng.direction()));
    const glm::vec3 target = x.translation + rng.uniform(0.1f, 3.0f) * rng.direction();
    // A pole at least ~6 degrees off the aim direction: closer, its projection (the up target) is ill-conditioned.
    glm::vec3 pole = rng.direction();
    const glm::vec3 aim = glm::normalize(target - x.translation);
    while (glm::length(pole - glm::dot(pole, aim) * aim) < 0.1f) pole = rng.direction();
    Motor correction;
    bool reached = false;
    AimIKJob job;
    job.joint = &local, job.target = target, job.forward = forward, job.up = up, job.pole_vector = pole;
    job.joint_correction = &correction, job.reached = &reached;
    REQUIRE(job.Run());
    CHECK(reached);
    const glm::quat ref = testing::aim_reference(x.translation, x.rotation, target, forward, up, pole);
    const glm::quat g = quat_from_rotor(correction.c[0], correction.c[1], correction.c[2], correction.c[4]);
    // Against the reference where the swing is well-conditioned (not within 8 degrees of a half turn).
    if (glm::dot(x.rotation * forward, aim) > -0.99f)
      worst_ref = std::max(worst_ref, 1.0f - std::abs(glm::dot(g, ref)));
    else
      ++near_half_turn;
    apply_ik_correction(local, correction);
    // The corrected joint (a root: local = model) points forward at the target, up toward the pole.
    const glm::vec3 p = motor_transform_point(local, glm::vec3(0.0f));
    worst_moved = std::max(worst_moved, glm::length(p - x.translation));
    const glm::vec3 f = glm::normalize(motor_transform_point(local, forward) - p);
    const glm::vec3 dir = glm::normalize(target - x.translation);
    worst_aim = std::max(worst_aim, glm::length(f - dir));
    const glm::vec3 u = glm::normalize(motor_transform_point(local, up) - p);
    const glm::vec3 pp = glm::normalize(pole - glm::dot(pole, dir) * dir);
    worst_up = std::max(worst_up, glm::length(u - pp));
  }
  INFO("worst: aim " << worst_aim << ", up " << worst_up << ", 1 - |<q, q_ref>| " << worst_ref << " ("
                     << near_half_turn << " near half turns not compared), moved " << worst_moved);
  CHECK(near_half_turn < 100);
  CHECK(worst_aim <= 1e-5f);
  CHECK(worst_up <= 1e-4f);
  CHECK(worst_ref <= 1e-5f);
  CHECK(worst_moved <= 1e-5f);
}

TEST_CASE("aim IK degenerate cases: target on the joint, pole along the aim, opposite forward", "[ik][bad-input]") {
  Motor joint = motor_from_transform(Transform{});
  Motor correction;
  bool reached = true;
  AimIKJob job;
  job.joint = &joint, job.joint_correction = &correction, job.reached = &reached;
  SECTION("target on the joint: no rotation, not reached") {
    REQUIRE(job.Run());
    CHECK(correction.c[0] == 1.0f);
    CHECK_FALSE(reached);
  }
  SECTION("forward exactly opposite the target: a half turn, finite") {
    job.target = glm::vec3(-2.0f, 0.0f, 0.0f);
    REQUIRE(job.Run());
    CHECK(finite(correction));
    const glm::vec3 f = motor_transform_point(motor_mul(joint, correction), glm::vec3(1, 0, 0));
    CHECK(glm::length(f - glm::vec3(-1, 0, 0)) <= 1e-5f);
  }
  SECTION("pole along the aim direction: aimed, no twist") {
    job.target = glm::vec3(0.0f, 0.0f, 3.0f), job.pole_vector = glm::vec3(0.0f, 0.0f, 1.0f);
    REQUIRE(job.Run());
    CHECK(finite(correction));
    const glm::vec3 f = motor_transform_point(motor_mul(joint, correction), glm::vec3(1, 0, 0));
    CHECK(glm::length(f - glm::vec3(0, 0, 1)) <= 1e-5f);
  }
  SECTION("bad input is refused") {
    job.forward = glm::vec3(0.0f);
    CHECK_FALSE(job.Validate());
    job.forward = glm::vec3(1, 0, 0), job.weight = std::numeric_limits<float>::quiet_NaN();
    CHECK_FALSE(job.Run());
  }
}
