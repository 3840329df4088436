// ChainIKJob (runtime/scripts/ik_chain_joint.clu, ik_chain_rotor.clu): hand-computed cases (one hinge, a
// planar two-hinge chain against its law-of-cosines solution), the generated Jacobian against central
// differences of the forward kinematics (LocalToModelJob), hinge limits, weight, orientation targets,
// unreachable and invalid input, and convergence on random reachable targets for 5-, 10- and 20-joint chains
// (cga/testing/chain_ik_cases.hpp, fixed seeds); ChainIKBatchJob (the SIMD batch kernel) on crowds against
// ChainIKJob chain by chain. Corrections are applied to the local pose with
// apply_ik_correction and the model pose recomputed, as an application does.
#include <catch2/catch.hpp>

#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include <ik_chain_joint.hpp>

#include "cga/runtime/ik.hpp"
#include "cga/runtime/ik_chain.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/testing/chain_ik_cases.hpp"

using namespace cga;
using cga::testing::ChainCase;
using cga::testing::ChainSolve;
using cga::testing::SeededRandom;

namespace {

bool finite(const Motor& m) {
  for (float c : m.c)
    if (!std::isfinite(c)) return false;
  return true;
}

// A chain along x: the root at the origin, bones of the given lengths, every joint a hinge about z (a planar
// chain), the effector at the end of the last bone. rest_angles: each joint's local turn about z.
ChainCase planar_chain(const std::vector<float>& lengths, const std::vector<float>& rest_angles) {
  ChainCase c;
  const int n = static_cast<int>(lengths.size());
  for (int j = 0; j < n; ++j) {
    c.skeleton.names.push_back("j" + std::to_string(j));
    c.skeleton.parents.push_back(j - 1);
    Transform t;
    if (j > 0) t.translation = glm::vec3(lengths[j - 1], 0, 0);
    t.rotation = glm::angleAxis(rest_angles[j], glm::vec3(0, 0, 1));
    c.skeleton.rest_local.push_back(t);
    c.local.push_back(motor_from_transform(t));
    c.axes.push_back(glm::vec3(0, 0, 1));
    c.length += lengths[j];
  }
  c.offset = glm::vec3(lengths.back(), 0, 0);
  c.model = c.model_of(c.local);
  return c;
}

// The turn about z of a rotation motor's rotor (a correction about the z hinge).
float z_angle(const Motor& m) {
  const glm::quat q = quat_from_rotor(m.c[0], m.c[1], m.c[2], m.c[4]);
  return 2.0f * std::atan2(q.z, q.w);
}

}  // namespace

TEST_CASE("chain IK: one hinge turns the effector onto the target by the angle between them", "[ik_chain]") {
  ChainCase c = planar_chain({1.0f}, {0.0f});
  c.target = glm::vec3(std::cos(0.7f), std::sin(0.7f), 0.0f);
  const ChainSolve s = testing::solve_chain_case(c, ChainIKJob{});
  REQUIRE(s.ok);
  CHECK(s.reached);
  CHECK(s.error <= 1e-4f);
  CHECK(std::abs(z_angle(s.corrections[0]) - 0.7f) <= 1e-4f);
  // The rotor is the quaternion (cos 0.35, 0, 0, sin 0.35): no tilt off the hinge.
  CHECK(std::abs(s.corrections[0].c[2]) <= 1e-6f);
  CHECK(std::abs(s.corrections[0].c[4]) <= 1e-6f);
}

