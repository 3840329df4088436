// The 5-joint arm's chain (arm5.clu) written with GATL (laffernandes/gatl, header-only), for the side-by-side
// timing of scripts/bench-vs-gatl.sh. Compiled only there, against the user's GATL checkout (GATL_DIR); never
// part of the project's build. GATL's compile-time constants (c<N>) let it fold the rest-pose geometry the
// way cgagen does symbolically; its lazy contexts evaluate each Taylor series in one pass.
//
// Sign convention: GATL's dual is the negative of Gaalop's (and cgagen's) '*', so each joint's line has the
// opposite orientation; GATL at angles -a computes what cgagen computes at a. The harness passes -a here.
#include <gatl/ga3c.hpp>

#include "arm_api.hpp"

namespace {

using namespace ga3c;

template <typename Bivector>
decltype(auto) taylor_exp(const Bivector& b) {
  auto ctx = make_lazy_context(b);
  auto x = ctx.template argument<0>();
  return ctx.eval(c<1> + x + x * x / c<2> + x * x * x / c<6> + x * x * x * x / c<24>);
}

template <typename A>
decltype(auto) half(const A& angle) {
  return scalar(angle) / c<2>;
}

}  // namespace

namespace cga::bench_arm {

void arm_gatl(const double angles[5], ArmResult& out) {
  // Link lengths (mm); 114.2 as 1142/10 keeps it a compile-time constant.
  auto d1 = c<200>; auto d2 = c<680>; auto d3 = c<150>; auto d4 = c<140>; auto d5 = c<1142> / c<10>;
  auto l12 = c<890>; auto l23 = c<880>;
  auto J2 = point(d1, c<0>, d2 + l12);
  auto J3 = point(d1 + l23, c<0>, d2 + l12 + d3);
  auto Jg = point(d1 + l23 + d4 + d5, c<0>, d2 + l12 + d3);

  auto R1 = taylor_exp(half(-angles[0]) * dual(no ^ point(c<0>, c<0>, c<1>) ^ ni));
  auto L2 = apply_rotor(R1, dual(point(d1, c<0>, d2) ^ point(d1, c<1>, d2) ^ ni));
  auto R2 = taylor_exp(half(-angles[1]) * L2);
  auto R21 = R2 * R1;
  auto L3 = apply_rotor(R21, dual(J2 ^ point(d1, c<1>, d2 + l12) ^ ni));
  auto R3 = taylor_exp(half(-angles[2]) * L3);
  auto J2a = apply_rotor(R21, J2);
  auto J2b = apply_rotor(R1, J2);
  auto t2 = euclidean_vector(sp(J2a, e1) - sp(J2b, e1), sp(J2a, e2) - sp(J2b, e2), sp(J2a, e3) - sp(J2b, e3));
  auto T2 = taylor_exp((-c<1> / c<2>) * (t2 ^ ni));
  auto V3 = R3 * T2 * R1;
  auto L4 = apply_rotor(V3, unit(dual(J3 ^ Jg ^ ni)));
  auto R4 = taylor_exp(half(-angles[3]) * L4);
  auto L5 = apply_rotor(R4 * V3, dual(J3 ^ point(d1 + l23, c<1>, d2 + l12 + d3) ^ ni));
  auto Rg = taylor_exp(half(-angles[4]) * L5);
  auto G = apply_rotor(Rg * V3, Jg);

  out.gripper[0] = sp(G, e1);
  out.gripper[1] = sp(G, e2);
  out.gripper[2] = sp(G, e3);
  out.rotor_scalars[0] = take_grade(R1, c<0>);
  out.rotor_scalars[1] = take_grade(R2, c<0>);
  out.rotor_scalars[2] = take_grade(R3, c<0>);
  out.rotor_scalars[3] = take_grade(R4, c<0>);
  out.rotor_scalars[4] = take_grade(Rg, c<0>);
}

}  // namespace cga::bench_arm
