// simd_targets() and ScopedSimdTarget: the dispatched batch kernels' instruction sets, and pinning one.
#include "cga/runtime/simd_targets.hpp"

#include <stdexcept>

#include <fmt/format.h>
#include <hwy/targets.h>

#include "skinning/batch.hpp"

namespace cga {

std::vector<SimdTarget> simd_targets() {
  std::vector<SimdTarget> out;
  for (const std::int64_t t : skinning_detail::batch_targets())
    out.push_back({t, t == HWY_EMU128 ? std::string("EMU128") : std::string(hwy::TargetName(t))});
  return out;
}

ScopedSimdTarget::ScopedSimdTarget(const SimdTarget& target) {
  bool known = false;
  for (const std::int64_t t : skinning_detail::batch_targets()) known |= t == target.bits;
  if (!known)
    throw std::invalid_argument(
        fmt::format("ScopedSimdTarget: {} (bit {}) is not an instruction set of this build and CPU", target.name,
                    target.bits));
  hwy::SetSupportedTargetsForTest(target.bits);
}

ScopedSimdTarget::~ScopedSimdTarget() { hwy::SetSupportedTargetsForTest(0); }

}  // namespace cga
