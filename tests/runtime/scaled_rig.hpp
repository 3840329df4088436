// Rigs with joint scales 100 and 0.01 (characters exported in centimetres) and a double-precision reference
// for every skinning method, shared by tests/runtime/test_scaled_rig.cpp (CPU) and tests/gpu (GL paths).
//
// make_centimetre_rig(): 8 joints in the layout an FBX export from Blender gives: the armature node scales by
// 100 (metres to centimetres) and is turned -90 degrees about x, its child "hips" scales by 0.01 back and
// holds translations in metres, and the bones below it are rigid with translations in centimetres. A
// 1200-vertex mesh around the bones, each vertex with 2 to 4 influences on neighbouring joints (some on the
// armature itself). As in huesitos.fbx, the mesh node scales by 100 too: the mesh is stored in metres and each offset
// matrix is the inverse rest model matrix of its joint times that scale, so every palette entry maps metres
// to centimetres (scale 100). One clip of 5 keys that turns and moves every joint and keeps the scales.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>
#include <motor_from_trs.hpp>
#include <transform_point_staged.hpp>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/character.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning.hpp"

namespace cga::test {

inline glm::dmat4 dmat_of(const Transform& x) {
  glm::dmat4 m = glm::mat4_cast(glm::dquat(x.rotation)) * double(x.scale);
  m[3] = glm::dvec4(glm::dvec3(x.translation), 1.0);
  return m;
}

inline Character make_centimetre_rig() {
  Character ch;
  ch.path = "synthetic centimetre rig";
  Skeleton& sk = ch.skeleton;
  auto q = [](float deg, glm::vec3 axis) { return glm::angleAxis(glm::radians(deg), glm::normalize(axis)); };
  struct J {
    const char* name;
    int parent;
    Transform rest;
  };
  const J joints[] = {
      {"Armature", -1, {{0.0f, 0.0f, 0.0f}, q(-90.0f, {1, 0, 0}), 100.0f}},
      {"Hips", 0, {{0.0f, 0.021f, 0.953f}, q(90.0f, {1, 0, 0}), 0.01f}},
      {"Spine", 1, {{0.0f, 11.7f, -1.3f}, q(4.0f, {1, 0, 0}), 1.0f}},
      {"Chest", 2, {{0.0f, 14.9f, 0.4f}, q(-6.0f, {1, 0.2f, 0}), 1.0f}},
      {"Head", 3, {{0.0f, 24.3f, 2.1f}, q(8.0f, {1, 0, 0}), 1.0f}},
      {"UpperArm.L", 3, {{17.2f, 19.8f, -0.7f}, q(-80.0f, {0, 0, 1}), 1.0f}},
      {"Forearm.L", 5, {{0.0f, 27.6f, 0.0f}, q(10.0f, {1, 0, 0}), 1.0f}},
      {"Thigh.R", 1, {{-9.6f, -4.2f, 0.8f}, q(150.0f, {0, 0.05f, 1}), 1.0f}},
  };
  for (const J& j : joints) {
    sk.names.push_back(j.name);
    sk.parents.push_back(j.parent);
    sk.rest_local.push_back(j.rest);
  }
  const int n = sk.joint_count();
  std::vector<glm::dmat4> rest(n);
  for (int j = 0; j < n; ++j)
    rest[j] = sk.parents[j] < 0 ? dmat_of(sk.rest_local[j]) : rest[sk.parents[j]] * dmat_of(sk.rest_local[j]);

  SkinnedMesh mesh;
  mesh.name = "body";
  for (int j = 0; j < n; ++j) {
    mesh.joint_remap.push_back(j);
    const glm::dmat4 inv = glm::inverse(rest[j]) * glm::scale(glm::dmat4(1.0), glm::dvec3(100.0));
    mesh.inverse_bind_matrix.push_back(glm::mat4(inv));
    Transform ib;
    const double s = std::cbrt(glm::determinant(glm::dmat3(inv)));
    ib.scale = float(s);
    ib.rotation = glm::quat(glm::normalize(glm::quat_cast(glm::dmat3(inv) / s)));
    ib.translation = glm::vec3(inv[3]);
    mesh.inverse_bind.push_back(ib);
  }
  // Vertices around each joint's rest position (mesh space, metres), bound to it and its neighbours.
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  const int per_joint = 150;
  for (int j = 0; j < n; ++j) {
    const glm::dvec3 at = glm::dvec3(rest[j][3]) / 100.0;
    for (int v = 0; v < per_joint; ++v) {
      mesh.px.push_back(float(at.x) + 0.12f * u(rng));
      mesh.py.push_back(float(at.y) + 0.12f * u(rng));
      mesh.pz.push_back(float(at.z) + 0.12f * u(rng));
      // The joint, its parent, grandparent and a child or sibling (the armature's neighbours: hips, spine).
      const int p = sk.parents[j] < 0 ? 1 : sk.parents[j];
      const int pp = sk.parents[p] < 0 ? 2 : sk.parents[p];
      const int other = j + 1 < n ? j + 1 : 3;
      std::array<std::uint16_t, 4> js{std::uint16_t(j), std::uint16_t(p), std::uint16_t(pp), std::uint16_t(other)};
      const int count = 2 + v % 3;
      std::array<float, 4> w{};
      float sum = 0.0f;
      for (int k = 0; k < count; ++k) sum += (w[k] = 0.2f + 0.8f * std::abs(u(rng)));
      for (int k = 0; k < 4; ++k) w[k] = k < count ? w[k] / sum : 0.0f;
      if (count < 4) js[3] = 0;
      if (count < 3) js[2] = 0;
      mesh.joints.push_back(js);
      mesh.weights.push_back(w);
    }
  }
  ch.meshes.push_back(std::move(mesh));

  Clip clip;
  clip.name = "sway";
  clip.duration = 2.0f;
  clip.ticks_per_second = 25.0f;
  clip.tracks.resize(n);
  for (int j = 0; j < n; ++j) {
    const Transform& r = sk.rest_local[j];
    JointTrack& t = clip.tracks[j];
    for (int k = 0; k < 5; ++k) {
      const float time = 0.5f * float(k);
      const float a = float(k) - 2.0f;
      glm::quat rot = r.rotation * q(11.0f * a + 3.0f * float(j), {0.3f * float(j % 3), 1.0f, 0.5f});
      if (!t.rotations.empty() && glm::dot(t.rotations.back().value, rot) < 0.0f) rot = -rot;
      t.rotations.push_back({time, rot, rotor_from_quat(rot)});
      // Metres below the armature and on the hips, centimetres below them.
      const float step = j <= 1 ? 0.013f : 0.9f;
      t.translations.push_back({time, r.translation + step * glm::vec3(a, 0.5f * a * a, -0.3f * a)});
    }
    t.scales.push_back({0.0f, r.scale});
  }
  build_joint_keys(clip);
  ch.clips.push_back(std::move(clip));
  return ch;
}

// The double-precision reference: the clip's local transforms at `time` (as the glm-matrix sampler gives
// them; at key times these are the keys), composed in double into each palette entry's similarity
// (scale, rotation, translation); then each method in double.
struct DoubleSimilarity {
  double scale;
  glm::dquat rotation;
  glm::dvec3 translation;
  glm::dvec3 operator()(const glm::dvec3& p) const { return scale * (rotation * p) + translation; }
};

inline std::vector<DoubleSimilarity> double_palette(const Character& ch, const SkinnedMesh& mesh, const Clip& clip,
                                                    float time) {
  const Skeleton& sk = ch.skeleton;
  const std::size_t n = static_cast<std::size_t>(sk.joint_count());
  baseline::PoseBuffer local(n);
  if (!baseline::TransformSamplingJob{&clip, time, local.transforms}.Run()) return {};
  std::vector<glm::dmat4> model(n);
  for (std::size_t j = 0; j < n; ++j)
    model[j] = sk.parents[j] < 0 ? dmat_of(local.transforms[j]) : model[sk.parents[j]] * dmat_of(local.transforms[j]);
  std::vector<DoubleSimilarity> out;
  for (std::size_t k = 0; k < mesh.joint_remap.size(); ++k) {
    const glm::dmat4 m = model[mesh.joint_remap[k]] * dmat_of(mesh.inverse_bind[k]);
    const glm::dmat3 l(m);
    const double sc = std::cbrt(glm::determinant(l));
    out.push_back({sc, glm::normalize(glm::quat_cast(l / sc)), glm::dvec3(m[3])});
  }
  return out;
}

// Vertex v skinned in double by `method`: lbs / cga-points blend the moved points; cga-motors blends the
// motors (sign fix on the rotor parts) and moves the point once, dividing by its weight; dqs blends the
// rigid parts as dual quaternions (it has no scale: it moves by the rotation and translation of each
// similarity and drops the scale); cga-log exponentiates the blend of the similarities' logarithms;
// cga-tlerp takes the linear part of cga-motors' blend and the weighted mean of the translations.
inline glm::dvec3 double_skin(SkinningMethod method, const std::vector<DoubleSimilarity>& pal,
                              const SkinnedMesh& mesh, std::size_t v) {
  const glm::dvec3 p(mesh.px[v], mesh.py[v], mesh.pz[v]);
  const auto& js = mesh.joints[v];
  const auto& ws = mesh.weights[v];
  switch (method) {
    case SkinningMethod::lbs:
    case SkinningMethod::cga_points: {
      glm::dvec3 out(0.0);
      for (int k = 0; k < 4; ++k) out += double(ws[k]) * pal[js[k]](p);
      return out;
    }
    case SkinningMethod::cga_motors:
    case SkinningMethod::cga_tlerp: {
      auto motor = [&](int k, double m[12]) {
        const DoubleSimilarity& x = pal[js[k]];
        kernels::motor_from_trs(x.translation.x, x.translation.y, x.translation.z, x.rotation.w, -x.rotation.z,
                                x.rotation.y, -x.rotation.x, x.scale, m);
      };
      double m0[12], sum[12] = {};
      motor(0, m0);
      for (int k = 0; k < 4; ++k) {
        double m[12];
        motor(k, m);
        const double dot = (m0[0] + m0[7]) * (m[0] + m[7]) + (m0[1] + m0[9]) * (m[1] + m[9]) +
                           (m0[2] + m0[10]) * (m[2] + m[10]) + (m0[4] + m0[11]) * (m[4] + m[11]);
        const double w = dot < 0.0 ? -double(ws[k]) : double(ws[k]);
        for (int c = 0; c < 12; ++c) sum[c] += w * m[c];
      }
      // The staged point transform (prepare on the blended motor, then the per-point body) over its weight;
      // in double the blade form's cancellation is harmless.
      double prepared[13], P[4];
      kernels::transform_point_staged_prepare(sum, prepared);
      kernels::transform_point_staged(prepared, p.x, p.y, p.z, P);
      if (method == SkinningMethod::cga_motors) return glm::dvec3(P[0], P[1], P[2]) / P[3];
      // cga-tlerp: the blended motor's linear part (its move of p less its move of the origin) plus the mean
      // of the bones' translations (a similarity moves the origin by its translation).
      double O[4];
      kernels::transform_point_staged(prepared, 0.0, 0.0, 0.0, O);
      glm::dvec3 t(0.0);
      for (int k = 0; k < 4; ++k) t += double(ws[k]) * pal[js[k]].translation;
      return glm::dvec3(P[0] / P[3] - O[0] / O[3], P[1] / P[3] - O[1] / O[3], P[2] / P[3] - O[2] / O[3]) + t;
    }
    case SkinningMethod::dqs: {
      const glm::dquat r0 = pal[js[0]].rotation;
      glm::dquat real(0.0, 0.0, 0.0, 0.0), dual(0.0, 0.0, 0.0, 0.0);
      for (int k = 0; k < 4; ++k) {
        const DoubleSimilarity& x = pal[js[k]];
        const double w = glm::dot(r0, x.rotation) < 0.0 ? -double(ws[k]) : double(ws[k]);
        const glm::dquat d = glm::dquat(0.0, x.translation.x, x.translation.y, x.translation.z) * x.rotation * 0.5;
        real = real + w * x.rotation;
        dual = dual + w * d;
      }
      const double len = glm::length(real);
      real = real / len, dual = dual / len;
      const glm::dquat t = dual * glm::conjugate(real) * 2.0;
      return real * p + glm::dvec3(t.x, t.y, t.z);
    }
    case SkinningMethod::cga_log: {
      // The twists (w, v) of the rigid parts (w the rotation vector, t = V(w) v) and the log scales, blended
      // with the skin weights and exponentiated: Rodrigues for the rotation, V(w) for the translation. Each
      // influence takes the branch of its rotation (angle theta or theta - 2 pi) nearer the first's.
      struct Twist {
        glm::dvec3 w, v;
      };
      auto twist = [](const DoubleSimilarity& x, bool other) {
        glm::dquat q = x.rotation;
        if (q.w < 0.0) q = -q;
        const glm::dvec3 axis_sin(q.x, q.y, q.z);
        const double s = glm::length(axis_sin);
        double theta = 2.0 * std::atan2(s, q.w);
        if (other && s > 1e-3) theta -= 2.0 * M_PI;
        const glm::dvec3 w = s > 0.0 ? axis_sin * (theta / s) : glm::dvec3(0.0);
        // V^-1 = I - [w]x / 2 + (1 - (theta/2) cot(theta/2)) / theta^2 [w]x^2, cot(theta/2) = q.w / s
        const double c2 = std::abs(theta) > 1e-8 ? (1.0 - 0.5 * theta * q.w / s) / (theta * theta) : 1.0 / 12.0;
        const glm::dvec3 wt = glm::cross(w, x.translation);
        return Twist{w, x.translation - 0.5 * wt + c2 * glm::cross(w, wt)};
      };
      const Twist first = twist(pal[js[0]], false);
      glm::dvec3 w_sum(0.0), v_sum(0.0);
      double log_scale = 0.0;
      for (int k = 0; k < 4; ++k) {
        const DoubleSimilarity& x = pal[js[k]];
        Twist t = twist(x, false);
        if (k > 0) {
          const Twist o = twist(x, true);
          if (glm::length(o.w - first.w) < glm::length(t.w - first.w)) t = o;
        }
        w_sum += double(ws[k]) * t.w;
        v_sum += double(ws[k]) * t.v;
        log_scale += double(ws[k]) * std::log(x.scale);
      }
      const double theta = glm::length(w_sum);
      const glm::dvec3 wv = glm::cross(w_sum, v_sum);
      const double a = theta > 1e-8 ? (1.0 - std::cos(theta)) / (theta * theta) : 0.5;
      const double b = theta > 1e-8 ? (theta - std::sin(theta)) / (theta * theta * theta) : 1.0 / 6.0;
      const glm::dvec3 t = v_sum + a * wv + b * glm::cross(w_sum, wv);
      const glm::dquat r = theta > 1e-12 ? glm::angleAxis(theta, w_sum / theta) : glm::dquat(1.0, 0.0, 0.0, 0.0);
      return r * (std::exp(log_scale) * p) + t;
    }
  }
  return p;
}

// One mesh's palettes at `time` through the runtime's jobs in `mode` (sampling, local-to-model, palette): the
// arrays of the mode's representation are filled.
struct Palettes {
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
  MotorPalette motors;
};
inline Palettes job_palettes(const Character& ch, std::size_t mesh_index, const Clip& clip, float time,
                             baseline::PoseMode mode) {
  const std::size_t n = static_cast<std::size_t>(ch.skeleton.joint_count());
  const SkinnedMesh& mesh = ch.meshes[mesh_index];
  baseline::PoseBuffer local(n), model(n);
  baseline::PaletteBuffer pal(mesh.joint_remap.size());
  if (!baseline::sample(mode, clip, time, local) || !baseline::local_to_model(mode, ch.skeleton, local, model) ||
      !baseline::palette(mode, mesh.joint_remap, baseline::make_inverse_bind(mesh), model, pal))
    return {};
  Palettes out;
  out.matrices = std::move(pal.matrices);
  out.dual_quats = std::move(pal.dual_quats);
  out.motors = std::move(pal.motors);
  return out;
}

// The pose mode each method's pipeline uses here: lbs GLM matrices, dqs GLM dual quaternions, the cga methods
// the motor modes given.
inline baseline::PoseMode pipeline_mode(SkinningMethod method, Interpolation motor_mode) {
  switch (method) {
    case SkinningMethod::lbs: return baseline::PoseMode::glm_matrix;
    case SkinningMethod::dqs: return baseline::PoseMode::glm_dualquat;
    default: return baseline::to_pose_mode(motor_mode);
  }
}

}  // namespace cga::test
