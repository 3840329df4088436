// LocalToModelJob (see jobs.hpp): model space from local space down the skeleton, parents first, by the
// 8-blade rigid product when no local motor has a dilation and by the split form of the motor product
// otherwise (common.hpp). Run() never allocates.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "common.hpp"
#include "../detail/rigid_mul_simd.hpp"

namespace cga {

namespace {

bool all_rigid(std::span<const Motor> m, std::size_t n) { return all_rigid(m.data(), n); }

// model[j] = model[parent] * local[j], parents first; rigid: every motor has b = 0 (8-blade product).
CGA_JOBS_CLONES void local_to_model_rigid(std::size_t n, const int* __restrict parents,
                                          const Motor* __restrict local, Motor* __restrict model) {
  for (std::size_t j = 0; j < n; ++j) {
    if (parents[j] < 0)
      model[j] = local[j];
    else
      detail::motor_mul_rigid_simd(model[parents[j]], local[j], model[j]);
  }
}

// The hierarchy with dilations: the model motors are kept in split form in `model` while the parents are
// read (parents[j] < j), and turned back into blades at the end, so each model motor is rounded into the
// blade form once.
CGA_JOBS_CLONES void local_to_model_general(std::size_t n, const int* __restrict parents,
                                            const Motor* __restrict local, Motor* __restrict model) {
  for (std::size_t j = 0; j < n; ++j) {
    float l[12];
    to_split(local[j], l);
    if (parents[j] < 0)
      std::copy(l, l + 12, model[j].c.data());
    else
      split_mul(model[parents[j]].c.data(), l, model[j].c.data());
  }
  for (std::size_t j = 0; j < n; ++j) {
    const Motor s = model[j];
    from_split(s.c.data(), model[j]);
  }
}

}  // namespace

bool LocalToModelJob::Validate() const {
  if (!skeleton) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  for (std::size_t j = 0; j < n; ++j)
    if (skeleton->parents[j] >= static_cast<int>(j)) return false;
  return fits(input, n) && fits(output, n);
}

bool LocalToModelJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  const int* parents = skeleton->parents.data();
  // Roots copy their local motor, so rigid locals make every model motor rigid.
  if (all_rigid(input, n))
    local_to_model_rigid(n, parents, input.data(), output.data());
  else
    local_to_model_general(n, parents, input.data(), output.data());
  return true;
}

}  // namespace cga