TEST_CASE("chain IK: a planar two-hinge chain takes the law-of-cosines solution", "[ik_chain]") {
  // Bones 1 and 0.8, bent by 0.3 rad at the elbow (the straight chain is singular: no radial motion).
  const float l1 = 1.0f, l2 = 0.8f;
  for (const glm::vec3 target : {glm::vec3(1.2f, 0.6f, 0.0f), glm::vec3(-0.4f, 1.1f, 0.0f), glm::vec3(0.5f, -0.2f, 0.0f)}) {
    ChainCase c = planar_chain({l1, l2}, {0.0f, 0.3f});
    c.target = target;
    const ChainSolve s = testing::solve_chain_case(c, ChainIKJob{});
    REQUIRE(s.ok);
    CHECK(s.reached);
    CHECK(s.error <= 1e-4f * (l1 + l2));
    // Analytic: elbow angle q2 = +-acos((d^2 - l1^2 - l2^2) / (2 l1 l2)) (either branch solves; the one the
    // solver took), shoulder q1 = atan2(y, x) - atan2(l2 sin q2, l1 + l2 cos q2).
    const float got1 = z_angle(s.corrections[0]), got2 = 0.3f + z_angle(s.corrections[1]);
    const float d2 = glm::dot(target, target);
    const float q2 = std::copysign(std::acos((d2 - l1 * l1 - l2 * l2) / (2 * l1 * l2)), got2);
    const float q1 = std::atan2(target.y, target.x) - std::atan2(l2 * std::sin(q2), l1 + l2 * std::cos(q2));
    INFO("target " << target.x << " " << target.y << ": q1 " << got1 << " vs " << q1 << ", q2 " << got2 << " vs "
                   << q2);
    CHECK(std::abs(std::remainder(got1 - q1, 2.0f * float(M_PI))) <= 2e-4f);
    CHECK(std::abs(std::remainder(got2 - q2, 2.0f * float(M_PI))) <= 2e-4f);
  }
}

TEST_CASE("chain IK: a straight chain pulled along its own line bends and reaches", "[ik_chain]") {
  // Singular: no joint moves the effector along the chain to first order, so no damped step helps until the
  // job bends the stalled chain once.
  for (const bool free : {false, true}) {
    ChainCase c = planar_chain({1.0f, 1.0f, 1.0f}, {0.0f, 0.0f, 0.0f});
    if (free) c.axes.assign(3, glm::vec3(0.0f));
    c.target = glm::vec3(2.0f, 0.0f, 0.0f);
    const ChainSolve s = testing::solve_chain_case(c, ChainIKJob{});
    REQUIRE(s.ok);
    CHECK(s.reached);
    CHECK(s.error <= 1e-4f * 3.0f);
  }
}

TEST_CASE("chain IK: the generated Jacobian column equals central differences of forward kinematics",
          "[ik_chain]") {
  SeededRandom rng(4242u);
  const ChainCase c = testing::random_chain_case(rng, 6);
  const glm::vec3 e = c.effector(c.model);
  const glm::vec3 u = motor_transform_point(c.model.back(), glm::vec3(1, 0, 0)) -
                      motor_transform_point(c.model.back(), glm::vec3(0.0f));
  const glm::vec3 w = motor_transform_point(c.model.back(), glm::vec3(0, 1, 0)) -
                      motor_transform_point(c.model.back(), glm::vec3(0.0f));
  const float h = 1e-2f;
  float worst = 0.0f;
  for (int j = 0; j < 6; ++j)
    for (const glm::vec3 axis : {c.axes[j], glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), glm::vec3(0, 0, 1)}) {
      const glm::vec3 a = glm::normalize(axis);
      float P[4], U[3], W[3], dP[4], dU[3], dW[3];
      const RigidMotor g = rigid_blades(c.model[j]);
      kernels::ik_chain_joint(g.data(), a.x, a.y, a.z, 0.0f, e.x, e.y, e.z, u.x, u.y, u.z, w.x, w.y, w.z, P, U, W, dP,
                              dU, dW);
      CHECK(std::abs(P[3] - 1.0f) <= 1e-5f);
      CHECK(glm::length(glm::vec3(P[0], P[1], P[2]) - e) <= 1e-5f * c.length);
      // Forward kinematics with the joint turned by +-h about its local axis.
      glm::vec3 fe[2], fu[2], fw[2];
      for (int k = 0; k < 2; ++k) {
        std::vector<Motor> local = c.local;
        Transform t;
        t.rotation = glm::angleAxis(k == 0 ? h : -h, a);
        apply_ik_correction(local[j], motor_from_transform(t));
        const std::vector<Motor> m = c.model_of(local);
        fe[k] = c.effector(m);
        const glm::vec3 o = motor_transform_point(m.back(), glm::vec3(0.0f));
        fu[k] = motor_transform_point(m.back(), glm::vec3(1, 0, 0)) - o;
        fw[k] = motor_transform_point(m.back(), glm::vec3(0, 1, 0)) - o;
      }
      const glm::vec3 de = (fe[0] - fe[1]) / (2 * h), du = (fu[0] - fu[1]) / (2 * h), dw = (fw[0] - fw[1]) / (2 * h);
      worst = std::max({worst, glm::length(de - glm::vec3(dP[0], dP[1], dP[2])) / c.length,
                        glm::length(du - glm::vec3(dU[0], dU[1], dU[2])), glm::length(dw - glm::vec3(dW[0], dW[1], dW[2]))});
      CHECK(std::abs(dP[3]) <= 1e-5f);
    }
  INFO("worst difference " << worst);
  CHECK(worst <= 2e-4f);
}

