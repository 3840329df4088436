// SamplingJob (see jobs.hpp): a clip's keys at one time, for every joint at once, from the clip's
// per-interval keys (ClipIntervals). paper and nlerp run vectorized across joints (sample_paper,
// sample_nlerp), screw per joint (motor log/exp). Run() never allocates.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "common.hpp"

namespace cga {

namespace {

// The paper's lerp of every joint (generated motor_lerp_paper), reading one interval's SoA keys (stride w,
// a multiple of kB, so whole blocks are always readable).
CGA_JOBS_CLONES void sample_paper(std::size_t n, std::size_t w, float t, const float* __restrict t0,
                                  const float* __restrict inv, const float* __restrict r0,
                                  const float* __restrict r1, const float* __restrict s0,
                                  const float* __restrict s1, Motor* __restrict out) {
  for (std::size_t j0 = 0; j0 < n; j0 += kB) {
    Block res;
    for (std::size_t l = 0; l < kB; ++l) {
      const std::size_t j = j0 + l;
      const float a = (t - t0[j]) * inv[j];
      float x[kR], y[kR], m[kM];
      for (std::size_t c = 0; c < kR; ++c) x[c] = r0[c * w + j], y[c] = r1[c * w + j];
      kernels::motor_lerp_paper(x, y, s0[j], s1[j], a, m);
      for (std::size_t c = 0; c < kM; ++c) res[c][l] = m[c];
    }
    store_block(res, std::min(kB, n - j0), out + j0);
  }
}

// nlerp of every joint: key i plus alpha times the (sign-matched) difference, normalized; 8 joints per step
// as coefficient rows (the interval's SoA arrays are padded to whole blocks).
CGA_JOBS_CLONES void sample_nlerp(std::size_t n, std::size_t w, float t, const float* __restrict t0,
                                  const float* __restrict inv, const float* __restrict m0,
                                  const float* __restrict md, Motor* __restrict out) {
#if defined(__GNUC__)
  for (std::size_t j0 = 0; j0 < n; j0 += kB) {
    const v8f a = (t - load8(t0 + j0)) * load8(inv + j0);
    v8f m[kM];
    for (std::size_t c = 0; c < kM; ++c) m[c] = load8(m0 + c * w + j0) + a * load8(md + c * w + j0);
    normalize_rows(m);
    scatter_rows(m, std::min(kB, n - j0), out + j0);
  }
#else
  for (std::size_t j = 0; j < n; ++j) {
    const float a = (t - t0[j]) * inv[j];
    float m[kM];
    for (std::size_t c = 0; c < kM; ++c) m[c] = m0[c * w + j] + a * md[c * w + j];
    motor_normalize_fast(m, out[j].c.data());
  }
#endif
}

}  // namespace

bool SamplingJob::Validate() const {
  if (!clip || !known_mode(mode)) return false;
  const std::size_t n = clip->keys.size();
  if (!fits(output, n)) return false;
  if (!std::isfinite(time)) return false;
  if (n == 0) return true;
  // The sampler reads clip->intervals, built by build_joint_keys; a clip whose keys were never built (or
  // a joint without keys) has none that match.
  const ClipIntervals& iv = clip->intervals;
  if (iv.joints != n || iv.times.empty()) return false;
  return iv.has_motors();
}

bool SamplingJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = clip->keys.size();
  if (n == 0) return true;
  const ClipIntervals& iv = clip->intervals;
  const std::size_t w = iv.stride;
  // Before the first key of every joint the first key holds, which interval 0 gives for t = times[0].
  const float t = std::max(std::clamp(time, 0.0f, clip->duration), iv.times.front());
  const std::size_t u = iv.find(t);
  const float* t0 = iv.t0.data() + u * w;
  const float* inv = iv.inv_span.data() + u * w;
  const std::uint32_t* key = iv.key.data() + u * w;
  switch (mode) {
    case Interpolation::paper:
      sample_paper(n, w, t, t0, inv, iv.rigid0.data() + u * kR * w, iv.rigid1.data() + u * kR * w,
                   iv.scale0.data() + u * w, iv.scale1.data() + u * w, output.data());
      break;
    case Interpolation::nlerp:
      sample_nlerp(n, w, t, t0, inv, iv.motor0.data() + u * kM * w, iv.motor_delta.data() + u * kM * w,
                   output.data());
      break;
    default:  // screw (Validate admits the motor modes only)
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        const std::size_t i = key[j];
        const float a = (t - t0[j]) * inv[j];
        output[j] = a == 0.0f ? k.motors[i] : motor_screw(k.motors[i], k.motors[i + 1], a);
      }
      break;
  }
  return true;
}

}  // namespace cga
