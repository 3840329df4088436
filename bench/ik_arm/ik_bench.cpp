// cga-ik-arm-bench: nanoseconds per call of the 5-joint arm's chain (arm5.clu, ga-benchmark's "inverse
// kinematics" algorithm) as cgagen -O2 compiles it, in double and in float; built with CGA_WITH_GATL
// (scripts/bench-vs-gatl.sh, given a GATL checkout) it times GATL's version of the same algorithm in the same
// process and prints the ratio.
//
// Each implementation runs over the same 1024 sets of random angles (fixed seed), in rounds of at least
// 0.25 s; the figure is the median of 7 rounds, and the rounds of the implementations alternate so that a
// change of machine load hits all of them alike. Before timing, every implementation's results are
// compared with cgagen's double kernel (gripper point and rotor scalars, relative 1e-9; float 1e-3).
//
// usage: cga-ik-arm-bench [--quick]   (--quick: one short round each, for the smoke test)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "arm5.hpp"
#include "arm_api.hpp"
#ifdef CGA_WITH_GABENCH_IK
#include "gabench_ik.hpp"  // ga-benchmark's own block, compiled by scripts/bench-vs-gatl.sh
#endif

namespace cga::bench_arm {
#ifdef CGA_WITH_GATL
void arm_gatl(const double angles[5], ArmResult& out);
#endif

namespace {

// Every output of the kernel is written to `sink` (so no part of the chain can be left out by the
// compiler), and the compared parts to `out`.
template <typename Real>
__attribute__((noinline)) void arm_cgagen(const double angles[5], ArmResult& out) {
  Real R1[16], R2[16], R3[16], T2[16], R4[16], Rg[16], Jg_f[32];
  cga::kernels::arm5(Real(angles[0]), Real(angles[1]), Real(angles[2]), Real(angles[3]), Real(angles[4]), R1, R2,
                     R3, T2, R4, Rg, Jg_f);
  for (int i = 0; i < 3; ++i) out.gripper[i] = Jg_f[i];
  const Real* rotors[5] = {R1, R2, R3, R4, Rg};
  for (int i = 0; i < 5; ++i) out.rotor_scalars[i] = rotors[i][0];
  asm volatile("" : : "r"(R1), "r"(R2), "r"(R3), "r"(T2), "r"(R4), "r"(Rg), "r"(Jg_f) : "memory");
}

#ifdef CGA_WITH_GABENCH_IK
// The same chain from ga-benchmark's script as written: its outputs in order of marking (R1 R2 L3 R3 T2 L4init
// L4 R4 Lginit Lg Rg Jg_f).
template <typename Real>
__attribute__((noinline)) void arm_gabench(const double angles[5], ArmResult& out) {
  Real R1[16], R2[16], L3[32], R3[16], T2[16], L4init[32], L4[32], R4[16], Lginit[32], Lg[32], Rg[16], Jg_f[32];
  cga::kernels::gabench_ik(Real(angles[0]), Real(angles[1]), Real(angles[2]), Real(angles[3]), Real(angles[4]), R1,
                           R2, L3, R3, T2, L4init, L4, R4, Lginit, Lg, Rg, Jg_f);
  for (int i = 0; i < 3; ++i) out.gripper[i] = Jg_f[i];
  const Real* rotors[5] = {R1, R2, R3, R4, Rg};
  for (int i = 0; i < 5; ++i) out.rotor_scalars[i] = rotors[i][0];
  asm volatile("" : : "r"(R1), "r"(R2), "r"(L3), "r"(R3), "r"(T2), "r"(L4init), "r"(L4), "r"(R4), "r"(Lginit),
               "r"(Lg), "r"(Rg), "r"(Jg_f) : "memory");
}
#endif

struct Candidate {
  std::string name;
  ArmFunction fn;
  double tolerance;  // relative, against cgagen's double kernel
  std::vector<double> rounds_ns;
};

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// One round: the angle sets over and over for at least `min_seconds`; ns per call.
double round_ns(ArmFunction fn, const std::vector<double>& angles, double min_seconds) {
  const size_t sets = angles.size() / 5;
  ArmResult r{};
  double acc = 0;
  size_t calls = 0;
  const auto start = std::chrono::steady_clock::now();
  double elapsed = 0;
  do {
    for (size_t i = 0; i < sets; ++i) {
      fn(&angles[5 * i], r);
      acc += r.gripper[0];
    }
    calls += sets;
  } while ((elapsed = seconds_since(start)) < min_seconds);
  asm volatile("" : : "r"(acc));
  return elapsed * 1e9 / static_cast<double>(calls);
}

}  // namespace
}  // namespace cga::bench_arm

