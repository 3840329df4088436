// The portable skinning block functions: the generated path of generated.hpp for every method of the table,
// built twice with target_clones: x86-64-v3 (AVX2 + FMA, what GCC auto-vectorizes) and the baseline ISA.
// SkinningJob runs it with use_simd = false; the tests check the batch path against it.
#include "generated.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_SKIN_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define CGA_SKIN_CLONES
#endif

namespace cga::skinning_detail {
namespace {

// flatten: the generated kernels are large; GCC would not inline them on its own.
template <class K, bool kNormals>
CGA_SKIN_CLONES __attribute__((flatten)) bool generated_block_fn(const float* pal, const Streams& s,
                                                                 std::size_t begin, std::size_t end,
                                                                 std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  generated_block<K, kNormals>(pal, s, begin, end);
  return true;
}

}  // namespace

const GeneratedBlocks& generated_blocks() {
  static const GeneratedBlocks blocks{{
#define CGA_METHOD_BLOCKS(id, ...) {generated_block_fn<id##_kernels, false>, generated_block_fn<id##_kernels, true>},
      CGA_SKINNING_METHODS(CGA_METHOD_BLOCKS)
#undef CGA_METHOD_BLOCKS
  }};
  return blocks;
}

}  // namespace cga::skinning_detail
