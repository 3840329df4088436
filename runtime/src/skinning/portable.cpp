// The portable skinning block functions (plain C++ on the loops of loops.hpp), built twice with
// target_clones: x86-64-v3 (AVX2 + FMA, what GCC auto-vectorizes across vertices) and the baseline ISA.
#include "loops.hpp"

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(__SANITIZE_ADDRESS__)
#define CGA_SKIN_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define CGA_SKIN_CLONES
#endif

namespace cga::skinning_detail {
namespace {

CGA_SKIN_CLONES bool matrix_block_p(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  matrix_block<false>(pal, s, begin, end);
  return true;
}
CGA_SKIN_CLONES bool matrix_block_pn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  matrix_block<true>(pal, s, begin, end);
  return true;
}

CGA_SKIN_CLONES bool dq_block_p(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  dq_block<false>(pal, s, begin, end);
  return true;
}
CGA_SKIN_CLONES bool dq_block_pn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  dq_block<true>(pal, s, begin, end);
  return true;
}

// flatten: GCC does not inline the generated kernel on its own, and the call would keep pass 2 scalar.
CGA_SKIN_CLONES __attribute__((flatten)) bool motor_block_p(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block<false>(pal, s, begin, end);
  return true;
}
CGA_SKIN_CLONES __attribute__((flatten)) bool motor_block_pn(const float* pal, const Streams& s, std::size_t begin, std::size_t end,
    std::size_t palette) {
  if (!block_ok(s.joints, s.weights, begin, end, palette)) return false;
  motor_block<true>(pal, s, begin, end);
  return true;
}

}  // namespace

const SkinKernels& portable_kernels() {
  // The portable loops have no prefetching variant: [.][0] and [.][1] are the same function.
  static const SkinKernels k{"portable",
                             {{matrix_block_p, matrix_block_p}, {matrix_block_pn, matrix_block_pn}},
                             {dq_block_p, dq_block_pn},
                             {{motor_block_p, motor_block_p}, {motor_block_pn, motor_block_pn}},
                             {{nullptr, nullptr}, {nullptr, nullptr}},
                             nullptr,
                             {{nullptr, nullptr}, {nullptr, nullptr}},
                             {}};
  return k;
}

}  // namespace cga::skinning_detail
