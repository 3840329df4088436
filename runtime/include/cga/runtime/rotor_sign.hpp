// The motor rotor sign fix of the pose jobs' nlerp blend and additive layers, and of the split motor form the
// jobs and the skinning palettes share. The skinning scripts (runtime/scripts/skin) write the same fix as a
// select.
//
// A motor M and -M are the same similarity, but a blend of coefficients is not sign-blind: before adding a
// motor into a blend it is negated when its rotor part points away from the first (reference) motor's. The
// rotor part is read in split form, G = a + b (a: blades 1 e12 e13 e23; b: the E-times blades e0inf e12e0inf
// e13e0inf e23e0inf, see transform_point_split.clu): G is the rotor scaled by 1 + k > 0 for a dilation
// 1 + kE, so its sign is the rotor's and a scaled motor needs no normalization first.
//
//   G_k = a_k + b_k over the blade pairs (kRotorBlades[i], kEBlades[i]), i < 4
//   w_k' = copysign(w_k, <G_0, G_k>)      (<.,.> the 4-lane dot product)
#pragma once

#include <math.h>

#define CGA_ROTOR_SIGN_FN inline

namespace cga::rotor_sign {

// Blade indices in types.hpp's order.
#define CGA_ROTOR_BLADES 0, 1, 2, 4
#define CGA_E_BLADES 7, 9, 10, 11
#define CGA_EINF_BLADES 3, 5, 6, 8
CGA_ROTOR_SIGN_FN constexpr int rotor_blade(int i) {
  constexpr int b[4] = {CGA_ROTOR_BLADES};
  return b[i];
}
CGA_ROTOR_SIGN_FN constexpr int e_blade(int i) {
  constexpr int b[4] = {CGA_E_BLADES};
  return b[i];
}
CGA_ROTOR_SIGN_FN constexpr int einf_blade(int i) {
  constexpr int b[4] = {CGA_EINF_BLADES};
  return b[i];
}

// The split form of 12 blade coefficients: G = a + b, H = a - b, U the einf blades.
CGA_ROTOR_SIGN_FN void split(const float m[12], float g[4], float h[4], float u[4]) {
  for (int i = 0; i < 4; ++i) {
    g[i] = m[rotor_blade(i)] + m[e_blade(i)];
    h[i] = m[rotor_blade(i)] - m[e_blade(i)];
    u[i] = m[einf_blade(i)];
  }
}
// The rotor part's dot product from the blade form (the reference's G precomputed by split or rotor_g).
CGA_ROTOR_SIGN_FN float rotor_g(const float m[12], int i) { return m[rotor_blade(i)] + m[e_blade(i)]; }

// <G_0, G_k> of two split entries' G lanes.
CGA_ROTOR_SIGN_FN float dot(const float g0[4], const float gk[4]) {
  return g0[0] * gk[0] + g0[1] * gk[1] + g0[2] * gk[2] + g0[3] * gk[3];
}
// The weight a motor enters the blend with: w with the sign of the rotor dot product (copysign, so that the
// SIMD paths can take it as a bitwise select of the dot's sign bit).
CGA_ROTOR_SIGN_FN float signed_weight(float w, float rotor_dot) { return copysignf(w, rotor_dot); }

}  // namespace cga::rotor_sign
