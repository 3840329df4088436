// Sampling, blending, local-to-model and skinning-palette jobs (see jobs.hpp). Run() loops are flat over
// joints with the mode switch outside, and never allocate.
#include "cga/runtime/jobs.hpp"

#include <algorithm>
#include <cmath>

namespace cga {

namespace {

template <class Span>
bool fits(const Span& s, std::size_t n) {
  return s.size() >= n;
}

bool mode_outputs_fit(Interpolation mode, std::size_t n, std::span<Motor> m, std::span<Transform> t,
                      std::span<glm::dualquat> d, std::span<float> s) {
  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp:
    case Interpolation::screw: return fits(m, n);
    case Interpolation::glm_matrix: return fits(t, n);
    case Interpolation::glm_dualquat: return fits(d, n) && fits(s, n);
  }
  return false;
}

// Key index i and fraction a with times[i] <= t < times[i+1]; a == 0 means "exactly key i".
inline void locate(const std::vector<float>& times, float t, std::size_t& i, float& a) {
  const std::size_t n = times.size();
  if (n == 1 || t <= times[0]) {
    i = 0, a = 0.0f;
    return;
  }
  if (t >= times[n - 1]) {
    i = n - 1, a = 0.0f;
    return;
  }
  i = static_cast<std::size_t>(std::upper_bound(times.begin(), times.end(), t) - times.begin()) - 1;
  a = (t - times[i]) / (times[i + 1] - times[i]);
}

inline Motor lerp_signed(const Motor& x, const Motor& y, float a) {
  const float b = motor_rotor_dot(x, y) < 0.0f ? -a : a;
  Motor out;
  for (int c = 0; c < 12; ++c) out.c[c] = (1.0f - a) * x.c[c] + b * y.c[c];
  return out;
}

inline glm::dualquat normalized(const glm::dualquat& q) {
  const float n = glm::length(q.real);
  return glm::dualquat(q.real / n, q.dual / n);
}

}  // namespace

glm::vec3 dual_quat_translation(const glm::dualquat& q) {
  const glm::quat t = (q.dual * glm::conjugate(q.real)) * 2.0f;
  return {t.x, t.y, t.z};
}

glm::mat3x4 to_palette_matrix(const glm::mat4& m) {
  glm::mat3x4 out;
  for (int r = 0; r < 3; ++r) out[r] = glm::vec4(m[0][r], m[1][r], m[2][r], m[3][r]);
  return out;
}

// ---------------------------------------------------------------------------------------------- sampling

bool SamplingJob::Validate() const {
  if (!clip) return false;
  const std::size_t n = clip->keys.size();
  if (!mode_outputs_fit(mode, n, out_motors, out_transforms, out_dual_quats, out_scales)) return false;
  // A joint without keys (a clip never passed through build_joint_keys) has nothing to sample.
  for (const JointKeys& k : clip->keys)
    if (k.size() == 0 || k.transforms.size() != k.size() || k.dual_quats.size() != k.size()) return false;
  if (uses_motors(mode))
    for (const JointKeys& k : clip->keys)
      if (k.motors.size() != k.size() || k.rigid.size() != k.size()) return false;  // built without kernels
  return std::isfinite(time);
}

bool SamplingJob::Run() const {
  if (!Validate()) return false;
  const float t = std::clamp(time, 0.0f, clip->duration);
  const std::size_t n = clip->keys.size();
  std::size_t i;
  float a;
  switch (mode) {
    case Interpolation::paper:
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        locate(k.times, t, i, a);
        out_motors[j] = a == 0.0f ? k.motors[i]
                                  : motor_lerp_paper(k.rigid[i], k.rigid[i + 1], k.transforms[i].scale,
                                                     k.transforms[i + 1].scale, a);
      }
      break;
    case Interpolation::nlerp:
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        locate(k.times, t, i, a);
        out_motors[j] = a == 0.0f ? k.motors[i] : motor_normalize(lerp_signed(k.motors[i], k.motors[i + 1], a));
      }
      break;
    case Interpolation::screw:
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        locate(k.times, t, i, a);
        out_motors[j] = a == 0.0f ? k.motors[i] : motor_screw(k.transforms[i], k.transforms[i + 1], a);
      }
      break;
    case Interpolation::glm_matrix:
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        locate(k.times, t, i, a);
        if (a == 0.0f) {
          out_transforms[j] = k.transforms[i];
          continue;
        }
        const Transform& x = k.transforms[i];
        const Transform& y = k.transforms[i + 1];
        out_transforms[j].translation = glm::mix(x.translation, y.translation, a);
        out_transforms[j].rotation = glm::normalize(glm::slerp(x.rotation, y.rotation, a));
        out_transforms[j].scale = x.scale + (y.scale - x.scale) * a;
      }
      break;
    case Interpolation::glm_dualquat:
      for (std::size_t j = 0; j < n; ++j) {
        const JointKeys& k = clip->keys[j];
        locate(k.times, t, i, a);
        if (a == 0.0f) {
          out_dual_quats[j] = k.dual_quats[i];
          out_scales[j] = k.transforms[i].scale;
          continue;
        }
        out_dual_quats[j] = normalized(glm::lerp(k.dual_quats[i], k.dual_quats[i + 1], a));
        out_scales[j] = k.transforms[i].scale + (k.transforms[i + 1].scale - k.transforms[i].scale) * a;
      }
      break;
  }
  return true;
}

