// klein's storage, read into the generated library's (libraries/pga3.gal). Every input of cga-klein-bench is
// drawn as a klein value and converted here, so that both sides get the same element, and every klein result is
// converted here before it is compared with the generated one.
//
// klein keeps each type in __m128 registers, lane 0 first (klein/detail/x86/x86_exp_log.hpp, "Partition memory
// layouts"):
//   plane   p0 (e0, e1, e2, e3)
//   rotor   p1 (1, e23, e31, e12)                  line   p1 (0, e23, e31, e12), p2 (0, e01, e02, e03)
//   motor   p1 (1, e23, e31, e12), p2 (e0123, e01, e02, e03)
//   point   p3 (e123, e032, e013, e021)            a point (x, y, z) is e123 + x e032 + y e013 + z e021
// pga3.gal spells every blade with increasing indices, so three of klein's blades change sign:
//   e31 = -e1^e3,  e032 = -e0^e2^e3,  e021 = -e0^e1^e2   (e013, e0123 and the others keep theirs).
// The checks of main.cpp confirm the map numerically: a motor applied to a point gives the same Euclidean point
// on both sides, for every drawn element.
#pragma once

#include <klein/klein.hpp>

#include "pga3.hpp"

namespace kb {

struct Lanes {
  alignas(16) float f[4];
  explicit Lanes(__m128 x) { _mm_store_ps(f, x); }
  float operator[](int k) const { return f[k]; }
};

inline pga3::plane to_pga3(const kln::plane& p) {
  const Lanes a(p.p0_);
  return {{a[0], a[1], a[2], a[3]}};
}

inline pga3::point to_pga3(const kln::point& p) {
  const Lanes a(p.p3_);
  return {{-a[1], a[2], -a[3], a[0]}};
}

inline pga3::line to_pga3(const kln::line& l) {
  const Lanes r(l.p1_), d(l.p2_);
  return {{d[1], d[2], d[3], r[1], -r[2], r[3]}};
}

inline pga3::rotor to_pga3(const kln::rotor& r) {
  const Lanes a(r.p1_);
  return {{a[0], a[1], -a[2], a[3]}};
}

inline pga3::motor to_pga3(const kln::motor& m) {
  const Lanes r(m.p1_), d(m.p2_);
  return {{r[0], r[1], -r[2], r[3], d[1], d[2], d[3], d[0]}};
}

// The other way, for klein's exp of a generated log (main.cpp's arbiter of log).
inline kln::line to_klein(const pga3::line& l) {
  return kln::line(l.v[0], l.v[1], l.v[2], l.v[3], -l.v[4], l.v[5]);
}

// A Euclidean point of klein's matrix (x, y, z, w) as a pga3 point (see the signs above).
inline pga3::point point_of_xyzw(const float xyzw[4]) { return {{-xyzw[0], xyzw[1], -xyzw[2], xyzw[3]}}; }

}  // namespace kb
