// The instruction sets of the runtime's dispatched SIMD batch kernels (CPU skinning, ChainIKBatchJob): those
// the build compiled them for and this CPU runs, best first, and a scope that pins the dispatch to one of them,
// so that tests and A/B benchmarks reach every instruction set of the machine. Without a scope each call runs
// the best one.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace cga {

struct SimdTarget {
  std::int64_t bits = 0;  // Highway's target bit (HWY_AVX3, HWY_AVX2, ...)
  std::string name;       // Highway's name for it: "AVX3", "AVX2", "SSE4", "EMU128", ...
};

// Best first; never empty (the build's static instruction set is always there).
std::vector<SimdTarget> simd_targets();

// Dispatch runs `target` (one of simd_targets()) while the scope lives; the process-wide setting, so scopes
// must not overlap across threads. Throws std::invalid_argument for a target not in simd_targets().
class ScopedSimdTarget {
 public:
  explicit ScopedSimdTarget(const SimdTarget& target);
  ~ScopedSimdTarget();
  ScopedSimdTarget(const ScopedSimdTarget&) = delete;
  ScopedSimdTarget& operator=(const ScopedSimdTarget&) = delete;
};

}  // namespace cga