// ---------------------------------------------------------------------------------------------- blending

bool BlendingJob::Validate() const {
  if (layers.empty()) return false;
  std::size_t n = 0;
  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp:
    case Interpolation::screw: n = out_motors.size(); break;
    case Interpolation::glm_matrix: n = out_transforms.size(); break;
    case Interpolation::glm_dualquat: n = out_dual_quats.size(); break;
  }
  float total = 0.0f;
  for (const BlendLayer& l : layers) {
    if (!std::isfinite(l.weight)) return false;
    if (l.weight <= 0.0f) continue;
    total += l.weight;
    switch (mode) {
      case Interpolation::paper:
      case Interpolation::nlerp:
      case Interpolation::screw:
        if (l.motors.size() < n) return false;
        break;
      case Interpolation::glm_matrix:
        if (l.transforms.size() < n) return false;
        break;
      case Interpolation::glm_dualquat:
        if (l.dual_quats.size() < n || l.scales.size() < n || out_scales.size() < n) return false;
        break;
    }
  }
  return total > 0.0f;
}

bool BlendingJob::Run() const {
  if (!Validate()) return false;
  float total = 0.0f;
  for (const BlendLayer& l : layers) total += std::max(l.weight, 0.0f);
  const float inv = 1.0f / total;
  // The first contributing layer is the reference for sign fixes and the start of the screw fold.
  std::size_t first = 0;
  while (layers[first].weight <= 0.0f) ++first;

  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp: {
      const bool fix = mode == Interpolation::nlerp;
      for (std::size_t j = 0; j < out_motors.size(); ++j) {
        Motor acc;
        acc.c.fill(0.0f);
        const Motor& ref = layers[first].motors[j];
        for (const BlendLayer& l : layers) {
          if (l.weight <= 0.0f) continue;
          const float w = l.weight * inv * (fix && motor_rotor_dot(ref, l.motors[j]) < 0.0f ? -1.0f : 1.0f);
          for (int c = 0; c < 12; ++c) acc.c[c] += w * l.motors[j].c[c];
        }
        out_motors[j] = fix ? motor_normalize(acc) : acc;
      }
      break;
    }
    case Interpolation::screw:
      for (std::size_t j = 0; j < out_motors.size(); ++j) {
        Transform acc = motor_to_transform(layers[first].motors[j]);
        float sum = layers[first].weight;
        for (std::size_t k = first + 1; k < layers.size(); ++k) {
          if (layers[k].weight <= 0.0f) continue;
          sum += layers[k].weight;
          acc = transform_screw(acc, motor_to_transform(layers[k].motors[j]), layers[k].weight / sum);
        }
        out_motors[j] = motor_from_transform(acc);
      }
      break;
    case Interpolation::glm_matrix:
      for (std::size_t j = 0; j < out_transforms.size(); ++j) {
        glm::vec3 t(0.0f);
        glm::quat q(0.0f, 0.0f, 0.0f, 0.0f);
        float s = 0.0f;
        const glm::quat& ref = layers[first].transforms[j].rotation;
        for (const BlendLayer& l : layers) {
          if (l.weight <= 0.0f) continue;
          const Transform& x = l.transforms[j];
          const float w = l.weight * inv;
          t += w * x.translation;
          q = q + x.rotation * (glm::dot(ref, x.rotation) < 0.0f ? -w : w);
          s += w * x.scale;
        }
        out_transforms[j] = Transform{t, glm::normalize(q), s};
      }
      break;
    case Interpolation::glm_dualquat:
      for (std::size_t j = 0; j < out_dual_quats.size(); ++j) {
        glm::dualquat q(glm::quat(0.0f, 0.0f, 0.0f, 0.0f), glm::quat(0.0f, 0.0f, 0.0f, 0.0f));
        float s = 0.0f;
        const glm::quat& ref = layers[first].dual_quats[j].real;
        for (const BlendLayer& l : layers) {
          if (l.weight <= 0.0f) continue;
          const float w = l.weight * inv;
          const glm::dualquat& x = l.dual_quats[j];
          q = q + x * (glm::dot(ref, x.real) < 0.0f ? -w : w);
          s += w * l.scales[j];
        }
        out_dual_quats[j] = normalized(q);
        out_scales[j] = s;
      }
      break;
  }
  return true;
}

// ----------------------------------------------------------------------------------------- local to model

