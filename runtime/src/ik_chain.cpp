// ChainIKJob (see ik_chain.hpp): damped least squares with Levenberg-Marquardt step control. The geometry is
// generated: each joint's Jacobian column comes from ik_chain_joint (the effector and the end frame's axes
// turned about the joint's axis line, differentiated by the angle at 0; without an orientation target its
// effector derivative alone, ik_chain_joint_position), the corrections' rotors from
// ik_chain_rotor, the forward kinematics from motor_mul_rigid and transform_point. This file does the plain
// numerics: the m x m normal equations (m = 3, or 9 with an orientation target), the limits (an active set:
// a hinge whose step would cross its limit is held there and the step solved again without it), the
// acceptance of steps and the weight. The solver (detail/ik_chain_solver.hpp) is shared with ChainIKBatchJob.
#include "cga/runtime/ik_chain.hpp"

#include "detail/ik_chain_solver.hpp"

namespace cga {

namespace ik_chain_detail {

Solver::Solver(const ChainIKJob& job) : job_(job) {
  const std::span<const Motor> joints = job.joints;
  const int n = n_ = static_cast<int>(joints.size());
  std::vector<RigidMotor> base(n);
  rel_.resize(n), axis_.assign(n, glm::vec3(0.0f)), col_.resize(n);
  for (int j = 0; j < n; ++j) {
    base[j] = rigid_part(joints[j]);
    rel_[j] = j == 0 ? base[0] : rigid_mul(rigid_reverse(base[j - 1]), base[j]);
    if (!job.axes.empty() && glm::length(job.axes[j]) > 0.0f) axis_[j] = glm::normalize(job.axes[j]);
    col_[j] = cols_;
    cols_ += hinge(j) ? 1 : 3;
    col_joint_.resize(cols_, j);
  }
  // The effector in the tip's rigid frame (where the animated, possibly scaled, tip puts it), the chain length.
  const glm::vec3 effector = motor_transform_point(joints[n - 1], job.effector_offset);
  effector_local_ = rigid_point(rigid_reverse(base[n - 1]), effector);
  glm::vec3 prev = rigid_point(base[0], glm::vec3(0.0f));
  for (int j = 1; j < n; ++j) {
    const glm::vec3 p = rigid_point(base[j], glm::vec3(0.0f));
    length_ += glm::length(p - prev);
    prev = p;
  }
  length_ += glm::length(effector - prev);
  length_ = std::max(length_, 1e-6f * std::max(1.0f, glm::length(job.target)));
  lambda_ = lambda_min_ = job.damping * length_;
  lambda_max_ = 1e4 * length_;
  oriented_ = job.target_orientation && job.orientation_weight > 0.0f;
  if (oriented_) {
    const RigidMotor t = rigid_part(*job.target_orientation);
    ut_ = rigid_direction(t, glm::vec3(1, 0, 0)), wt_ = rigid_direction(t, glm::vec3(0, 1, 0));
    m_ = 9;
    orient_scale_ = job.orientation_weight * length_;
  }
  for (State* s : {&cur_, &next_}) {
    s->angle.assign(n, 0.0f);
    s->rot.assign(n, RigidMotor{1, 0, 0, 0, 0, 0, 0, 0});
    s->model.resize(n);
  }
  pose(cur_);
  hit_ = done(cur_);
  jac_.resize(static_cast<std::size_t>(m_) * cols_), step_.resize(cols_);
  held_.resize(n), held_angle_.resize(n);
}

glm::vec3 Solver::axis_of(int c) const {
  const int j = col_joint_[c];
  if (hinge(j)) return axis_[j];
  const int k = c - col_[j];
  return glm::vec3(k == 0, k == 1, k == 2);
}

void Solver::pose(State& s) const {
  for (int j = 0; j < n_; ++j) {
    const RigidMotor c = hinge(j) ? turn(axis_[j], s.angle[j]) : s.rot[j];
    s.model[j] = rigid_mul(j == 0 ? rel_[0] : rigid_mul(s.model[j - 1], rel_[j]), c);
  }
  s.e = rigid_point(s.model[n_ - 1], effector_local_);
  const glm::vec3 d = job_.target - s.e;
  s.r[0] = d.x, s.r[1] = d.y, s.r[2] = d.z;
  s.err2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
  if (oriented_) {
    s.u = rigid_direction(s.model[n_ - 1], glm::vec3(1, 0, 0));
    s.w = rigid_direction(s.model[n_ - 1], glm::vec3(0, 1, 0));
    const glm::vec3 du = orient_scale_ * (ut_ - s.u), dw = orient_scale_ * (wt_ - s.w);
    const float o[6] = {du.x, du.y, du.z, dw.x, dw.y, dw.z};
    for (int i = 0; i < 6; ++i) s.r[3 + i] = o[i], s.err2 += double(o[i]) * o[i];
  }
}

bool Solver::done(const State& s) const {
  if (!(glm::length(job_.target - s.e) <= job_.tolerance * length_)) return false;
  if (!oriented_) return true;
  return std::max(glm::length(ut_ - s.u), glm::length(wt_ - s.w)) <= job_.orientation_tolerance;
}

void Solver::store_column(int c, const float* P, const float* dP, const float* dU, const float* dW) {
  // The point's Euclidean part P/P0 (P0 = 1 for a rigid motor, to rounding) by the quotient rule.
  for (int i = 0; i < 3; ++i) jac_[i * cols_ + c] = (dP[i] - P[i] * dP[3] / P[3]) / P[3];
  if (oriented_)
    for (int i = 0; i < 3; ++i) {
      jac_[(3 + i) * cols_ + c] = orient_scale_ * dU[i] / P[3];
      jac_[(6 + i) * cols_ + c] = orient_scale_ * dW[i] / P[3];
    }
}

void Solver::jacobian() {
  const glm::vec3 &e = cur_.e, &u = cur_.u, &w = cur_.w;
  for (int c = 0; c < cols_; ++c) {
    const glm::vec3 a = axis_of(c);
    const float* m = cur_.model[col_joint_[c]].data();
    float P[4], U[3], W[3], dP[4], dU[3], dW[3];
    if (oriented_) {
      kernels::ik_chain_joint(m, a.x, a.y, a.z, 0.0f, e.x, e.y, e.z, u.x, u.y, u.z, w.x, w.y, w.z, P, U, W, dP, dU, dW);
      store_column(c, P, dP, dU, dW);
    } else {
      kernels::ik_chain_joint_position(m, a.x, a.y, a.z, 0.0f, e.x, e.y, e.z, u.x, u.y, u.z, w.x, w.y, w.z, dP);
      store_position_column(c, dP);
    }
  }
}

void Solver::step() {
  const int m = m_, cols = cols_;
  const std::span<const float> lo = job_.min_angles, hi = job_.max_angles;
  // The damped step, solved again without the hinges that it would push past a limit (held at it).
  std::fill(held_.begin(), held_.end(), 0);
  for (int pass = 0; pass < 2; ++pass) {
    double a[kMaxRows * kMaxRows] = {}, r[kMaxRows], y[kMaxRows];
    for (int i = 0; i < m; ++i) {
      r[i] = cur_.r[i];
      for (int k = 0; k <= i; ++k) {
        double s = 0.0;
        for (int c = 0; c < cols; ++c)
          if (!held_[col_joint_[c]]) s += double(jac_[i * cols + c]) * jac_[k * cols + c];
        a[i * m + k] = a[k * m + i] = s;
      }
    }
    solve_damped(a, lambda_ * lambda_, r, m, y);
    for (int c = 0; c < cols; ++c) {
      double s = 0.0;
      for (int i = 0; i < m; ++i) s += jac_[i * cols + c] * y[i];
      step_[c] = static_cast<float>(s);
    }
    bool again = false;
    if (!lo.empty())
      for (int j = 0; j < n_; ++j) {
        if (held_[j] || !hinge(j)) continue;
        const float t = cur_.angle[j] + step_[col_[j]];
        if (t < lo[j] || t > hi[j]) held_[j] = 1, held_angle_[j] = std::clamp(t, lo[j], hi[j]), again = true;
      }
    if (!again) break;
  }
  for (int j = 0; j < n_; ++j) {
    if (hinge(j)) {
      float t = held_[j] ? held_angle_[j] : cur_.angle[j] + step_[col_[j]];
      if (!lo.empty()) t = std::clamp(t, lo[j], hi[j]);
      next_.angle[j] = t;
    } else {
      const glm::vec3 d(step_[col_[j]], step_[col_[j] + 1], step_[col_[j] + 2]);
      const float len = glm::length(d);
      next_.rot[j] = len > 0.0f ? rigid_mul(cur_.rot[j], turn(d / len, len)) : cur_.rot[j];
    }
  }
  pose(next_);
  ++it_;
  if (next_.err2 < cur_.err2) {
    std::swap(cur_, next_);
    lambda_ = std::max(lambda_ * 0.5, double(lambda_min_));
    hit_ = done(cur_);
  } else {
    lambda_ *= 4.0;
    if (lambda_ > lambda_max_ && !kicked_) kick();
  }
}

// Stalled: no damped step lowers the residual (a straight chain pulled along its own line, where no joint
// moves the effector along the chain to first order, or a local minimum). Once per solve the chain is bent
// by kKick rad at every joint, alternating in sign (within the limits; a free joint about its local z), and
// the damping starts again.
void Solver::kick() {
  constexpr float kKick = 0.1f;
  kicked_ = true;
  for (int j = 0; j < n_; ++j) {
    const float by = j % 2 == 0 ? kKick : -kKick;
    if (hinge(j)) {
      float t = cur_.angle[j] + by;
      if (!job_.min_angles.empty()) t = std::clamp(t, job_.min_angles[j], job_.max_angles[j]);
      cur_.angle[j] = t;
    } else {
      cur_.rot[j] = rigid_mul(cur_.rot[j], turn(glm::vec3(0, 0, 1), by));
    }
  }
  pose(cur_);
  hit_ = done(cur_);
  lambda_ = lambda_min_;
}

void Solver::finish() const {
  for (int j = 0; j < n_; ++j)
    job_.corrections[j] = weighted(hinge(j) ? turn(axis_[j], cur_.angle[j]) : cur_.rot[j], job_.weight);
  if (job_.reached) *job_.reached = hit_ && job_.weight >= 1.0f;
  if (job_.iterations) *job_.iterations = it_;
}

}  // namespace ik_chain_detail

using ik_chain_detail::finite;

bool ChainIKJob::Validate() const {
  const std::size_t n = joints.size();
  if (n == 0 || corrections.size() != n) return false;
  if (!axes.empty() && axes.size() != n) return false;
  if (min_angles.size() != max_angles.size() || (!min_angles.empty() && min_angles.size() != n)) return false;
  if (!finite(effector_offset) || !finite(target)) return false;
  if (!(weight >= 0.0f && weight <= 1.0f) || max_iterations < 1) return false;
  if (!(tolerance > 0.0f) || !(orientation_tolerance > 0.0f) || !(damping > 0.0f) || !std::isfinite(damping))
    return false;
  if (!std::isfinite(tolerance) || !std::isfinite(orientation_tolerance)) return false;
  if (!(orientation_weight >= 0.0f) || !std::isfinite(orientation_weight)) return false;
  if (target_orientation && !finite(*target_orientation)) return false;
  for (const Motor& m : joints)
    if (!finite(m) || !(m.c[0] * m.c[0] + m.c[1] * m.c[1] + m.c[2] * m.c[2] + m.c[4] * m.c[4] > 0.0f)) return false;
  for (const glm::vec3& a : axes)
    if (!finite(a)) return false;
  for (std::size_t i = 0; i < min_angles.size(); ++i)
    if (!(min_angles[i] <= 0.0f) || !(max_angles[i] >= 0.0f) || !std::isfinite(min_angles[i]) ||
        !std::isfinite(max_angles[i]))
      return false;
  return true;
}

bool ChainIKJob::Run() const {
  if (!Validate()) return false;
  ik_chain_detail::Solver solver(*this);
  while (solver.active()) {
    solver.jacobian();
    solver.step();
  }
  solver.finish();
  return true;
}

}  // namespace cga
