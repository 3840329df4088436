// Random joint chains with reachable targets for ChainIKJob (tests/runtime/test_ik_chain.cpp, bench/bench_ik.cpp),
// from SeededRandom (the same numbers with every standard library). A chain of n joints: the root at a random
// place and rotation, each child a bone of length 0.5..1.5 along a random direction with a random rotation,
// hinge axes random unit vectors of each joint's frame (or all free), the end effector 0.5..1 from the tip.
// The target is where the effector goes when every hinge turns by a random angle in [-max_turn, max_turn]
// (free joints by a random rotation of up to max_turn), so it is reachable; the orientation target is the
// tip's rotation there. Header-only.
#pragma once

#include <cmath>
#include <vector>

#include "cga/runtime/ik.hpp"
#include "cga/runtime/ik_chain.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/testing/seeded_random.hpp"

namespace cga::testing {

struct ChainCase {
  Skeleton skeleton;
  std::vector<Motor> local, model;  // the animated pose
  std::vector<glm::vec3> axes;      // hinge axes (zero: free)
  glm::vec3 offset{0.0f};           // the effector in the tip's frame
  glm::vec3 target{0.0f};
  Motor target_orientation;         // the tip's model motor in the target pose
  float length = 0.0f;              // bones plus the effector offset

  // The model pose of local (every joint's parent the joint before it).
  std::vector<Motor> model_of(const std::vector<Motor>& l) const {
    std::vector<Motor> out(l.size());
    LocalToModelJob{&skeleton, l, out}.Run();
    return out;
  }
  glm::vec3 effector(const std::vector<Motor>& m) const { return motor_transform_point(m.back(), offset); }
};

inline glm::vec3 random_direction(SeededRandom& rng) {
  for (;;) {
    const glm::vec3 v(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const float n = glm::length(v);
    if (n > 0.1f && n <= 1.0f) return v / n;
  }
}

inline glm::quat random_rotation(SeededRandom& rng) {
  for (;;) {
    const glm::quat q(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const float n = glm::length(q);
    if (n > 0.1f && n <= 1.0f) return q / n;
  }
}

// A chain of n joints; free: every joint free (3 DOF), else hinges; the target pose turns each joint by up to
// max_turn rad.
inline ChainCase random_chain_case(SeededRandom& rng, int n, bool free = false, float max_turn = 1.0f) {
  ChainCase c;
  c.local.resize(n);
  c.axes.resize(n);
  std::vector<Motor> moved(n);
  for (int j = 0; j < n; ++j) {
    c.skeleton.names.push_back("j" + std::to_string(j));
    c.skeleton.parents.push_back(j - 1);
    Transform t;
    if (j == 0) {
      t.translation = glm::vec3(rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2));
    } else {
      const float l = rng.uniform(0.5f, 1.5f);
      t.translation = l * random_direction(rng);
      c.length += l;
    }
    t.rotation = random_rotation(rng);
    c.skeleton.rest_local.push_back(t);
    c.local[j] = motor_from_transform(t);
    c.axes[j] = free ? glm::vec3(0.0f) : random_direction(rng);
    // The target pose: the joint turned about its axis (or a random one) by up to 1 rad.
    const glm::vec3 axis = free ? random_direction(rng) : c.axes[j];
    Transform turn;
    turn.rotation = glm::angleAxis(rng.uniform(-max_turn, max_turn), axis);
    moved[j] = motor_mul(c.local[j], motor_from_transform(turn));
  }
  const float l = rng.uniform(0.5f, 1.0f);
  c.offset = l * random_direction(rng);
  c.length += l;
  c.model = c.model_of(c.local);
  const std::vector<Motor> target_model = c.model_of(moved);
  c.target = c.effector(target_model);
  c.target_orientation = target_model.back();
  return c;
}

// A crowd for ChainIKBatchJob: one rig (random_chain_case's, hinges), chains posed differently (each joint
// turned by up to 0.5 rad about its hinge, the root moved by up to 1), each with a reachable target (its
// joints turned further by up to max_turn) and that pose's tip rotation.
struct ChainCrowd {
  int chain_joints = 0;
  std::vector<glm::vec3> axes;
  glm::vec3 offset{0.0f};
  std::vector<Motor> joints;  // chain c at [c chain_joints, (c + 1) chain_joints)
  std::vector<glm::vec3> targets;
  std::vector<Motor> orientations;
  float length = 0.0f;
};

inline ChainCrowd random_crowd(SeededRandom& rng, int chains, int n, float max_turn = 3.14159265f) {
  const ChainCase rig = random_chain_case(rng, n);
  ChainCrowd crowd;
  crowd.chain_joints = n, crowd.axes = rig.axes, crowd.offset = rig.offset, crowd.length = rig.length;
  const auto turned = [&](std::vector<Motor> local, float by) {
    for (int j = 0; j < n; ++j) {
      Transform t;
      t.rotation = glm::angleAxis(rng.uniform(-by, by), rig.axes[j]);
      local[j] = motor_mul(local[j], motor_from_transform(t));
    }
    return local;
  };
  for (int c = 0; c < chains; ++c) {
    std::vector<Motor> local = turned(rig.local, 0.5f);
    Transform shift;
    shift.translation = glm::vec3(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    local[0] = motor_mul(motor_from_transform(shift), local[0]);
    const std::vector<Motor> model = rig.model_of(local), target_model = rig.model_of(turned(local, max_turn));
    crowd.joints.insert(crowd.joints.end(), model.begin(), model.end());
    crowd.targets.push_back(rig.effector(target_model));
    crowd.orientations.push_back(target_model.back());
  }
  return crowd;
}

// Runs ChainIKJob on the case and applies the corrections; returns the solved local pose.
struct ChainSolve {
  bool ok = false, reached = false;
  int iterations = 0;
  std::vector<Motor> corrections, local, model;
  float error = 0.0f;  // effector to target
};

inline ChainSolve solve_chain_case(const ChainCase& c, ChainIKJob job) {
  ChainSolve s;
  s.corrections.resize(c.local.size());
  job.joints = c.model;
  if (job.axes.empty()) job.axes = c.axes;
  job.effector_offset = c.offset;
  job.target = c.target;
  job.corrections = s.corrections;
  job.reached = &s.reached;
  job.iterations = &s.iterations;
  s.ok = job.Run();
  s.local = c.local;
  for (std::size_t j = 0; j < s.local.size(); ++j) apply_ik_correction(s.local[j], s.corrections[j]);
  s.model = c.model_of(s.local);
  s.error = glm::length(c.effector(s.model) - job.target);
  return s;
}

}  // namespace cga::testing