bool LocalToModelJob::Validate() const {
  if (!skeleton) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  for (std::size_t j = 0; j < n; ++j)
    if (skeleton->parents[j] >= static_cast<int>(j)) return false;
  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp:
    case Interpolation::screw: return fits(local_motors, n) && fits(model_motors, n);
    case Interpolation::glm_matrix: return fits(local_transforms, n) && fits(model_matrices, n);
    case Interpolation::glm_dualquat:
      return fits(local_dual_quats, n) && fits(local_scales, n) && fits(model_dual_quats, n) &&
             fits(model_scales, n);
  }
  return false;
}

bool LocalToModelJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  const int* parents = skeleton->parents.data();
  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp:
    case Interpolation::screw:
      for (std::size_t j = 0; j < n; ++j)
        model_motors[j] = parents[j] < 0 ? local_motors[j] : motor_mul(model_motors[parents[j]], local_motors[j]);
      break;
    case Interpolation::glm_matrix:
      for (std::size_t j = 0; j < n; ++j) {
        const Transform& x = local_transforms[j];
        glm::mat4 local = glm::mat4_cast(x.rotation) * x.scale;
        local[3] = glm::vec4(x.translation, 1.0f);
        model_matrices[j] = parents[j] < 0 ? local : model_matrices[parents[j]] * local;
      }
      break;
    case Interpolation::glm_dualquat:
      for (std::size_t j = 0; j < n; ++j) {
        if (parents[j] < 0) {
          model_dual_quats[j] = local_dual_quats[j];
          model_scales[j] = local_scales[j];
          continue;
        }
        const float ps = model_scales[parents[j]];
        glm::dualquat local = local_dual_quats[j];
        // s_p R_p (s_l R_l x + t_l) + t_p = rigid(R_p R_l, s_p R_p t_l + t_p) applied to (s_p s_l) x.
        if (ps != 1.0f) local = glm::dualquat(local.real, dual_quat_translation(local) * ps);
        model_dual_quats[j] = normalized(model_dual_quats[parents[j]] * local);
        model_scales[j] = ps * local_scales[j];
      }
      break;
  }
  return true;
}

// --------------------------------------------------------------------------------------- skinning palette

InverseBind make_inverse_bind(const SkinnedMesh& mesh) {
  InverseBind ib;
  const std::size_t n = mesh.joint_remap.size();
  ib.matrices = mesh.inverse_bind_matrix;
  ib.dual_quats.resize(n);
  ib.scales.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    ib.dual_quats[k] = glm::dualquat(mesh.inverse_bind[k].rotation, mesh.inverse_bind[k].translation);
    ib.scales[k] = mesh.inverse_bind[k].scale;
  }
  if constexpr (kHaveMotorKernels) {
    ib.motors.resize(n);
    for (std::size_t k = 0; k < n; ++k) ib.motors[k] = motor_from_transform(mesh.inverse_bind[k]);
  }
  return ib;
}

bool SkinningPaletteJob::Validate() const {
  if (!inverse_bind) return false;
  const std::size_t n = joint_remap.size();
  std::size_t joints = 0;
  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp:
    case Interpolation::screw:
      if (!fits(out_motors, n) || inverse_bind->motors.size() < n) return false;
      joints = model_motors.size();
      break;
    case Interpolation::glm_matrix:
      if (!fits(out_matrices, n) || inverse_bind->matrices.size() < n) return false;
      joints = model_matrices.size();
      break;
    case Interpolation::glm_dualquat:
      if (!fits(out_dual_quats, n) || inverse_bind->dual_quats.size() < n || inverse_bind->scales.size() < n)
        return false;
      joints = std::min(model_dual_quats.size(), model_scales.size());
      break;
  }
  for (int j : joint_remap)
    if (j < 0 || static_cast<std::size_t>(j) >= joints) return false;
  return true;
}

bool SkinningPaletteJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = joint_remap.size();
  switch (mode) {
    case Interpolation::paper:
    case Interpolation::nlerp:
    case Interpolation::screw:
      for (std::size_t k = 0; k < n; ++k)
        out_motors[k] = motor_mul(model_motors[joint_remap[k]], inverse_bind->motors[k]);
      break;
    case Interpolation::glm_matrix:
      for (std::size_t k = 0; k < n; ++k)
        out_matrices[k] = to_palette_matrix(model_matrices[joint_remap[k]] * inverse_bind->matrices[k]);
      break;
    case Interpolation::glm_dualquat:
      for (std::size_t k = 0; k < n; ++k) {
        const float ps = model_scales[joint_remap[k]];
        glm::dualquat ib = inverse_bind->dual_quats[k];
        if (ps != 1.0f) ib = glm::dualquat(ib.real, dual_quat_translation(ib) * ps);
        out_dual_quats[k] = normalized(model_dual_quats[joint_remap[k]] * ib);
      }
      break;
  }
  return true;
}

}  // namespace cga
