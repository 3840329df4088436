// Interpolation mode names and the merged per-joint keys of a clip (see animation.hpp).
#include "cga/runtime/animation.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

namespace cga {

std::string_view to_string(Interpolation mode) {
  switch (mode) {
    case Interpolation::paper: return "paper";
    case Interpolation::nlerp: return "nlerp";
    case Interpolation::screw: return "screw";
  }
  return "?";
}

Interpolation parse_interpolation(std::string_view text) {
  for (Interpolation m : kAllInterpolations)
    if (text == to_string(m)) return m;
  throw std::invalid_argument(fmt::format("unknown interpolation mode '{}' (choose paper, nlerp, screw)", text));
}

namespace {

// Index i with times[i] <= t < times[i+1] (clamped to the ends) and the fraction between them.
template <class Key>
std::pair<std::size_t, float> locate(const std::vector<Key>& keys, float t) {
  if (keys.size() == 1 || t <= keys.front().time) return {0, 0.0f};
  if (t >= keys.back().time) return {keys.size() - 1, 0.0f};
  const auto it = std::upper_bound(keys.begin(), keys.end(), t, [](float v, const Key& k) { return v < k.time; });
  const std::size_t i = static_cast<std::size_t>(it - keys.begin()) - 1;
  const float span = keys[i + 1].time - keys[i].time;
  return {i, span > 0.0f ? (t - keys[i].time) / span : 0.0f};
}

glm::vec3 eval(const std::vector<VectorKey>& keys, float t) {
  const auto [i, a] = locate(keys, t);
  if (a == 0.0f) return keys[i].value;
  return glm::mix(keys[i].value, keys[i + 1].value, a);
}
glm::quat eval(const std::vector<RotationKey>& keys, float t) {
  const auto [i, a] = locate(keys, t);
  if (a == 0.0f) return keys[i].value;
  return glm::normalize(glm::slerp(keys[i].value, keys[i + 1].value, a));
}
float eval(const std::vector<ScaleKey>& keys, float t) {
  const auto [i, a] = locate(keys, t);
  if (a == 0.0f) return keys[i].value;
  return keys[i].value + (keys[i + 1].value - keys[i].value) * a;
}

}  // namespace

void build_joint_keys(Clip& clip) {
  clip.keys.assign(clip.tracks.size(), {});
  for (std::size_t j = 0; j < clip.tracks.size(); ++j) {
    const JointTrack& tr = clip.tracks[j];
    if (tr.translations.empty() || tr.rotations.empty() || tr.scales.empty())
      throw std::invalid_argument(fmt::format("clip '{}': joint {} has an empty key track", clip.name, j));
    std::vector<float> times;
    for (const auto& k : tr.translations) times.push_back(k.time);
    for (const auto& k : tr.rotations) times.push_back(k.time);
    for (const auto& k : tr.scales) times.push_back(k.time);
    std::sort(times.begin(), times.end());
    // Times closer than a microsecond are one key (files repeat times with rounding noise).
    times.erase(std::unique(times.begin(), times.end(), [](float a, float b) { return b - a < 1e-6f; }),
                times.end());
    JointKeys& k = clip.keys[j];
    k.times = times;
    k.transforms.resize(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
      k.transforms[i].translation = eval(tr.translations, times[i]);
      k.transforms[i].rotation = eval(tr.rotations, times[i]);
      k.transforms[i].scale = eval(tr.scales, times[i]);
    }
    // Rotations stay sign-continuous after merging (slerp keeps the sign of its first key).
    for (std::size_t i = 1; i < times.size(); ++i)
      if (glm::dot(k.transforms[i - 1].rotation, k.transforms[i].rotation) < 0.0f)
        k.transforms[i].rotation = -k.transforms[i].rotation;
    k.dual_quats.resize(times.size());
    for (std::size_t i = 0; i < times.size(); ++i)
      k.dual_quats[i] = glm::dualquat(k.transforms[i].rotation, k.transforms[i].translation);
    k.motors.resize(times.size());
    k.rigid.resize(times.size());
    for (std::size_t i = 0; i < times.size(); ++i) {
      k.motors[i] = motor_from_transform(k.transforms[i]);
      Transform rigid = k.transforms[i];
      rigid.scale = 1.0f;
      k.rigid[i] = rigid_blades(motor_from_transform(rigid));
    }
  }
  build_clip_intervals(clip);
}

std::size_t ClipIntervals::find(float t) const {
  const auto it = std::upper_bound(times.begin(), times.end(), t);
  return it == times.begin() ? 0 : static_cast<std::size_t>(it - times.begin()) - 1;
}

void build_clip_intervals(Clip& clip) {
  ClipIntervals& iv = clip.intervals;
  iv = ClipIntervals{};
  for (const JointKeys& k : clip.keys) {
    if (k.size() == 0) throw std::invalid_argument(fmt::format("clip '{}': a joint has no keys", clip.name));
    iv.times.insert(iv.times.end(), k.times.begin(), k.times.end());
  }
  std::sort(iv.times.begin(), iv.times.end());
  iv.times.erase(std::unique(iv.times.begin(), iv.times.end()), iv.times.end());
  if (iv.times.empty()) return;  // no joints
  iv.joints = clip.keys.size();
  iv.stride = (iv.joints + ClipIntervals::kLanes - 1) / ClipIntervals::kLanes * ClipIntervals::kLanes;
  const std::size_t n_iv = iv.times.size(), w = iv.stride;
  iv.key.assign(n_iv * w, 0);
  iv.t0.assign(n_iv * w, 0.0f);
  iv.inv_span.assign(n_iv * w, 0.0f);
  iv.scale0.assign(n_iv * w, 1.0f);
  iv.scale1.assign(n_iv * w, 1.0f);
  const bool motors = std::all_of(clip.keys.begin(), clip.keys.end(), [](const JointKeys& k) {
    return k.motors.size() == k.size() && k.rigid.size() == k.size();
  });
  if (motors) {
    const Motor one = Motor::identity();
    const RigidMotor one_rigid = rigid_blades(one);
    iv.rigid0.resize(n_iv * ClipIntervals::kRigid * w);
    iv.rigid1.resize(n_iv * ClipIntervals::kRigid * w);
    iv.motor0.resize(n_iv * ClipIntervals::kMotor * w);
    iv.motor_delta.assign(n_iv * ClipIntervals::kMotor * w, 0.0f);
    for (std::size_t u = 0; u < n_iv; ++u)
      for (std::size_t j = 0; j < w; ++j) {  // padding lanes: the identity
        for (std::size_t c = 0; c < ClipIntervals::kRigid; ++c)
          iv.rigid0[(u * ClipIntervals::kRigid + c) * w + j] = iv.rigid1[(u * ClipIntervals::kRigid + c) * w + j] =
              one_rigid[c];
        for (std::size_t c = 0; c < ClipIntervals::kMotor; ++c) iv.motor0[(u * ClipIntervals::kMotor + c) * w + j] = one.c[c];
      }
  }
  for (std::size_t j = 0; j < iv.joints; ++j) {
    const JointKeys& k = clip.keys[j];
    for (std::size_t u = 0; u < n_iv; ++u) {
      const float t = iv.times[u];
      // The joint's key at or before the interval's start (its first key when it starts later).
      const auto it = std::upper_bound(k.times.begin(), k.times.end(), t);
      const std::size_t i = it == k.times.begin() ? 0 : static_cast<std::size_t>(it - k.times.begin()) - 1;
      const bool moving = t >= k.times[i] && i + 1 < k.size();
      const std::size_t i1 = moving ? i + 1 : i;
      const std::size_t s = u * w + j;
      iv.key[s] = static_cast<std::uint32_t>(i);
      iv.t0[s] = k.times[i];
      iv.inv_span[s] = moving ? 1.0f / (k.times[i + 1] - k.times[i]) : 0.0f;
      iv.scale0[s] = k.transforms[i].scale;
      iv.scale1[s] = k.transforms[i1].scale;
      if (!motors) continue;
      for (std::size_t c = 0; c < ClipIntervals::kRigid; ++c) {
        iv.rigid0[(u * ClipIntervals::kRigid + c) * w + j] = k.rigid[i][c];
        iv.rigid1[(u * ClipIntervals::kRigid + c) * w + j] = k.rigid[i1][c];
      }
      // nlerp's antipodal sign fix depends on the pair only, so it is applied here once.
      const float sign = motor_rotor_dot(k.motors[i], k.motors[i1]) < 0.0f ? -1.0f : 1.0f;
      for (std::size_t c = 0; c < ClipIntervals::kMotor; ++c) {
        iv.motor0[(u * ClipIntervals::kMotor + c) * w + j] = k.motors[i].c[c];
        iv.motor_delta[(u * ClipIntervals::kMotor + c) * w + j] = sign * k.motors[i1].c[c] - k.motors[i].c[c];
      }
    }
  }
}

}  // namespace cga
