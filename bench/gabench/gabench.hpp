// gabench: ga-benchmark's operation set (22 unary and binary operations, every grade pair) on cgagen kernels
// and, with GATL_DIR, on GATL, timed side by side. This header holds what the harness (main.cpp), the
// generated cgagen registrations (GabenchScripts.cmake) and the GATL side (gatl_side.hpp) share: the input
// blades, the registry of implementations, and the batch loop both sides are timed with.
#pragma once

#include <benchmark/benchmark.h>

#include <array>
#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <string_view>
#include <tuple>
#include <type_traits>
#include <vector>

namespace gabench {

// ga-benchmark's batch: this many seeded random arguments, one call per benchmark iteration.
inline constexpr std::size_t kSamples = 10000;

// Random blades of one grade, as ga-benchmark makes them: scalar times the outer product of `grade` vectors.
// factors: sample-major, `grade` vectors of `dim` coordinates each, over the model's vectors in GATL's
// order; coeffs: the blade over cgagen's blades of that grade (cgagen's order), `blades` per sample.
struct BladeSet {
  int grade = 0;
  int dim = 0;
  int blades = 0;
  std::vector<double> scalars;
  std::vector<double> factors;
  std::vector<double> coeffs;
  const double* factor(std::size_t sample, int k) const { return factors.data() + (sample * grade + k) * dim; }
  const double* coeff(std::size_t sample) const { return coeffs.data() + sample * blades; }
};

// The arguments of one case: A (and B for a binary operation).
struct Inputs {
  const BladeSet* a = nullptr;
  const BladeSet* b = nullptr;
};

// A result by cgagen blade name ("1", "e1^einf", ...), coefficient.
using Named = std::map<std::string, double>;

// One implementation of one case, ready to run: `run` is the benchmark body, `eval` the result of sample i.
struct Side {
  std::function<void(benchmark::State&)> run;
  std::function<Named(std::size_t)> eval;
};

struct Entry {
  std::string model, op, solution;  // solution: "cgagen" or "GATL"
  int ga = 0, gb = -1;              // gb < 0: unary
  std::function<Side(const Inputs&)> make;
};

std::vector<Entry>& registry();
bool add(Entry e);

// The timed loop of both sides is ga-benchmark's: one call per iteration on the next argument (a fixed count
// of iterations, kSamples, so each argument is used once), its result kept by DoNotOptimize (so stored, on
// both sides alike). More iterations than arguments is an error.
inline bool enough(benchmark::State& state) {
  if (state.max_iterations <= static_cast<benchmark::IterationCount>(kSamples)) return true;
  state.SkipWithError("gabench: more iterations than arguments");
  return false;
}

// A GATL result as printed by GATL's operator<< ("c * <e1^no> + ..."), read back by cgagen blade name.
Named parse_gatl(const std::string& model, const std::string& text);

// ---- the cgagen side: a kernel `void k(const double A[], [const double B[],] double R[])`, registered by
// cg_side.hpp's macros ----

template <std::size_t NR>
inline Named named(const std::array<std::string_view, NR>& blades, const double* r) {
  Named out;
  for (std::size_t k = 0; k < NR; ++k)
    if (r[k] != 0.0) out[std::string(blades[k])] += r[k];
  return out;
}

// The timed loops hoist the argument pointers into locals, so that the DoNotOptimize barrier (which clobbers
// memory) reloads nothing but the arguments themselves: the same on both sides (gatl_side.hpp).
template <auto Kernel, std::size_t NR>
Side cg_unary(const Inputs& in, const std::array<std::string_view, NR>& blades) {
  const BladeSet* a = in.a;
  Side s;
  s.run = [a](benchmark::State& state) {
    if (!enough(state)) return;
    const double* pa = a->coeffs.data();
    const std::size_t na = static_cast<std::size_t>(a->blades);
    for (auto _ : state) {
      double r[NR];
      Kernel(pa, r);
      benchmark::DoNotOptimize(r);
      pa += na;
    }
  };
  s.eval = [a, &blades](std::size_t i) {
    double r[NR];
    Kernel(a->coeff(i), r);
    return named(blades, r);
  };
  return s;
}

template <auto Kernel, std::size_t NR>
Side cg_binary(const Inputs& in, const std::array<std::string_view, NR>& blades) {
  const BladeSet* a = in.a;
  const BladeSet* b = in.b;
  Side s;
  s.run = [a, b](benchmark::State& state) {
    if (!enough(state)) return;
    const double* pa = a->coeffs.data();
    const double* pb = b->coeffs.data();
    const std::size_t na = static_cast<std::size_t>(a->blades), nb = static_cast<std::size_t>(b->blades);
    for (auto _ : state) {
      double r[NR];
      Kernel(pa, pb, r);
      benchmark::DoNotOptimize(r);
      pa += na;
      pb += nb;
    }
  };
  s.eval = [a, b, &blades](std::size_t i) {
    double r[NR];
    Kernel(a->coeff(i), b->coeff(i), r);
    return named(blades, r);
  };
  return s;
}

using UnaryKernel = void (*)(const double*, double*);
using BinaryKernel = void (*)(const double*, const double*, double*);

}  // namespace gabench

#define GABENCH_CAT_(a, b) a##b
#define GABENCH_CAT(a, b) GABENCH_CAT_(a, b)
