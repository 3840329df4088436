// The GLM baseline pose jobs and the any-mode pipeline (see cga/baselines/pose_jobs.hpp). Straightforward
// per-joint loops: they are what the motor jobs are measured against, not tuned themselves.
#include "cga/baselines/pose_jobs.hpp"

#include <algorithm>
#include <cmath>

#include "cga/runtime/motor.hpp"

namespace cga::baseline {

namespace {

inline glm::dualquat normalized(const glm::dualquat& q) {
  const float n = glm::length(q.real);
  return glm::dualquat(q.real / n, q.dual / n);
}

template <class Span>
bool fits(const Span& s, std::size_t n) {
  return s.size() >= n;
}

bool parents_ok(const Skeleton& sk) {
  for (int j = 0; j < sk.joint_count(); ++j)
    if (sk.parents[j] >= j) return false;
  return true;
}

// The clip's per-joint keys hold the baseline representations, and its intervals the key indices.
bool clip_ok(const Clip* clip, float time) {
  if (!clip || !std::isfinite(time)) return false;
  const std::size_t n = clip->keys.size();
  if (n == 0) return true;
  const ClipIntervals& iv = clip->intervals;
  if (iv.joints != n || iv.times.empty()) return false;
  for (const JointKeys& k : clip->keys)
    if (k.size() == 0 || k.transforms.size() != k.size() || k.dual_quats.size() != k.size()) return false;
  return true;
}

// Calls f(j, key index i, alpha) for every joint at `time`.
template <class F>
void for_each_joint_key(const Clip& clip, float time, F&& f) {
  const std::size_t n = clip.keys.size();
  if (n == 0) return;
  const ClipIntervals& iv = clip.intervals;
  const std::size_t w = iv.stride;
  const float t = std::max(std::clamp(time, 0.0f, clip.duration), iv.times.front());
  const std::size_t u = iv.find(t);
  const float* t0 = iv.t0.data() + u * w;
  const float* inv = iv.inv_span.data() + u * w;
  const std::uint32_t* key = iv.key.data() + u * w;
  for (std::size_t j = 0; j < n; ++j) f(j, static_cast<std::size_t>(key[j]), (t - t0[j]) * inv[j]);
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

// ------------------------------------------------------------------------------------------ Transform / mat4

bool TransformSamplingJob::Validate() const { return clip_ok(clip, time) && fits(output, clip->keys.size()); }

bool TransformSamplingJob::Run() const {
  if (!Validate()) return false;
  for_each_joint_key(*clip, time, [&](std::size_t j, std::size_t i, float a) {
    const JointKeys& k = clip->keys[j];
    if (a == 0.0f) {
      output[j] = k.transforms[i];
      return;
    }
    const Transform& x = k.transforms[i];
    const Transform& y = k.transforms[i + 1];
    output[j].translation = glm::mix(x.translation, y.translation, a);
    output[j].rotation = glm::normalize(glm::slerp(x.rotation, y.rotation, a));
    output[j].scale = x.scale + (y.scale - x.scale) * a;
  });
  return true;
}

bool TransformBlendingJob::Validate() const {
  float total = 0.0f;
  for (const TransformLayer& l : layers) {
    if (!std::isfinite(l.weight)) return false;
    if (l.weight <= 0.0f) continue;
    total += l.weight;
    if (l.transforms.size() < output.size()) return false;
  }
  return total > 0.0f;
}

bool TransformBlendingJob::Run() const {
  if (!Validate()) return false;
  float total = 0.0f;
  for (const TransformLayer& l : layers) total += std::max(l.weight, 0.0f);
  const float inv = 1.0f / total;
  std::size_t first = 0;
  while (layers[first].weight <= 0.0f) ++first;
  for (std::size_t j = 0; j < output.size(); ++j) {
    glm::vec3 t(0.0f);
    glm::quat q(0.0f, 0.0f, 0.0f, 0.0f);
    float s = 0.0f;
    const glm::quat& ref = layers[first].transforms[j].rotation;
    for (const TransformLayer& l : layers) {
      if (l.weight <= 0.0f) continue;
      const Transform& x = l.transforms[j];
      const float w = l.weight * inv;
      t += w * x.translation;
      q = q + x.rotation * (glm::dot(ref, x.rotation) < 0.0f ? -w : w);
      s += w * x.scale;
    }
    output[j] = Transform{t, glm::normalize(q), s};
  }
  return true;
}

bool MatrixLocalToModelJob::Validate() const {
  if (!skeleton || !parents_ok(*skeleton)) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  return fits(input, n) && fits(output, n);
}

bool MatrixLocalToModelJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  for (std::size_t j = 0; j < n; ++j) {
    const Transform& x = input[j];
    glm::mat4 local = glm::mat4_cast(x.rotation) * x.scale;
    local[3] = glm::vec4(x.translation, 1.0f);
    const int p = skeleton->parents[j];
    output[j] = p < 0 ? local : output[p] * local;
  }
  return true;
}

bool MatrixPaletteJob::Validate() const {
  const std::size_t n = joint_remap.size();
  if (!fits(output, n) || !fits(inverse_bind, n)) return false;
  for (int j : joint_remap)
    if (j < 0 || static_cast<std::size_t>(j) >= model.size()) return false;
  return true;
}

bool MatrixPaletteJob::Run() const {
  if (!Validate()) return false;
  for (std::size_t k = 0; k < joint_remap.size(); ++k)
    output[k] = to_palette_matrix(model[joint_remap[k]] * inverse_bind[k]);
  return true;
}

// ------------------------------------------------------------------------------- dual quaternion + scale

bool DualQuatSamplingJob::Validate() const {
  return clip_ok(clip, time) && fits(output, clip->keys.size()) && fits(output_scales, clip->keys.size());
}

bool DualQuatSamplingJob::Run() const {
  if (!Validate()) return false;
  for_each_joint_key(*clip, time, [&](std::size_t j, std::size_t i, float a) {
    const JointKeys& k = clip->keys[j];
    if (a == 0.0f) {
      output[j] = k.dual_quats[i];
      output_scales[j] = k.transforms[i].scale;
      return;
    }
    output[j] = normalized(glm::lerp(k.dual_quats[i], k.dual_quats[i + 1], a));
    output_scales[j] = k.transforms[i].scale + (k.transforms[i + 1].scale - k.transforms[i].scale) * a;
  });
  return true;
}

bool DualQuatBlendingJob::Validate() const {
  const std::size_t n = output.size();
  if (output_scales.size() < n) return false;
  float total = 0.0f;
  for (const DualQuatLayer& l : layers) {
    if (!std::isfinite(l.weight)) return false;
    if (l.weight <= 0.0f) continue;
    total += l.weight;
    if (l.dual_quats.size() < n || l.scales.size() < n) return false;
  }
  return total > 0.0f;
}

bool DualQuatBlendingJob::Run() const {
  if (!Validate()) return false;
  float total = 0.0f;
  for (const DualQuatLayer& l : layers) total += std::max(l.weight, 0.0f);
  const float inv = 1.0f / total;
  std::size_t first = 0;
  while (layers[first].weight <= 0.0f) ++first;
  for (std::size_t j = 0; j < output.size(); ++j) {
    glm::dualquat q(glm::quat(0.0f, 0.0f, 0.0f, 0.0f), glm::quat(0.0f, 0.0f, 0.0f, 0.0f));
    float s = 0.0f;
    const glm::quat& ref = layers[first].dual_quats[j].real;
    for (const DualQuatLayer& l : layers) {
      if (l.weight <= 0.0f) continue;
      const float w = l.weight * inv;
      const glm::dualquat& x = l.dual_quats[j];
      q = q + x * (glm::dot(ref, x.real) < 0.0f ? -w : w);
      s += w * l.scales[j];
    }
    output[j] = normalized(q);
    output_scales[j] = s;
  }
  return true;
}

bool DualQuatLocalToModelJob::Validate() const {
  if (!skeleton || !parents_ok(*skeleton)) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  return fits(input, n) && fits(input_scales, n) && fits(output, n) && fits(output_scales, n);
}

bool DualQuatLocalToModelJob::Run() const {
  if (!Validate()) return false;
  const std::size_t n = static_cast<std::size_t>(skeleton->joint_count());
  for (std::size_t j = 0; j < n; ++j) {
    const int p = skeleton->parents[j];
    if (p < 0) {
      output[j] = input[j];
      output_scales[j] = input_scales[j];
      continue;
    }
    const float ps = output_scales[p];
    glm::dualquat local = input[j];
    // s_p R_p (s_l R_l x + t_l) + t_p = rigid(R_p R_l, s_p R_p t_l + t_p) applied to (s_p s_l) x.
    if (ps != 1.0f) local = glm::dualquat(local.real, dual_quat_translation(local) * ps);
    output[j] = normalized(output[p] * local);
    output_scales[j] = ps * input_scales[j];
  }
  return true;
}

bool DualQuatPaletteJob::Validate() const {
  const std::size_t n = joint_remap.size();
  if (!fits(output, n) || !fits(inverse_bind, n)) return false;
  const std::size_t joints = std::min(model.size(), model_scales.size());
  for (int j : joint_remap)
    if (j < 0 || static_cast<std::size_t>(j) >= joints) return false;
  return true;
}

bool DualQuatPaletteJob::Run() const {
  if (!Validate()) return false;
  for (std::size_t k = 0; k < joint_remap.size(); ++k) {
    const float ps = model_scales[joint_remap[k]];
    glm::dualquat ib = inverse_bind[k];
    if (ps != 1.0f) ib = glm::dualquat(ib.real, dual_quat_translation(ib) * ps);
    output[k] = normalized(model[joint_remap[k]] * ib);
  }
  return true;
}

// ------------------------------------------------------------------------------------ any-mode pipeline

namespace {

// The Interpolation of a motor PoseMode (the values are shared). A value outside the enum stays one, and the
// motor job's Validate() refuses it, so the pipeline returns false where to_interpolation() would throw.
Interpolation motor_mode(PoseMode mode) { return static_cast<Interpolation>(mode); }

}  // namespace

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
  ib.motors = make_inverse_bind_motors(mesh);
  return ib;
}

bool sample(PoseMode mode, const Clip& clip, float time, PoseBuffer& out) {
  switch (mode) {
    case PoseMode::glm_matrix: return TransformSamplingJob{&clip, time, out.transforms}.Run();
    case PoseMode::glm_dualquat: return DualQuatSamplingJob{&clip, time, out.dual_quats, out.scales}.Run();
    default: return SamplingJob{&clip, time, motor_mode(mode), out.motors}.Run();
  }
}

bool blend(PoseMode mode, std::span<const PoseLayer> layers, PoseBuffer& out) {
  constexpr std::size_t kMaxLayers = 16;
  if (layers.size() > kMaxLayers) return false;
  for (const PoseLayer& l : layers)
    if (!l.pose) return false;
  switch (mode) {
    case PoseMode::glm_matrix: {
      TransformLayer t[kMaxLayers];
      for (std::size_t k = 0; k < layers.size(); ++k) t[k] = {layers[k].weight, layers[k].pose->transforms};
      return TransformBlendingJob{{t, layers.size()}, out.transforms}.Run();
    }
    case PoseMode::glm_dualquat: {
      DualQuatLayer d[kMaxLayers];
      for (std::size_t k = 0; k < layers.size(); ++k)
        d[k] = {layers[k].weight, layers[k].pose->dual_quats, layers[k].pose->scales};
      return DualQuatBlendingJob{{d, layers.size()}, out.dual_quats, out.scales}.Run();
    }
    default: {
      BlendLayer m[kMaxLayers];
      for (std::size_t k = 0; k < layers.size(); ++k) m[k] = {layers[k].weight, layers[k].pose->motors};
      return BlendingJob{motor_mode(mode), {m, layers.size()}, out.motors}.Run();
    }
  }
}

bool local_to_model(PoseMode mode, const Skeleton& skeleton, const PoseBuffer& local, PoseBuffer& model) {
  switch (mode) {
    case PoseMode::glm_matrix: return MatrixLocalToModelJob{&skeleton, local.transforms, model.matrices}.Run();
    case PoseMode::glm_dualquat:
      return DualQuatLocalToModelJob{&skeleton, local.dual_quats, local.scales, model.dual_quats, model.scales}.Run();
    default: return LocalToModelJob{&skeleton, local.motors, model.motors}.Run();
  }
}

bool palette(PoseMode mode, std::span<const int> joint_remap, const InverseBind& inverse_bind,
             const PoseBuffer& model, PaletteBuffer& out) {
  switch (mode) {
    case PoseMode::glm_matrix:
      return MatrixPaletteJob{joint_remap, inverse_bind.matrices, model.matrices, out.matrices}.Run();
    case PoseMode::glm_dualquat:
      return DualQuatPaletteJob{joint_remap, inverse_bind.dual_quats, model.dual_quats, model.scales, out.dual_quats}
          .Run();
    default: return SkinningPaletteJob{joint_remap, inverse_bind.motors, model.motors, out.motors}.Run();
  }
}

glm::vec3 joint_position(PoseMode mode, const PoseBuffer& model, int j) {
  switch (mode) {
    case PoseMode::glm_matrix: return glm::vec3(model.matrices[j][3]);
    case PoseMode::glm_dualquat: return dual_quat_translation(model.dual_quats[j]);
    default: return motor_transform_point(model.motors[j], glm::vec3(0.0f));
  }
}

}  // namespace cga::baseline
