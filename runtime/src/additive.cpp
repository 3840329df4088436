// Additive layers (see additive.hpp): the delta of a clip from its reference pose and its weighted
// application by the motor log/exp (screw) or by the normalized lerp toward the identity (nlerp).
#include "cga/runtime/additive.hpp"

#include <cmath>

#include "cga/runtime/motor.hpp"
#include "cga/runtime/rotor_sign.hpp"

namespace cga {

bool make_additive_delta(std::span<const Motor> reference, std::span<const Motor> pose, std::span<Motor> delta) {
  if (reference.size() < pose.size() || delta.size() < pose.size()) return false;
  for (std::size_t j = 0; j < pose.size(); ++j)
    delta[j] = motor_normalize_fast(motor_mul(motor_reverse(reference[j]), pose[j]));
  return true;
}

bool AdditiveBlendingJob::Validate() const {
  if (mode != Interpolation::screw && mode != Interpolation::nlerp) return false;
  const std::size_t n = output.size();
  if (base.size() < n) return false;
  for (const AdditiveLayer& l : layers) {
    if (!(l.weight >= 0.0f && l.weight <= 1.0f)) return false;
    if (l.weight > 0.0f && l.deltas.size() < n) return false;
  }
  return true;
}

bool AdditiveBlendingJob::Run() const {
  if (!Validate()) return false;
  const Motor identity;
  for (std::size_t j = 0; j < output.size(); ++j) {
    Motor acc = base[j];
    for (const AdditiveLayer& l : layers) {
      if (l.weight <= 0.0f) continue;
      const Motor& d = l.deltas[j];
      Motor dw;
      if (mode == Interpolation::screw) {
        dw = l.weight >= 1.0f ? d : motor_screw(identity, d, l.weight);
      } else {
        // (1 - w) 1 + w Δ, with Δ's sign matched to the identity's rotor part (its scalar), normalized.
        const float w = rotor_sign::signed_weight(l.weight, rotor_sign::rotor_g(d.c.data(), 0));
        for (int c = 0; c < 12; ++c) dw.c[c] = w * d.c[c];
        dw.c[0] += 1.0f - l.weight;
        dw = motor_normalize_fast(dw);
      }
      acc = motor_mul(acc, dw);
    }
    output[j] = acc;
  }
  return true;
}

}  // namespace cga