TEST_CASE("chain IK: hinge limits hold the corrections in range", "[ik_chain]") {
  ChainCase c = planar_chain({1.0f, 1.0f, 1.0f}, {0.0f, 0.2f, 0.2f});
  c.target = glm::vec3(0.0f, 2.0f, 0.0f);  // needs far more than 0.25 rad per joint
  const std::vector<float> lo(3, -0.25f), hi(3, 0.25f);
  ChainIKJob job;
  job.min_angles = lo, job.max_angles = hi;
  const ChainSolve s = testing::solve_chain_case(c, job);
  REQUIRE(s.ok);
  CHECK_FALSE(s.reached);
  for (const Motor& m : s.corrections) {
    REQUIRE(finite(m));
    CHECK(z_angle(m) <= 0.25f + 1e-5f);
    CHECK(z_angle(m) >= -0.25f - 1e-5f);
  }
  // The best the limits allow toward (0, 2): every joint at its upper limit.
  for (const Motor& m : s.corrections) CHECK(z_angle(m) == Approx(0.25f).margin(1e-3));
  // A target inside the limits is reached with them.
  ChainCase near = planar_chain({1.0f, 1.0f, 1.0f}, {0.0f, 0.2f, 0.2f});
  near.target = near.effector(near.model_of({near.local[0], motor_mul(near.local[1], motor_from_transform(
                                                                                         {{}, glm::angleAxis(0.1f, glm::vec3(0, 0, 1)), 1.0f})),
                                             near.local[2]}));
  const ChainSolve t = testing::solve_chain_case(near, job);
  CHECK(t.reached);
  for (const Motor& m : t.corrections) CHECK(std::abs(z_angle(m)) <= 0.25f + 1e-5f);
}

TEST_CASE("chain IK: weight 0 leaves the pose, weight 1/2 goes part of the way", "[ik_chain]") {
  SeededRandom rng(7u);
  const ChainCase c = testing::random_chain_case(rng, 5);
  ChainIKJob job;
  job.weight = 0.0f;
  const ChainSolve s = testing::solve_chain_case(c, job);
  REQUIRE(s.ok);
  CHECK_FALSE(s.reached);
  CHECK(s.iterations == 0);
  for (const Motor& m : s.corrections) CHECK(m.c == Motor::identity().c);
  job.weight = 0.5f;
  const ChainSolve half = testing::solve_chain_case(c, job);
  const ChainSolve full = testing::solve_chain_case(c, ChainIKJob{});
  REQUIRE(half.ok);
  CHECK_FALSE(half.reached);
  for (std::size_t j = 0; j < c.local.size(); ++j) {
    // nlerp halfway from the identity: the half correction's angle lies strictly between 0 and the full one.
    const float a_half = 2.0f * std::acos(std::min(1.0f, std::abs(half.corrections[j].c[0])));
    const float a_full = 2.0f * std::acos(std::min(1.0f, std::abs(full.corrections[j].c[0])));
    CHECK(a_half <= a_full + 1e-6f);
  }
}