int main(int argc, char** argv) {
  using namespace cga::bench_arm;
  const bool quick = argc > 1 && std::string(argv[1]) == "--quick";
  std::mt19937_64 rng(2020);
  std::uniform_real_distribution<double> angle(-3.1, 3.1);
  std::vector<double> angles(5 * 1024);
  for (double& a : angles) a = angle(rng);

  std::vector<Candidate> all = {{"cgagen -O2, double", arm_cgagen<double>, 1e-12, {}},
                                {"cgagen -O2, float", arm_cgagen<float>, 2e-3, {}}};
#ifdef CGA_WITH_GABENCH_IK
  all.push_back({"cgagen -O2, ga-benchmark's script, double", arm_gabench<double>, 1e-12, {}});
#endif
#ifdef CGA_WITH_GATL
  // GATL at -a computes cgagen's chain at a (its dual has the other sign; arm_gatl negates the angles).
  all.push_back({"GATL, double", arm_gatl, 1e-4, {}});
#endif

  // Agreement first: a timing of a wrong result means nothing.
  int failures = 0;
  for (auto& c : all) {
    double worst = 0;
    for (size_t i = 0; i < angles.size() / 5; ++i) {
      ArmResult ref{}, got{};
      arm_cgagen<double>(&angles[5 * i], ref);
      c.fn(&angles[5 * i], got);
      const double scale = std::max({1.0, std::abs(ref.gripper[0]), std::abs(ref.gripper[1]), std::abs(ref.gripper[2])});
      for (int k = 0; k < 3; ++k) worst = std::max(worst, std::abs(got.gripper[k] - ref.gripper[k]) / scale);
      for (int k = 0; k < 5; ++k)
        worst = std::max(worst, std::abs(got.rotor_scalars[k] - ref.rotor_scalars[k]) /
                                    std::max(1.0, std::abs(ref.rotor_scalars[k])));
    }
    std::printf("check %-20s max relative difference to cgagen double %.2e (limit %.0e)%s\n", c.name.c_str(), worst,
                c.tolerance, worst <= c.tolerance ? "" : "  FAILED");
    if (!(worst <= c.tolerance)) ++failures;
  }
  if (failures) return 1;

  const int rounds = quick ? 1 : 7;
  const double min_seconds = quick ? 0.01 : 0.25;
  for (int r = 0; r < rounds; ++r)
    for (auto& c : all) c.rounds_ns.push_back(round_ns(c.fn, angles, min_seconds));

  std::printf("\n5-joint arm chain (bench/ik_arm/arm5.clu), ns per call, median of %d rounds\n", rounds);
  const double base = [&] {
    auto v = all[0].rounds_ns;
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
  }();
  double gatl = 0, gabench = 0;
  for (auto& c : all) {
    std::sort(c.rounds_ns.begin(), c.rounds_ns.end());
    const double median = c.rounds_ns[c.rounds_ns.size() / 2];
    if (c.name.rfind("GATL", 0) == 0) gatl = median;
    if (c.name.find("ga-benchmark") != std::string::npos) gabench = median;
    std::printf("  %-42s %8.1f ns  (rounds %.1f .. %.1f)\n", c.name.c_str(), median, c.rounds_ns.front(),
                c.rounds_ns.back());
  }
  if (gatl > 0) std::printf("cgagen double (arm5.clu) / GATL double: %.2fx the time\n", base / gatl);
  if (gatl > 0 && gabench > 0)
    std::printf("cgagen double (ga-benchmark's script) / GATL double: %.2fx the time\n", gabench / gatl);
  return 0;
}
