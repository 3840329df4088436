// gabench's cgagen side, registered by the translation units that GabenchScripts.cmake writes: each generated
// kernel as called (cg_unary/cg_binary of gabench.hpp) and on local copies of its arguments (below).
#pragma once

#include "gabench.hpp"

namespace gabench {

// The same kernels called on local copies of their arguments ("cgagen (local args)"): the kernel's arguments and
// result are pointers, and once the result array has escaped to DoNotOptimize the compiler must assume a store
// to R[k] may change A or B, so it reloads every input after every store and cannot vectorize; GATL's values
// have no such question. Copying the inputs into arrays whose address never escapes removes the aliasing (each
// input is still loaded once per call); the difference between the two cgagen rows is that cost.
template <auto Kernel, std::size_t NA, std::size_t NR>
Side cg_unary_local(const Inputs& in, const std::array<std::string_view, NR>& blades) {
  Side s = cg_unary<Kernel, NR>(in, blades);
  const BladeSet* a = in.a;
  s.run = [a](benchmark::State& state) {
    if (!enough(state)) return;
    const double* pa = a->coeffs.data();
    for (auto _ : state) {
      double x[NA], r[NR];
      for (std::size_t k = 0; k < NA; ++k) x[k] = pa[k];
      Kernel(x, r);
      benchmark::DoNotOptimize(r);
      pa += NA;
    }
  };
  return s;
}

template <auto Kernel, std::size_t NA, std::size_t NB, std::size_t NR>
Side cg_binary_local(const Inputs& in, const std::array<std::string_view, NR>& blades) {
  Side s = cg_binary<Kernel, NR>(in, blades);
  const BladeSet* a = in.a;
  const BladeSet* b = in.b;
  s.run = [a, b](benchmark::State& state) {
    if (!enough(state)) return;
    const double* pa = a->coeffs.data();
    const double* pb = b->coeffs.data();
    for (auto _ : state) {
      double x[NA], y[NB], r[NR];
      for (std::size_t k = 0; k < NA; ++k) x[k] = pa[k];
      for (std::size_t k = 0; k < NB; ++k) y[k] = pb[k];
      Kernel(x, y, r);
      benchmark::DoNotOptimize(r);
      pa += NA;
      pb += NB;
    }
  };
  return s;
}

}  // namespace gabench

// One generated kernel MODEL_OP_GA[_GB] (cgagen's double overload, NA/NB coefficients in) registered as the
// "cgagen" side and, called on local copies of its arguments, as "cgagen-local".
#define GABENCH_KERNEL_UNARY(MODEL, OP, GA, NA)                                                                   \
  const bool GABENCH_CAT(kernel_, MODEL##_##OP##_##GA) = ::gabench::add(                                       \
      {#MODEL, #OP, "cgagen", GA, -1, [](const ::gabench::Inputs& in) {                                     \
         constexpr auto& blades = MODEL##_##OP##_##GA##_R_blades;                                          \
         return ::gabench::cg_unary<static_cast<::gabench::UnaryKernel>(&MODEL##_##OP##_##GA),             \
                                    std::tuple_size_v<std::remove_reference_t<decltype(blades)>>>(in, blades); \
       }});                                                                                                 \
  const bool GABENCH_CAT(reg_local_, MODEL##_##OP##_##GA) = ::gabench::add(                                 \
      {#MODEL, #OP, "cgagen-local", GA, -1, [](const ::gabench::Inputs& in) {                               \
         constexpr auto& blades = MODEL##_##OP##_##GA##_R_blades;                                          \
         return ::gabench::cg_unary_local<static_cast<::gabench::UnaryKernel>(&MODEL##_##OP##_##GA), NA,   \
                                          std::tuple_size_v<std::remove_reference_t<decltype(blades)>>>(in, blades); \
       }});
#define GABENCH_KERNEL_BINARY(MODEL, OP, GA, GB, NA, NB)                                                          \
  const bool GABENCH_CAT(kernel_, MODEL##_##OP##_##GA##_##GB) = ::gabench::add(                                \
      {#MODEL, #OP, "cgagen", GA, GB, [](const ::gabench::Inputs& in) {                                     \
         constexpr auto& blades = MODEL##_##OP##_##GA##_##GB##_R_blades;                                   \
         return ::gabench::cg_binary<static_cast<::gabench::BinaryKernel>(&MODEL##_##OP##_##GA##_##GB),    \
                                     std::tuple_size_v<std::remove_reference_t<decltype(blades)>>>(in, blades); \
       }});                                                                                                 \
  const bool GABENCH_CAT(reg_local_, MODEL##_##OP##_##GA##_##GB) = ::gabench::add(                          \
      {#MODEL, #OP, "cgagen-local", GA, GB, [](const ::gabench::Inputs& in) {                               \
         constexpr auto& blades = MODEL##_##OP##_##GA##_##GB##_R_blades;                                   \
         return ::gabench::cg_binary_local<static_cast<::gabench::BinaryKernel>(&MODEL##_##OP##_##GA##_##GB), \
                                           NA, NB, std::tuple_size_v<std::remove_reference_t<decltype(blades)>>>(in, blades); \
       }});