TEST_CASE("chain IK: an orientation target turns the end frame too", "[ik_chain]") {
  SeededRandom rng(99u);
  int reached = 0;
  for (int i = 0; i < 20; ++i) {
    const ChainCase c = testing::random_chain_case(rng, 6, /*free=*/true);
    ChainIKJob job;
    job.target_orientation = &c.target_orientation;
    job.max_iterations = 100;
    const ChainSolve s = testing::solve_chain_case(c, job);
    REQUIRE(s.ok);
    if (!s.reached) continue;
    ++reached;
    CHECK(s.error <= 1e-4f * c.length);
    const glm::quat want = glm::normalize(quat_from_rotor(c.target_orientation.c[0], c.target_orientation.c[1],
                                                          c.target_orientation.c[2], c.target_orientation.c[4]));
    const Motor& tip = s.model.back();
    const glm::quat got = glm::normalize(quat_from_rotor(tip.c[0], tip.c[1], tip.c[2], tip.c[4]));
    CHECK(std::abs(glm::dot(want, got)) >= 1.0f - 1e-5f);
  }
  INFO("reached " << reached << " of 20");
  CHECK(reached >= 18);
}

TEST_CASE("chain IK: an unreachable target stretches the chain toward it", "[ik_chain]") {
  ChainCase c = planar_chain({1.0f, 1.0f, 1.0f}, {0.0f, 0.4f, -0.3f});
  const glm::vec3 dir = glm::normalize(glm::vec3(1.0f, 2.0f, 0.5f));
  c.target = 10.0f * dir;
  // The z hinges keep the chain in its plane: free joints can point it anywhere.
  c.axes.assign(3, glm::vec3(0.0f));
  ChainIKJob job;
  job.max_iterations = 200;
  const ChainSolve s = testing::solve_chain_case(c, job);
  REQUIRE(s.ok);
  CHECK_FALSE(s.reached);
  for (const Motor& m : s.corrections) REQUIRE(finite(m));
  // Fully stretched along the target direction: 3 from the root, 7 short of the target.
  const glm::vec3 e = c.effector(s.model);
  CHECK(glm::length(e - 3.0f * dir) <= 1e-2f);
  CHECK(s.error == Approx(7.0f).margin(1e-2));
}

TEST_CASE("chain IK: invalid input is refused and leaves the outputs", "[ik_chain]") {
  SeededRandom rng(5u);
  const ChainCase c = testing::random_chain_case(rng, 4);
  Motor sentinel;
  sentinel.c.fill(7.0f);
  std::vector<Motor> out(4, sentinel);
  bool reached = true;
  int iterations = -3;
  ChainIKJob good;
  good.joints = c.model, good.axes = c.axes, good.effector_offset = c.offset, good.target = c.target;
  good.corrections = out, good.reached = &reached, good.iterations = &iterations;
  REQUIRE(good.Validate());
  const auto refused = [&](const ChainIKJob& job) {
    CHECK_FALSE(job.Validate());
    CHECK_FALSE(job.Run());
    for (const Motor& m : out) CHECK(m.c == sentinel.c);
    CHECK(reached);
    CHECK(iterations == -3);
  };
  ChainIKJob job = good;
  job.joints = {}, job.corrections = {};
  refused(job);  // zero-length chain
  job = good, job.target.y = std::numeric_limits<float>::quiet_NaN();
  refused(job);
  job = good, job.target.x = std::numeric_limits<float>::infinity();
  refused(job);
  job = good, job.corrections = std::span<Motor>(out).first(3);
  refused(job);
  job = good, job.axes = std::span<const glm::vec3>(c.axes).first(2);
  refused(job);
  job = good, job.weight = 1.5f;
  refused(job);
  job = good, job.weight = std::numeric_limits<float>::quiet_NaN();
  refused(job);
  job = good, job.max_iterations = 0;
  refused(job);
  job = good, job.damping = 0.0f;
  refused(job);
  const std::vector<float> lo(4, 0.1f), hi(4, 1.0f), nan4(4, std::numeric_limits<float>::quiet_NaN());
  job = good, job.min_angles = lo, job.max_angles = hi;  // 0 outside [min, max]
  refused(job);
  job = good, job.min_angles = nan4, job.max_angles = hi;
  refused(job);
  job = good, job.min_angles = lo;  // one without the other
  refused(job);
  std::vector<Motor> bad = c.model;
  bad[2].c[5] = std::numeric_limits<float>::quiet_NaN();
  job = good, job.joints = bad;
  refused(job);
  Motor bad_orientation;
  bad_orientation.c[1] = std::numeric_limits<float>::quiet_NaN();
  job = good, job.target_orientation = &bad_orientation;
  refused(job);
  REQUIRE(good.Run());
  for (const Motor& m : out) CHECK(finite(m));
}

