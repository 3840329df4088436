// ChainIKJob (see ik_chain.hpp): damped least squares with Levenberg-Marquardt step control. The geometry is
// generated: each joint's Jacobian column comes from ik_chain_joint (the effector and the end frame's axes
// turned about the joint's axis line, differentiated by the angle at 0), the corrections' rotors from
// ik_chain_rotor, the forward kinematics from motor_mul_rigid and transform_point. This file does the plain
// numerics: the m x m normal equations (m = 3, or 9 with an orientation target), the limits (an active set:
// a hinge whose step would cross its limit is held there and the step solved again without it), the
// acceptance of steps and the weight.
#include "cga/runtime/ik_chain.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <ik_chain_joint.hpp>
#include <ik_chain_rotor.hpp>

#include "cga/runtime/motor.hpp"

namespace cga {

namespace {

constexpr int kMaxRows = 9;

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const Motor& m) {
  for (float c : m.c)
    if (!std::isfinite(c)) return false;
  return true;
}

// The rigid part T*R of a model-space motor (a scaled joint's scale dropped: the rotations the job turns
// about the joint's origin commute with a uniform scale).
RigidMotor rigid_part(const Motor& m) {
  if (motor_is_rigid(m)) return rigid_blades(m);
  Transform t = motor_to_transform(m);
  t.scale = 1.0f;
  return rigid_blades(motor_from_transform(t));
}

RigidMotor rigid_mul(const RigidMotor& a, const RigidMotor& b) {
  RigidMotor c;
  kernels::motor_mul_rigid(a.data(), b.data(), c.data());
  return c;
}

RigidMotor rigid_reverse(const RigidMotor& a) { return rigid_blades(motor_reverse(motor_from_rigid(a))); }

glm::vec3 rigid_point(const RigidMotor& m, const glm::vec3& p) { return motor_transform_point(motor_from_rigid(m), p); }

// A direction turned by the rotor part of a rigid motor (its translation blades dropped).
glm::vec3 rigid_direction(const RigidMotor& m, const glm::vec3& d) {
  Motor r;
  r.c[0] = m[0], r.c[1] = m[1], r.c[2] = m[2], r.c[4] = m[4];
  return motor_transform_point(r, d);
}

// The rotation motor of the turn by `angle` about the unit `axis` (generated ik_chain_rotor).
RigidMotor turn(const glm::vec3& axis, float angle) {
  float r[4];
  kernels::ik_chain_rotor(axis.x, axis.y, axis.z, angle, r);
  return {r[0], r[1], r[2], 0.0f, r[3], 0.0f, 0.0f, 0.0f};
}

// nlerp of a rotation motor's rotor from the identity by w (the short way), as TwoBoneIKJob weighs.
Motor weighted(const RigidMotor& c, float w) {
  float q[4] = {c[0], c[1], c[2], c[4]};
  const float n = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  for (float& x : q) x /= n;
  if (w < 1.0f) {
    if (q[0] < 0.0f)
      for (float& x : q) x = -x;
    q[0] = 1.0f - w + w * q[0];
    for (int i = 1; i < 4; ++i) q[i] *= w;
    const float m = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (float& x : q) x /= m;
  }
  Motor out;
  out.c[0] = q[0], out.c[1] = q[1], out.c[2] = q[2], out.c[4] = q[3];
  return out;
}

// Solves (A + mu I) y = r for the symmetric positive semi-definite m x m A by Cholesky (mu > 0).
void solve_damped(const double* a, double mu, const double* r, int m, double* y) {
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

// The solver's state and scratch for one Run().
struct Solver {
  const ChainIKJob& job;
  int n = 0, m = 3, cols = 0;
  bool oriented = false;
  float length = 0.0f, lambda_min = 0.0f, orient_scale = 0.0f;
  std::vector<RigidMotor> base, rel;    // input rigid model motors; ~G[j-1] G[j] (rel[0] = G[0])
  std::vector<glm::vec3> axis;          // unit hinge axes; zero for a free joint
  std::vector<int> col;                 // first Jacobian column of each joint
  glm::vec3 effector_local{0.0f}, ut{1, 0, 0}, wt{0, 1, 0};
  // State: per joint the hinge angle, or the free joint's rotation; the posed chain it gives.
  struct State {
    std::vector<float> angle;
    std::vector<RigidMotor> rot, model;
    glm::vec3 e{0.0f}, u{0.0f}, w{0.0f};
    float r[kMaxRows] = {};
    double err2 = 0.0;
  };

  explicit Solver(const ChainIKJob& j) : job(j) {}

  void pose(State& s) const {
    for (int j = 0; j < n; ++j) {
      const RigidMotor c = axis[j] != glm::vec3(0.0f) ? turn(axis[j], s.angle[j]) : s.rot[j];
      s.model[j] = rigid_mul(j == 0 ? rel[0] : rigid_mul(s.model[j - 1], rel[j]), c);
    }
    s.e = rigid_point(s.model[n - 1], effector_local);
    const glm::vec3 d = job.target - s.e;
    s.r[0] = d.x, s.r[1] = d.y, s.r[2] = d.z;
    s.err2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z;
    if (oriented) {
      s.u = rigid_direction(s.model[n - 1], glm::vec3(1, 0, 0));
      s.w = rigid_direction(s.model[n - 1], glm::vec3(0, 1, 0));
      const glm::vec3 du = orient_scale * (ut - s.u), dw = orient_scale * (wt - s.w);
      const float o[6] = {du.x, du.y, du.z, dw.x, dw.y, dw.z};
      for (int i = 0; i < 6; ++i) s.r[3 + i] = o[i], s.err2 += double(o[i]) * o[i];
    }
  }

  bool done(const State& s) const {
    const glm::vec3 d = job.target - s.e;
    if (!(glm::length(d) <= job.tolerance * length)) return false;
    if (!oriented) return true;
    return std::max(glm::length(ut - s.u), glm::length(wt - s.w)) <= job.orientation_tolerance;
  }
};

}  // namespace

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
  Solver sv(*this);
  const int n = sv.n = static_cast<int>(joints.size());
  sv.base.resize(n), sv.rel.resize(n), sv.axis.assign(n, glm::vec3(0.0f)), sv.col.resize(n);
  for (int j = 0; j < n; ++j) {
    sv.base[j] = rigid_part(joints[j]);
    sv.rel[j] = j == 0 ? sv.base[0] : rigid_mul(rigid_reverse(sv.base[j - 1]), sv.base[j]);
    if (!axes.empty() && glm::length(axes[j]) > 0.0f) sv.axis[j] = glm::normalize(axes[j]);
    sv.col[j] = sv.cols;
    sv.cols += sv.axis[j] != glm::vec3(0.0f) ? 1 : 3;
  }
  // The effector in the tip's rigid frame (where the animated, possibly scaled, tip puts it), the chain length.
  const glm::vec3 effector = motor_transform_point(joints[n - 1], effector_offset);
  sv.effector_local = rigid_point(rigid_reverse(sv.base[n - 1]), effector);
  glm::vec3 prev = rigid_point(sv.base[0], glm::vec3(0.0f));
  for (int j = 1; j < n; ++j) {
    const glm::vec3 p = rigid_point(sv.base[j], glm::vec3(0.0f));
    sv.length += glm::length(p - prev);
    prev = p;
  }
  sv.length += glm::length(effector - prev);
  sv.length = std::max(sv.length, 1e-6f * std::max(1.0f, glm::length(target)));
  sv.lambda_min = damping * sv.length;
  sv.oriented = target_orientation && orientation_weight > 0.0f;
  if (sv.oriented) {
    const RigidMotor t = rigid_part(*target_orientation);
    sv.ut = rigid_direction(t, glm::vec3(1, 0, 0)), sv.wt = rigid_direction(t, glm::vec3(0, 1, 0));
    sv.m = 9;
    sv.orient_scale = orientation_weight * sv.length;
  }
  const int m = sv.m, cols = sv.cols;

