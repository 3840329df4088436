// The batch path's block functions (batch.cpp): [method][normals], every method of the table on its blend's
// generated SIMD batch kernels. Private to runtime/src/skinning/.
#pragma once

#include <cstdint>
#include <vector>

#include "generated.hpp"

namespace cga::skinning_detail {

const GeneratedBlocks& batch_blocks();
// The Highway targets batch.cpp was compiled for that the CPU runs, best first.
std::vector<std::int64_t> batch_targets();

}  // namespace cga::skinning_detail