TEST_CASE("chain IK: a target on the effector needs no iteration, and a scaled chain solves like a rigid one",
          "[ik_chain]") {
  ChainCase c = planar_chain({1.0f, 1.0f}, {0.0f, 0.5f});
  c.target = c.effector(c.model);
  const ChainSolve s = testing::solve_chain_case(c, ChainIKJob{});
  REQUIRE(s.ok);
  CHECK(s.reached);
  CHECK(s.iterations == 0);
  for (const Motor& m : s.corrections) CHECK(m.c == Motor::identity().c);
  // Root scale 2: bones and effector twice as long in model space.
  ChainCase scaled = planar_chain({1.0f, 1.0f}, {0.0f, 0.5f});
  scaled.skeleton.rest_local[0].scale = 2.0f;
  scaled.local[0] = motor_from_transform(scaled.skeleton.rest_local[0]);
  scaled.model = scaled.model_of(scaled.local);
  scaled.target = glm::vec3(1.0f, 2.5f, 0.0f);
  const ChainSolve t = testing::solve_chain_case(scaled, ChainIKJob{});
  REQUIRE(t.ok);
  CHECK(t.reached);
  CHECK(t.error <= 1e-4f * 4.0f);
}

TEST_CASE("chain IK converges on random reachable targets: 5, 10 and 20 hinges, and free joints", "[ik_chain]") {
  // Targets from every joint turned by up to pi (cga/testing/chain_ik_cases.hpp). Success: the effector
  // within 1e-4 of the chain length (the job's default tolerance), default settings (64 trials, damping 0.05).
  // The thresholds sit below the rates measured (docs/runtime.md).
  struct Row {
    int joints;
    bool free;
    double min_rate;
  };
  for (const Row row : {Row{5, false, 0.95}, Row{10, false, 0.99}, Row{20, false, 0.99}, Row{10, true, 0.99}}) {
    SeededRandom rng(1000u + static_cast<std::uint32_t>(row.joints) + (row.free ? 7u : 0u));
    const int cases = 500;
    int ok = 0, reached_flag = 0;
    long iterations = 0;
    for (int i = 0; i < cases; ++i) {
      const ChainCase c = testing::random_chain_case(rng, row.joints, row.free, float(M_PI));
      const ChainSolve s = testing::solve_chain_case(c, ChainIKJob{});
      REQUIRE(s.ok);
      for (const Motor& m : s.corrections) REQUIRE(finite(m));
      const bool hit = s.error <= 1e-4f * c.length;
      ok += hit;
      reached_flag += s.reached;
      iterations += s.iterations;
    }
    const double rate = double(ok) / cases;
    std::printf("chain IK %2d %s joints: success %.3f, reached flag %.3f, mean trials %.1f\n", row.joints,
                row.free ? "free " : "hinge", rate, double(reached_flag) / cases, double(iterations) / cases);
    CHECK(rate >= row.min_rate);
  }
}

