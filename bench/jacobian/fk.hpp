// Plain C++ forward kinematics of the benchmark's chains (bench/jacobian), templated on the number type T so
// that ceres::Jet<double, N> differentiates it: rigid transforms (3x3 rotation matrix + translation) and
// quaternions, no geometric algebra. They compute exactly what the scripts compute, including what the
// scripts' rotors do that a textbook arm would not:
//   - a joint's rotor is the 4th-order Taylor series of exp(ang/2 * L) for its line L. With L = lambda*L^
//     (L^ a unit line, lambda its scale) and b = ang/2 * lambda, that is c + s*L^ with c = 1 - b^2/2 + b^4/24,
//     s = b - b^3/6: the quaternion (c, s*u) about the line's direction u, a rotation by 2*atan2(s, c) with
//     weight c^2 + s^2 (not 1);
//   - a sandwich by a versor of weight w multiplies a point's weight and a line's scale by w, so the weights
//     compound along the chain and enter the next joints' b (Frame::w);
//   - the outputs are conformal points w*(x + |x|^2/2 einf + e0), the weights included.
// arm5(): bench/ik_arm/arm5.clu (with its translator T2 from weighted coordinates and V3 = R3*T2*R1,
// V5 = Rg*V3 as that script has them). chain(): cga::testing::joint_chain_script(n) (the carried chain).
#pragma once

#include <array>
#include <cmath>

namespace cga::bench_jacobian {

// A versor's action on points: x -> R x + t, the weight multiplied by w.
template <typename T>
struct Frame {
  T R[3][3];
  T t[3];
  T w;
};

template <typename T>
Frame<T> identity() {
  Frame<T> f;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) f.R[i][j] = T(i == j ? 1.0 : 0.0);
    f.t[i] = T(0.0);
  }
  f.w = T(1.0);
  return f;
}

// a * b: b's action first (the sandwich by the product a*b).
template <typename T>
Frame<T> compose(const Frame<T>& a, const Frame<T>& b) {
  Frame<T> f;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) f.R[i][j] = a.R[i][0] * b.R[0][j] + a.R[i][1] * b.R[1][j] + a.R[i][2] * b.R[2][j];
    f.t[i] = a.R[i][0] * b.t[0] + a.R[i][1] * b.t[1] + a.R[i][2] * b.t[2] + a.t[i];
  }
  f.w = a.w * b.w;
  return f;
}

template <typename T, typename P>
void apply(const Frame<T>& f, const P p[3], T out[3]) {
  for (int i = 0; i < 3; ++i) out[i] = f.R[i][0] * p[0] + f.R[i][1] * p[1] + f.R[i][2] * p[2] + f.t[i];
}

// A line: through p along the unit direction u, with scale lambda.
template <typename T>
struct Line {
  T p[3];
  T u[3];
  T lambda;
};

template <typename T>
Line<T> rest_line(double px, double py, double pz, double ux, double uy, double uz) {
  return Line<T>{{T(px), T(py), T(pz)}, {T(ux), T(uy), T(uz)}, T(1.0)};
}

template <typename T>
Line<T> carry(const Frame<T>& f, const Line<T>& l) {
  Line<T> m;
  apply(f, l.p, m.p);
  for (int i = 0; i < 3; ++i) m.u[i] = f.R[i][0] * l.u[0] + f.R[i][1] * l.u[1] + f.R[i][2] * l.u[2];
  m.lambda = l.lambda * f.w;
  return m;
}

// The sense of a joint's rotation about its line's direction: the rotor c + s*L^ of the dual line
// L^ = *(P ^ Q ^ einf), Q - P = u, turns by +2*atan2(s, c) about u.
constexpr double kSense = 1.0;

