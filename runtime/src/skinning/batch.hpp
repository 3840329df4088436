// The batch path's block functions (batch.cpp): [method][normals], every method of the table on its blend's
// generated SIMD batch kernels. Private to runtime/src/skinning/.
#pragma once

#include "generated.hpp"

namespace cga::skinning_detail {

const GeneratedBlocks& batch_blocks();

}  // namespace cga::skinning_detail