TEST_CASE("chain IK batch: a crowd solves as ChainIKJob solves each chain", "[ik_chain]") {
  SeededRandom rng(31u);
  for (const bool oriented : {false, true}) {
    const int chains = oriented ? 50 : 300, n = 10;
    const testing::ChainCrowd crowd = testing::random_crowd(rng, chains, n);
    std::vector<Motor> out(crowd.joints.size());
    std::vector<std::uint8_t> reached(chains);
    std::vector<int> iterations(chains);
    ChainIKBatchJob batch;
    batch.chain_joints = n, batch.joints = crowd.joints, batch.axes = crowd.axes;
    batch.effector_offset = crowd.offset, batch.targets = crowd.targets;
    if (oriented) batch.target_orientations = crowd.orientations;
    batch.corrections = out, batch.reached = reached, batch.iterations = iterations;
    REQUIRE(batch.Run());
    int hits = 0, same = 0;
    float worst = 0.0f;
    for (int c = 0; c < chains; ++c) {
      std::vector<Motor> single(n);
      bool r = false;
      int it = 0;
      ChainIKJob job;
      job.joints = std::span<const Motor>(crowd.joints).subspan(static_cast<std::size_t>(c * n), n);
      job.axes = crowd.axes, job.effector_offset = crowd.offset, job.target = crowd.targets[c];
      if (oriented) job.target_orientation = &crowd.orientations[c];
      job.corrections = single, job.reached = &r, job.iterations = &it;
      REQUIRE(job.Run());
      hits += reached[c];
      if (r == bool(reached[c]) && it == iterations[c]) {
        ++same;
        for (int j = 0; j < n; ++j)
          for (int k = 0; k < 12; ++k) worst = std::max(worst, std::abs(single[j].c[k] - out[c * n + j].c[k]));
      }
      for (int j = 0; j < n; ++j) REQUIRE(finite(out[c * n + j]));
    }
    std::printf("chain IK batch, %d chains of %d hinges%s: reached %.3f, same flag and trials as ChainIKJob %.3f, "
                "worst coefficient difference then %.2g\n",
                chains, n, oriented ? " with orientation" : "", double(hits) / chains, double(same) / chains,
                double(worst));
    CHECK(double(hits) / chains >= (oriented ? 0.9 : 0.99));
    CHECK(double(same) / chains >= 0.9);
    CHECK(worst <= 1e-3f);
  }
}

TEST_CASE("chain IK batch: invalid input is refused and leaves the outputs", "[ik_chain]") {
  SeededRandom rng(8u);
  const testing::ChainCrowd crowd = testing::random_crowd(rng, 3, 4);
  Motor sentinel;
  sentinel.c.fill(7.0f);
  std::vector<Motor> out(12, sentinel);
  ChainIKBatchJob good;
  good.chain_joints = 4, good.joints = crowd.joints, good.axes = crowd.axes, good.targets = crowd.targets;
  good.corrections = out;
  REQUIRE(good.Validate());
  std::vector<glm::vec3> nan_target = crowd.targets;
  nan_target[1].z = std::numeric_limits<float>::quiet_NaN();
  std::vector<std::uint8_t> two(2);
  for (int k = 0; k < 6; ++k) {
    ChainIKBatchJob job = good;
    if (k == 0) job.chain_joints = 0;
    if (k == 1) job.joints = {}, job.corrections = {};
    if (k == 2) job.chain_joints = 5;  // 12 joints are not chains of 5
    if (k == 3) job.targets = std::span<const glm::vec3>(crowd.targets).first(2);
    if (k == 4) job.targets = nan_target;
    if (k == 5) job.reached = two;
    CHECK_FALSE(job.Validate());
    CHECK_FALSE(job.Run());
    for (const Motor& m : out) CHECK(m.c == sentinel.c);
  }
  REQUIRE(good.Run());
}