// The joint's versor: the Taylor rotor of exp(ang/2 * L), as a rotation about the line and a weight.
template <typename T>
Frame<T> joint(const T& ang, const Line<T>& l) {
  const T b = ang * l.lambda * (0.5 * kSense), b2 = b * b;
  const T c = T(1.0) + b2 * (b2 * (1.0 / 24) - 0.5);
  const T s = b * (T(1.0) - b2 * (1.0 / 6));
  const T x = s * l.u[0], y = s * l.u[1], z = s * l.u[2];
  const T n = c * c + s * s;  // the weight (|u| = 1)
  const T k = T(1.0) / n;
  const T wx = c * x * k, wy = c * y * k, wz = c * z * k;
  const T xx = x * x * k, yy = y * y * k, zz = z * z * k, xy = x * y * k, xz = x * z * k, yz = y * z * k;
  Frame<T> f;
  f.R[0][0] = T(1.0) - 2.0 * (yy + zz);
  f.R[0][1] = 2.0 * (xy - wz);
  f.R[0][2] = 2.0 * (xz + wy);
  f.R[1][0] = 2.0 * (xy + wz);
  f.R[1][1] = T(1.0) - 2.0 * (xx + zz);
  f.R[1][2] = 2.0 * (yz - wx);
  f.R[2][0] = 2.0 * (xz - wy);
  f.R[2][1] = 2.0 * (yz + wx);
  f.R[2][2] = T(1.0) - 2.0 * (xx + yy);
  for (int i = 0; i < 3; ++i)  // turn about the line through p: x -> p + R (x - p)
    f.t[i] = l.p[i] - (f.R[i][0] * l.p[0] + f.R[i][1] * l.p[1] + f.R[i][2] * l.p[2]);
  f.w = n;
  return f;
}

// The conformal point of weight f.w at f's image of p: the coefficients (e1, e2, e3, e0, einf).
template <typename T>
void point_out(const Frame<T>& f, const double p[3], T out[5]) {
  T x[3];
  apply(f, p, x);
  const T half_sq = 0.5 * (x[0] * x[0] + x[1] * x[1] + x[2] * x[2]);
  for (int i = 0; i < 3; ++i) out[i] = f.w * x[i];
  out[3] = f.w;
  out[4] = f.w * half_sq;
}

// bench/ik_arm/arm5.clu: angles ang[0..4], the gripper point Jg_f.
template <typename T>
void arm5(const T ang[5], T jg_f[5]) {
  const double d1 = 200, d2 = 680, d3 = 150, d4 = 140, d5 = 114.2, l12 = 890, l23 = 880;
  const double a1x = d1, a1z = d2, a2x = d1, a2z = d2 + l12, a3x = d1 + l23, a3z = d2 + l12 + d3;
  const double gx = d1 + l23 + d4 + d5, gz = d2 + l12 + d3;
  const double J2[3] = {a2x, 0, a2z}, Jg[3] = {gx, 0, gz};

  const Frame<T> R1 = joint(ang[0], rest_line<T>(0, 0, 0, 0, 0, 1));
  const Frame<T> R2 = joint(ang[1], carry(R1, rest_line<T>(a1x, 0, a1z, 0, 1, 0)));
  const Frame<T> R21 = compose(R2, R1);
  const Frame<T> R3 = joint(ang[2], carry(R21, rest_line<T>(a2x, 0, a2z, 0, 1, 0)));
  // T2: the translation between J2's weighted images after joints 1 and 2 and after joint 1 alone.
  T j2a[3], j2b[3];
  apply(R21, J2, j2a);
  apply(R1, J2, j2b);
  Frame<T> T2 = identity<T>();
  for (int i = 0; i < 3; ++i) T2.t[i] = R21.w * j2a[i] - R1.w * j2b[i];
  const Frame<T> V3 = compose(R3, compose(T2, R1));
  const Frame<T> R4 = joint(ang[3], carry(V3, rest_line<T>(a3x, 0, a3z, 1, 0, 0)));  // J3 -> Jg, along x
  const Frame<T> V4 = compose(R4, V3);
  const Frame<T> Rg = joint(ang[4], carry(V4, rest_line<T>(a3x, 0, a3z, 0, 1, 0)));
  point_out(compose(Rg, V3), Jg, jg_f);
}

// cga::testing::joint_chain_script(n): angles ang[0..n-1], the end point E. Joint k (1-based) turns about the
// line through (150 k, 0, 200 k) along z (odd k) or y (even k), carried by the joints before it.
template <typename T, int N>
void chain(const T ang[N], T e[5]) {
  Frame<T> V = identity<T>();
  for (int k = 1; k <= N; ++k) {
    const Line<T> rest = rest_line<T>(150.0 * k, 0, 200.0 * k, 0, k % 2 ? 0 : 1, k % 2 ? 1 : 0);
    V = compose(joint(ang[k - 1], carry(V, rest)), V);
  }
  const double end[3] = {150.0 * N + 100, 0, 200.0 * N};
  point_out(V, end, e);
}

}  // namespace cga::bench_jacobian
