// BlendingJob (see jobs.hpp): N weighted poses into one, in the paper's weighted sum, nlerp (sign-matched,
// normalized) or the screw fold; whole poses vectorized across joints (blend_nlerp, scale_into/add_scaled),
// per-joint weights (partial blending) joint by joint. Run() never allocates.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "common.hpp"

namespace cga {

namespace {

// nlerp's blend: the weighted sum with each motor's sign matched to the reference layer's, normalized; 8 joints
// per step as coefficient rows.
CGA_JOBS_CLONES void blend_nlerp(std::size_t n, std::span<const BlendLayer> layers, std::size_t first, float inv,
                                 Motor* __restrict out) {
#if defined(__GNUC__)
  using simd::v8i;
  const auto rows_of = [n](const Motor* m, std::size_t j0, v8f r[kM]) {
    if (j0 + kB <= n) return gather_rows([m, j0](int l) -> const Motor& { return m[j0 + l]; }, r);
    Block b;
    load_block(m + j0, n - j0, b);
    for (std::size_t c = 0; c < kM; ++c) r[c] = load8(b[c]);
  };
  for (std::size_t j0 = 0; j0 < n; j0 += kB) {
    v8f ref[kM], acc[kM], x[kM];
    rows_of(layers[first].motors.data(), j0, ref);
    const float w0 = layers[first].weight * inv;
    for (std::size_t c = 0; c < kM; ++c) acc[c] = w0 * ref[c];
    // The sign fix of rotor_sign.hpp on 8 joints: the reference's rotor part G = a + b.
    using rotor_sign::e_blade, rotor_sign::rotor_blade;
    v8f g[4];
    for (int i = 0; i < 4; ++i) g[i] = ref[rotor_blade(i)] + ref[e_blade(i)];
    for (std::size_t k = first + 1; k < layers.size(); ++k) {
      if (layers[k].weight <= 0.0f) continue;
      rows_of(layers[k].motors.data(), j0, x);
      const float w = layers[k].weight * inv;
      v8f dot = g[0] * (x[rotor_blade(0)] + x[e_blade(0)]);
      for (int i = 1; i < 4; ++i) dot += g[i] * (x[rotor_blade(i)] + x[e_blade(i)]);
      // rotor_sign::signed_weight: w with the dot's sign bit.
      const v8i flip = reinterpret_cast<v8i>(dot) & static_cast<int>(0x80000000u);
      const v8f s = reinterpret_cast<v8f>(reinterpret_cast<v8i>(v8f{} + w) ^ flip);
      for (std::size_t c = 0; c < kM; ++c) acc[c] += s * x[c];
    }
    normalize_rows(acc);
    scatter_rows(acc, std::min(kB, n - j0), out + j0);
  }
#else
  for (std::size_t j = 0; j < n; ++j) {
    const Motor& ref = layers[first].motors[j];
    Motor acc;
    for (std::size_t c = 0; c < kM; ++c) acc.c[c] = layers[first].weight * inv * ref.c[c];
    for (std::size_t k = first + 1; k < layers.size(); ++k) {
      if (layers[k].weight <= 0.0f) continue;
      const Motor& x = layers[k].motors[j];
      const float w = layers[k].weight * inv;
      const float s = rotor_sign::signed_weight(w, motor_rotor_dot(ref, x));
      for (std::size_t c = 0; c < kM; ++c) acc.c[c] += s * x.c[c];
    }
    motor_normalize_fast(acc.c.data(), out[j].c.data());
  }
#endif
}

// out = sum of w_l * in_l over the flat coefficient arrays (the paper's weighted sum).
CGA_JOBS_CLONES void scale_into(std::size_t count, float w, const float* __restrict in, float* __restrict out) {
#pragma GCC ivdep
  for (std::size_t x = 0; x < count; ++x) out[x] = w * in[x];
}
CGA_JOBS_CLONES void add_scaled(std::size_t count, float w, const float* __restrict in, float* __restrict out) {
#pragma GCC ivdep
  for (std::size_t x = 0; x < count; ++x) out[x] += w * in[x];
}

bool has_joint_weights(std::span<const BlendLayer> layers) {
  for (const BlendLayer& l : layers)
    if (l.weight > 0.0f && !l.joint_weights.empty()) return true;
  return false;
}

// The weight layer l gives joint j (0 for a layer left out).
inline float joint_weight(const BlendLayer& l, std::size_t j) {
  if (!(l.weight > 0.0f)) return 0.0f;
  return l.joint_weights.empty() ? l.weight : l.weight * l.joint_weights[j];
}

// Partial blending: every joint normalized by its own weight sum (the per-joint form of the loops above; not
// vectorized across joints, since the weights differ per joint).
void blend_per_joint(Interpolation mode, std::span<const BlendLayer> layers, std::span<const Motor> rest,
                     std::span<Motor> output) {
  for (std::size_t j = 0; j < output.size(); ++j) {
    float total = 0.0f;
    std::size_t first = layers.size();
    for (std::size_t k = 0; k < layers.size(); ++k) {
      const float w = joint_weight(layers[k], j);
      if (w > 0.0f && first == layers.size()) first = k;
      total += w;
    }
    if (!(total > 0.0f)) {
      output[j] = rest[j];
      continue;
    }
    const Motor& ref = layers[first].motors[j];
    Motor acc;
    if (mode == Interpolation::screw) {
      acc = ref;
      float sum = joint_weight(layers[first], j);
      for (std::size_t k = first + 1; k < layers.size(); ++k) {
        const float w = joint_weight(layers[k], j);
        if (!(w > 0.0f)) continue;
        sum += w;
        acc = motor_screw(acc, layers[k].motors[j], w / sum);
      }
      output[j] = motor_normalize_fast(acc);
      continue;
    }
    const float inv = 1.0f / total;
    for (std::size_t c = 0; c < kM; ++c) acc.c[c] = 0.0f;
    for (std::size_t k = first; k < layers.size(); ++k) {
      float w = joint_weight(layers[k], j) * inv;
      if (!(w > 0.0f)) continue;
      const Motor& x = layers[k].motors[j];
      if (mode == Interpolation::nlerp) w = rotor_sign::signed_weight(w, motor_rotor_dot(ref, x));
      for (std::size_t c = 0; c < kM; ++c) acc.c[c] += w * x.c[c];
    }
    output[j] = mode == Interpolation::nlerp ? motor_normalize_fast(acc) : acc;
  }
}

}  // namespace

bool BlendingJob::Validate() const {
  if (layers.empty() || !known_mode(mode)) return false;
  const std::size_t n = output.size();
  if (!rest_pose.empty() && rest_pose.size() < n) return false;
  float total = 0.0f;
  for (const BlendLayer& l : layers) {
    if (!std::isfinite(l.weight)) return false;
    if (l.weight <= 0.0f) continue;
    total += l.weight;
    if (l.motors.size() < n) return false;
    if (!l.joint_weights.empty()) {
      if (l.joint_weights.size() < n) return false;
      for (std::size_t j = 0; j < n; ++j)
        if (!(l.joint_weights[j] >= 0.0f) || !std::isfinite(l.joint_weights[j])) return false;
    }
  }
  if (!(total > 0.0f)) return false;
  // With per-joint weights a joint may get none: then it needs the rest pose.
  if (rest_pose.empty() && has_joint_weights(layers))
    for (std::size_t j = 0; j < n; ++j) {
      float sum = 0.0f;
      for (const BlendLayer& l : layers) sum += joint_weight(l, j);
      if (!(sum > 0.0f)) return false;
    }
  return true;
}

bool BlendingJob::Run() const {
  if (!Validate()) return false;
  float total = 0.0f;
  for (const BlendLayer& l : layers) total += std::max(l.weight, 0.0f);
  const float inv = 1.0f / total;
  // The first contributing layer is the reference for sign fixes and the start of the screw fold.
  std::size_t first = 0;
  while (layers[first].weight <= 0.0f) ++first;
  const std::size_t n = output.size();
  if (has_joint_weights(layers)) {
    blend_per_joint(mode, layers, rest_pose, output);
    return true;
  }

  switch (mode) {
    case Interpolation::paper: {
      float* out = output.data()->c.data();
      scale_into(n * kM, layers[first].weight * inv, layers[first].motors.data()->c.data(), out);
      for (std::size_t l = first + 1; l < layers.size(); ++l)
        if (layers[l].weight > 0.0f) add_scaled(n * kM, layers[l].weight * inv, layers[l].motors.data()->c.data(), out);
      break;
    }
    case Interpolation::nlerp: blend_nlerp(n, layers, first, inv, output.data()); break;
    default:  // screw
      for (std::size_t j = 0; j < n; ++j) {
        Motor acc = layers[first].motors[j];
        float sum = layers[first].weight;
        for (std::size_t k = first + 1; k < layers.size(); ++k) {
          if (layers[k].weight <= 0.0f) continue;
          sum += layers[k].weight;
          acc = motor_screw(acc, layers[k].motors[j], layers[k].weight / sum);
        }
        output[j] = motor_normalize_fast(acc);
      }
      break;
  }
  return true;
}

}  // namespace cga