  Solver::State cur, next;
  for (Solver::State* s : {&cur, &next}) {
    s->angle.assign(n, 0.0f);
    s->rot.assign(n, RigidMotor{1, 0, 0, 0, 0, 0, 0, 0});
    s->model.resize(n);
  }
  sv.pose(cur);

  std::vector<float> jac(static_cast<std::size_t>(m) * cols), step(cols);
  std::vector<char> held(n);
  std::vector<float> held_angle(n);
  double lambda = sv.lambda_min;
  const double lambda_max = 1e4 * sv.length;
  int it = 0;
  bool hit = sv.done(cur);
  while (!hit && it < max_iterations && lambda <= lambda_max) {
    // The Jacobian: one generated kernel call per joint axis, at angle 0 on the posed chain.
    for (int j = 0; j < n; ++j) {
      const bool hinge = sv.axis[j] != glm::vec3(0.0f);
      for (int k = 0; k < (hinge ? 1 : 3); ++k) {
        const glm::vec3 a = hinge ? sv.axis[j] : glm::vec3(k == 0, k == 1, k == 2);
        float P[4], U[3], W[3], dP[4], dU[3], dW[3];
        kernels::ik_chain_joint(cur.model[j].data(), a.x, a.y, a.z, 0.0f, cur.e.x, cur.e.y, cur.e.z, cur.u.x,
                                cur.u.y, cur.u.z, cur.w.x, cur.w.y, cur.w.z, P, U, W, dP, dU, dW);
        const int c = sv.col[j] + k;
        for (int i = 0; i < 3; ++i) jac[i * cols + c] = (dP[i] - P[i] * dP[3] / P[3]) / P[3];
        if (sv.oriented)
          for (int i = 0; i < 3; ++i) {
            jac[(3 + i) * cols + c] = sv.orient_scale * dU[i] / P[3];
            jac[(6 + i) * cols + c] = sv.orient_scale * dW[i] / P[3];
          }
      }
    }
    // The damped step, solved again without the hinges that it would push past a limit (held at it).
    std::fill(held.begin(), held.end(), 0);
    for (int pass = 0; pass < 2; ++pass) {
      double a[kMaxRows * kMaxRows] = {}, r[kMaxRows], y[kMaxRows];
      for (int i = 0; i < m; ++i) {
        r[i] = cur.r[i];
        for (int k = 0; k <= i; ++k) {
          double s = 0.0;
          for (int j = 0; j < n; ++j) {
            if (held[j]) continue;
            const int c0 = sv.col[j], c1 = c0 + (sv.axis[j] != glm::vec3(0.0f) ? 1 : 3);
            for (int c = c0; c < c1; ++c) s += double(jac[i * cols + c]) * jac[k * cols + c];
          }
          a[i * m + k] = a[k * m + i] = s;
        }
      }
      solve_damped(a, lambda * lambda, r, m, y);
      for (int c = 0; c < cols; ++c) {
        double s = 0.0;
        for (int i = 0; i < m; ++i) s += jac[i * cols + c] * y[i];
        step[c] = static_cast<float>(s);
      }
      bool again = false;
      if (!min_angles.empty())
        for (int j = 0; j < n; ++j) {
          if (held[j] || sv.axis[j] == glm::vec3(0.0f)) continue;
          const float t = cur.angle[j] + step[sv.col[j]];
          if (t < min_angles[j] || t > max_angles[j])
            held[j] = 1, held_angle[j] = std::clamp(t, min_angles[j], max_angles[j]), again = true;
        }
      if (!again) break;
    }
    for (int j = 0; j < n; ++j) {
      if (sv.axis[j] != glm::vec3(0.0f)) {
        float t = held[j] ? held_angle[j] : cur.angle[j] + step[sv.col[j]];
        if (!min_angles.empty()) t = std::clamp(t, min_angles[j], max_angles[j]);
        next.angle[j] = t;
      } else {
        const glm::vec3 d(step[sv.col[j]], step[sv.col[j] + 1], step[sv.col[j] + 2]);
        const float len = glm::length(d);
        next.rot[j] = len > 0.0f ? rigid_mul(cur.rot[j], turn(d / len, len)) : cur.rot[j];
      }
    }
    sv.pose(next);
    ++it;
    if (next.err2 < cur.err2) {
      std::swap(cur, next);
      lambda = std::max(lambda * 0.5, double(sv.lambda_min));
      hit = sv.done(cur);
    } else {
      lambda *= 4.0;
    }
  }

  for (int j = 0; j < n; ++j) {
    const RigidMotor c = sv.axis[j] != glm::vec3(0.0f) ? turn(sv.axis[j], cur.angle[j]) : cur.rot[j];
    corrections[j] = weighted(c, weight);
  }
  if (reached) *reached = hit && weight >= 1.0f;
  if (iterations) *iterations = it;
  return true;
}

}  // namespace cga
