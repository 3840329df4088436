// The interface between the arm benchmark's harness (ik_bench.cpp) and the implementations it times: each
// computes the 5-joint arm's chain (arm5.clu) for one set of joint angles and writes what it produced into
// an ArmResult, so that the harness can check the implementations against each other.
#pragma once

namespace cga::bench_arm {

// The gripper point's Euclidean coordinates, and the scalar parts of the five joint rotors: enough to see
// that two implementations computed the same chain (each rotor's scalar part is cos-like in its angle).
struct ArmResult {
  double gripper[3];
  double rotor_scalars[5];
};

using ArmFunction = void (*)(const double angles[5], ArmResult& out);

}  // namespace cga::bench_arm
