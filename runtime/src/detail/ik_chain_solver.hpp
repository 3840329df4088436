// ChainIKJob's solver (src/ik_chain.cpp), shared with ChainIKBatchJob (src/ik_chain_batch.cpp), which runs
// many of them in lockstep and fills their Jacobians with the SIMD batch kernel. Internal to cga::runtime.
// One Solver is one chain: init() reads the job, then while active() a Jacobian is filled (jacobian() with
// the scalar kernels, or by the caller through store_column()) and step() takes one
// Levenberg-Marquardt trial; finish() writes the outputs.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

#include <ik_chain_joint.hpp>
#include <ik_chain_joint_position.hpp>
#include <ik_chain_rotor.hpp>

#include "cga/runtime/ik_chain.hpp"
#include "cga/runtime/motor.hpp"
#include "ik_weight.hpp"

namespace cga::ik_chain_detail {


inline constexpr int kMaxRows = 9;

inline bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
inline bool finite(const Motor& m) {
  for (float c : m.c)
    if (!std::isfinite(c)) return false;
  return true;
}

// The rigid part T*R of a model-space motor (a scaled joint's scale dropped: the rotations the job turns
// about the joint's origin commute with a uniform scale).
inline RigidMotor rigid_part(const Motor& m) { return rigid_blades(motor_is_rigid(m) ? m : motor_rigid(m)); }

inline RigidMotor rigid_mul(const RigidMotor& a, const RigidMotor& b) {
  RigidMotor c;
  kernels::motor_mul_rigid(a.data(), b.data(), c.data());
  return c;
}

inline RigidMotor rigid_reverse(const RigidMotor& a) { return rigid_blades(motor_reverse(motor_from_rigid(a))); }

inline glm::vec3 rigid_point(const RigidMotor& m, const glm::vec3& p) { return motor_transform_point(motor_from_rigid(m), p); }

// A direction turned by the rotor part of a rigid motor (its translation blades dropped).
inline glm::vec3 rigid_direction(const RigidMotor& m, const glm::vec3& d) {
  Motor r;
  r.c[0] = m[0], r.c[1] = m[1], r.c[2] = m[2], r.c[4] = m[4];
  return motor_transform_point(r, d);
}

// The rotation motor of the turn by `angle` about the unit `axis` (generated ik_chain_rotor).
inline RigidMotor turn(const glm::vec3& axis, float angle) {
  float r[4];
  kernels::ik_chain_rotor(axis.x, axis.y, axis.z, angle, r);
  return {r[0], r[1], r[2], 0.0f, r[3], 0.0f, 0.0f, 0.0f};
}

// The weighted correction of a rotation motor's rotor (normalized first), as the other IK jobs weigh theirs.
inline Motor weighted(const RigidMotor& c, float w) {
  return ik_detail::rotation_motor(ik_detail::weighted(glm::normalize(quat_from_rotor(c[0], c[1], c[2], c[4])), w));
}

// Solves (A + mu I) y = r for the symmetric positive semi-definite m x m A by Cholesky (mu > 0).
inline void solve_damped(const double* a, double mu, const double* r, int m, double* y) {
  double l[kMaxRows][kMaxRows] = {};
  for (int i = 0; i < m; ++i)
    for (int j = 0; j <= i; ++j) {
      double s = a[i * m + j] + (i == j ? mu : 0.0);
      for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
      l[i][j] = i == j ? std::sqrt(std::max(s, 1e-300)) : s / l[j][j];
    }
  double z[kMaxRows];
  for (int i = 0; i < m; ++i) {
    double s = r[i];
    for (int k = 0; k < i; ++k) s -= l[i][k] * z[k];
    z[i] = s / l[i][i];
  }
  for (int i = m - 1; i >= 0; --i) {
    double s = z[i];
    for (int k = i + 1; k < m; ++k) s -= l[k][i] * y[k];
    y[i] = s / l[i][i];
  }
}

// The solver's state and scratch for one chain.
class Solver {
 public:
  // Reads a valid job (Validate() true).
  explicit Solver(const ChainIKJob& job);

  // Weight 0 leaves the pose: no trials.
  bool active() const { return job_.weight > 0.0f && !hit_ && it_ < job_.max_iterations && lambda_ <= lambda_max_; }
  int columns() const { return cols_; }
  bool oriented() const { return oriented_; }
  // Column c's joint, its axis in the joint's frame, the posed joint's rigid model motor, the current effector
  // and end frame axes: the inputs of ik_chain_joint for that column.
  int joint_of(int c) const { return col_joint_[c]; }
  glm::vec3 axis_of(int c) const;
  const RigidMotor& posed(int j) const { return cur_.model[j]; }
  const glm::vec3& effector() const { return cur_.e; }
  const glm::vec3& frame_x() const { return cur_.u; }
  const glm::vec3& frame_y() const { return cur_.w; }
  // Column c from ik_chain_joint's outputs P, P_d_a, U_d_a, W_d_a (with an orientation target), or from
  // ik_chain_joint_position's P_d_a (without: the posed motors are rigid and unit, so P's weight is 1).
  void store_column(int c, const float* P, const float* dP, const float* dU, const float* dW);
  void store_position_column(int c, const float* dP) {
    for (int i = 0; i < 3; ++i) jac_[i * cols_ + c] = dP[i];
  }
  void jacobian();  // every column by the scalar kernel
  void step();      // one trial on the stored Jacobian
  void finish() const;

 private:
  struct State {
    std::vector<float> angle;            // per hinge
    std::vector<RigidMotor> rot, model;  // per free joint its rotation; the posed chain
    glm::vec3 e{0.0f}, u{0.0f}, w{0.0f};
    float r[kMaxRows] = {};
    double err2 = 0.0;
  };
  bool hinge(int j) const { return axis_[j] != glm::vec3(0.0f); }
  void pose(State& s) const;
  void kick();
  bool done(const State& s) const;

  const ChainIKJob& job_;
  int n_ = 0, m_ = 3, cols_ = 0, it_ = 0;
  bool oriented_ = false, hit_ = false, kicked_ = false;
  float length_ = 0.0f, lambda_min_ = 0.0f, orient_scale_ = 0.0f;
  double lambda_ = 0.0, lambda_max_ = 0.0;
  std::vector<RigidMotor> rel_;  // ~G[j-1] G[j] of the input rigid motors (rel[0] = G[0])
  std::vector<glm::vec3> axis_;  // unit hinge axes; zero for a free joint
  std::vector<int> col_, col_joint_;  // first column of each joint; joint of each column
  glm::vec3 effector_local_{0.0f}, ut_{1, 0, 0}, wt_{0, 1, 0};
  State cur_, next_;
  std::vector<float> jac_, step_, held_angle_;  // jac_: m x cols, row-major
  std::vector<char> held_;
};

}  // namespace cga::ik_chain_detail
