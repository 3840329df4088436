// The rigid motor product written out by hand in 4-wide vectors, for the two places where one product waits
// for the previous one: LocalToModelJob's hierarchy (each model motor waits for its parent's) and motor_screw
// (src/motor.cpp). It is the generated motor_mul_rigid's 48 products, read off the kernel; it stays because it
// is measurably faster there than the generated kernel (docs/runtime.md, "LocalToModelJob", gives the
// figures): its sums are 4 lanes wide and 2 deep where the generated kernel's are 8 long. Loops over many
// independent products (the skinning palette) use the generated kernel. Private to the runtime; always
// inlined into its caller, so it is built for the caller's ISA (the jobs' target clones).
//
// With a = (c0, c1, c2, c4) (1 e12 e13 e23) and e = (c3, c5, c6, c8) (e1inf e2inf e3inf e123inf) of each factor,
//   C.a = a0 b + a1 P1(b) + a2 P2(b) + a3 P3(b)                      (b = B.a, f = B.e)
//   C.e = e0 b + e1 P1(b) + e2 P2(b) + e3 P3(b) + a0 f - a1 P1(f) - a2 P2(f) + a3 P3(f)
// with the signed permutations P1(v) = (-v1, v0, v3, -v2), P2(v) = (-v2, -v3, v0, v1), P3(v) = (-v3, v2,
// -v1, v0). test_sampling compares it with motor_mul, test_palette the rigid hierarchy with chains of motor_mul.
#pragma once

#include "cga/runtime/motor.hpp"
#include "simd.hpp"

namespace cga::detail {

#if defined(__GNUC__)
using simd::load4;
using simd::store4;
using simd::v4f;
using v4i = int __attribute__((vector_size(16)));
template <int L0, int L1, int L2, int L3>
CGA_SIMD_INLINE v4f flip(v4f v) {  // negate the lanes whose L is 1
  constexpr int m = static_cast<int>(0x80000000u);
  const v4i mask = {L0 ? m : 0, L1 ? m : 0, L2 ? m : 0, L3 ? m : 0};
  return reinterpret_cast<v4f>(reinterpret_cast<v4i>(v) ^ mask);
}
CGA_SIMD_INLINE v4f p1(v4f v) { return flip<1, 0, 0, 1>(__builtin_shufflevector(v, v, 1, 0, 3, 2)); }
CGA_SIMD_INLINE v4f p2(v4f v) { return flip<1, 1, 0, 0>(__builtin_shufflevector(v, v, 2, 3, 0, 1)); }
CGA_SIMD_INLINE v4f p3(v4f v) { return flip<1, 0, 1, 0>(__builtin_shufflevector(v, v, 3, 2, 1, 0)); }

CGA_SIMD_INLINE void motor_mul_rigid_simd(const Motor& x, const Motor& y, Motor& out) {
  // The left factor (the parent, on the dependency chain) is only splatted, straight from memory (load-port
  // work, no shuffles); only the right factor (the local motor, off the chain) is permuted.
  const auto s = [&](int c) {
    const float v = x.c[c];
    return v4f{v, v, v, v};
  };
  const v4f yl = load4(&y.c[0]), ym = load4(&y.c[4]), yh = load4(&y.c[8]);
  const v4f b = __builtin_shufflevector(yl, ym, 0, 1, 2, 4);
  const v4f f = __builtin_shufflevector(__builtin_shufflevector(yl, ym, 3, 5, 6, 7), yh, 0, 1, 2, 4);
  const v4f b1 = p1(b), b2 = p2(b), b3 = p3(b);
  const v4f ca = (s(0) * b + s(1) * b1) + (s(2) * b2 + s(4) * b3);
  const v4f ce = ((s(3) * b + s(5) * b1) + (s(6) * b2 + s(8) * b3)) +
                 ((s(0) * f - s(1) * p1(f)) + (s(4) * p3(f) - s(2) * p2(f)));
  const v4f zero = {0.0f, 0.0f, 0.0f, 0.0f};
  // Whole 16-byte stores only: the next product of the hierarchy loads them back (store forwarding).
  store4(&out.c[0], __builtin_shufflevector(ca, ce, 0, 1, 2, 4));  // 1 e12 e13 e1inf
  store4(&out.c[4], __builtin_shufflevector(__builtin_shufflevector(ca, ce, 3, 5, 6, 7), zero, 0, 1, 2, 4));
  store4(&out.c[8], __builtin_shufflevector(ce, zero, 3, 4, 4, 4));  // e123inf, b group 0
}
#else
CGA_SIMD_INLINE void motor_mul_rigid_simd(const Motor& x, const Motor& y, Motor& out) { motor_mul_rigid(x, y, out); }
#endif

}  // namespace cga::detail
