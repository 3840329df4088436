// Additive layers in motor form (ozz-animation's additive blending): a clip's delta from its reference pose,
// Δ_j = M_ref,j⁻¹ · M_j per joint, applied on top of a base pose with a weight w:  out_j = base_j · Δ_j(w).
// Two weightings of the delta, both the identity at w = 0 and Δ at w = 1:
//   screw  Δ(w) = exp(w · log Δ): the screw motion of Δ scaled to the fraction w (constant angle and slide
//          along the screw axis; motor_screw from the identity), exact for every w;
//   nlerp  Δ(w) = normalize((1 − w) · 1 + w · Δ) (the paper's lerp toward the identity, sign-fixed and
//          normalized): a multiply-add per coefficient and a normalization instead of a log and an exp, but
//          its angle is not w·θ (exact at w = 1/2; tests/runtime/test_additive.cpp measures the deviation).
// Scaled joints: the delta's dilation is weighted as part of the motor in both modes.
#pragma once

#include <span>

#include "cga/runtime/animation.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

// delta[j] = ~reference[j] · pose[j], normalized (for unit motors ~M is M⁻¹). Sizes: delta >= pose.size(),
// reference >= pose.size(). Returns false on a size mismatch.
bool make_additive_delta(std::span<const Motor> reference, std::span<const Motor> pose, std::span<Motor> delta);

struct AdditiveLayer {
  float weight = 0.0f;              // [0, 1]; 0 leaves the layer out
  std::span<const Motor> deltas;    // size >= output.size()
};

struct AdditiveBlendingJob {
  Interpolation mode = Interpolation::screw;  // screw or nlerp (others are refused)
  std::span<const Motor> base;               // size >= output.size()
  std::span<const AdditiveLayer> layers;     // applied in order: out = base · Δ_0(w_0) · Δ_1(w_1) ...
  std::span<Motor> output;                   // may alias base

  bool Validate() const;
  bool Run() const;
};

}  // namespace cga
