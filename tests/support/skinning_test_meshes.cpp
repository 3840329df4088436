// The two-bone twist cylinder and the random meshes and poses of skinning_test_meshes.hpp.
#include "cga/testing/skinning_test_meshes.hpp"
#include "cga/testing/seeded_random.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning_palettes.hpp"

namespace cga {

TwistCylinder make_twist_cylinder(const TwistCylinderSpec& spec) {
  if (!(spec.radius > 0.0f) || !(spec.length > 0.0f) || spec.segments < 3 || spec.rings < 3 ||
      !(spec.blend_width > 0.0f) || spec.blend_width > spec.length)
    throw std::invalid_argument(fmt::format(
        "make_twist_cylinder: bad spec (radius {}, length {}, segments {}, rings {}, blend_width {})", spec.radius,
        spec.length, spec.segments, spec.rings, spec.blend_width));
  TwistCylinder cyl;
  cyl.spec = spec;
  cyl.spec.rings = spec.rings | 1;  // odd: the middle ring exists
  const int rings = cyl.spec.rings;
  const float half = 0.5f * spec.length;

  cyl.skeleton.names = {"root", "twist"};
  cyl.skeleton.parents = {-1, 0};
  cyl.skeleton.rest_local = {Transform{}, Transform{glm::vec3(0.0f, 0.0f, half)}};

  SkinnedMesh& m = cyl.mesh;
  m.name = "twist_cylinder";
  m.joint_remap = {0, 1};
  m.inverse_bind = {Transform{}, Transform{glm::vec3(0.0f, 0.0f, -half)}};
  m.inverse_bind_matrix = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.0f, -half))};

  const float ramp_start = half - 0.5f * spec.blend_width;
  for (int r = 0; r < rings; ++r) {
    const float z = spec.length * static_cast<float>(r) / static_cast<float>(rings - 1);
    // The middle ring gets exactly 0.5 whatever the rounding of z.
    const float w1 = r == rings / 2 ? 0.5f : std::clamp((z - ramp_start) / spec.blend_width, 0.0f, 1.0f);
    for (int s = 0; s < spec.segments; ++s) {
      const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(s) / static_cast<float>(spec.segments);
      const auto index = static_cast<std::uint32_t>(m.px.size());
      m.px.push_back(spec.radius * std::cos(phi));
      m.py.push_back(spec.radius * std::sin(phi));
      m.pz.push_back(z);
      m.nx.push_back(std::cos(phi));
      m.ny.push_back(std::sin(phi));
      m.nz.push_back(0.0f);
      m.joints.push_back({0, 1, 0, 0});
      m.weights.push_back({1.0f - w1, w1, 0.0f, 0.0f});
      if (r == rings / 2) cyl.middle_ring.push_back(index);
      if (w1 == 0.0f) cyl.bone0_only.push_back(index);
      if (w1 == 1.0f) cyl.bone1_only.push_back(index);
    }
  }
  const auto at = [&](int r, int s) {
    return static_cast<std::uint32_t>(r * spec.segments + (s % spec.segments));
  };
  // Each quad (r, s) (r, s+1) (r+1, s+1) (r+1, s) is split along the diagonal (r, s+1)-(r+1, s): a positive
  // twist turns ring r+1 toward +phi relative to ring r, which brings those two corners together; the other
  // diagonal would be stretched by the twist into a chord that cuts into the cylinder.
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < spec.segments; ++s) {
      m.indices.insert(m.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s)});
      m.indices.insert(m.indices.end(), {at(r, s + 1), at(r + 1, s + 1), at(r + 1, s)});
    }
  return cyl;
}

std::vector<Transform> twist_cylinder_skinning_transforms(const TwistCylinderSpec& spec, float angle, float scale) {
  // p' = c + s R (p - c) about the joint c = (0, 0, length / 2); R about z keeps c fixed, so t = (1 - s) c.
  const glm::vec3 c(0.0f, 0.0f, 0.5f * spec.length);
  Transform twist;
  twist.rotation = glm::angleAxis(angle, glm::vec3(0.0f, 0.0f, 1.0f));
  twist.scale = scale;
  twist.translation = (1.0f - scale) * c;
  return {Transform{}, twist};
}

namespace {

using Random = testing::SeededRandom;

}  // namespace

SkinnedMesh make_random_skinned_mesh(std::size_t vertex_count, int joint_count, std::uint32_t seed, float extent) {
  if (joint_count < 4 || joint_count > 65536)
    throw std::invalid_argument(
        fmt::format("make_random_skinned_mesh: joint_count {} outside [4, 65536]", joint_count));
  Random rng(seed);
  SkinnedMesh m;
  m.name = fmt::format("random_{}_{}", vertex_count, seed);
  for (std::size_t i = 0; i < vertex_count; ++i) {
    m.px.push_back(rng.uniform(-extent, extent));
    m.py.push_back(rng.uniform(-extent, extent));
    m.pz.push_back(rng.uniform(-extent, extent));
    glm::vec3 n(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    n = glm::length(n) > 1e-3f ? glm::normalize(n) : glm::vec3(0, 0, 1);
    m.nx.push_back(n.x);
    m.ny.push_back(n.y);
    m.nz.push_back(n.z);
    const int used = rng.below(4) == 0 ? 1 + static_cast<int>(rng.below(3)) : 4;
    std::array<std::uint16_t, 4> j{0, 0, 0, 0};
    std::array<float, 4> w{0, 0, 0, 0};
    float sum = 0.0f;
    for (int k = 0; k < used; ++k) {
      bool fresh = false;
      while (!fresh) {  // distinct joints, as exporters give
        j[k] = static_cast<std::uint16_t>(rng.below(static_cast<std::uint32_t>(joint_count)));
        fresh = std::find(j.begin(), j.begin() + k, j[k]) == j.begin() + k;
      }
      w[k] = rng.uniform(0.05f, 1.0f);
      sum += w[k];
    }
    for (int k = 0; k < used; ++k) w[k] /= sum;
    m.joints.push_back(j);
    m.weights.push_back(w);
  }
  return m;
}

std::vector<Transform> make_random_transforms(int count, std::uint32_t seed, float max_translation,
                                              float max_log_scale) {
  Random rng(seed);
  std::vector<Transform> out;
  for (int k = 0; k < count; ++k) {
    Transform x;
    // Shoemake's uniform unit quaternion.
    const float u1 = rng.uniform(0, 1), u2 = rng.uniform(0, 2 * std::numbers::pi_v<float>),
                u3 = rng.uniform(0, 2 * std::numbers::pi_v<float>);
    const float a = std::sqrt(1 - u1), b = std::sqrt(u1);
    x.rotation = glm::normalize(glm::quat(a * std::sin(u2), a * std::cos(u2), b * std::sin(u3), b * std::cos(u3)));
    x.translation = glm::vec3(rng.uniform(-max_translation, max_translation),
                              rng.uniform(-max_translation, max_translation),
                              rng.uniform(-max_translation, max_translation));
    x.scale = max_log_scale > 0 ? std::exp(rng.uniform(-max_log_scale, max_log_scale)) : 1.0f;
    out.push_back(x);
  }
  return out;
}

RandomPalettes make_random_palettes(int bones, std::size_t count, std::uint32_t seed) {
  RandomPalettes out;
  out.matrices.resize(count), out.dual_quats.resize(count), out.motors.resize(count);
  for (std::size_t p = 0; p < count; ++p)
    for (const Transform& x : make_random_transforms(bones, seed + static_cast<std::uint32_t>(p), 1.0f)) {
      out.matrices[p].push_back(to_skinning_matrix(x));
      out.dual_quats[p].push_back(to_dual_quat(x));
      out.motors[p].push_back(motor_from_transform(x));
    }
  return out;
}

std::vector<EngineVertex> make_engine_vertices(const SkinnedMesh& mesh) {
  if (!mesh.has_normals()) throw std::invalid_argument("make_engine_vertices: the mesh has no normals");
  std::vector<EngineVertex> v(mesh.vertex_count());
  for (std::size_t i = 0; i < v.size(); ++i)
    v[i] = {{mesh.px[i], mesh.py[i], mesh.pz[i]}, {mesh.nx[i], mesh.ny[i], mesh.nz[i]}, mesh.weights[i],
            mesh.joints[i]};
  return v;
}

SkinningJob make_engine_vertex_job(SkinningMethod method, std::span<const EngineVertex> in, std::span<float> out,
                                   bool normals) {
  const std::size_t n = in.size();
  if (n == 0 || out.size() < 6 * n) throw std::invalid_argument("make_engine_vertex_job: empty input or short output");
  constexpr std::size_t kFloats = sizeof(EngineVertex) / sizeof(float);  // 12
  const std::span<const float> f(in.front().p, kFloats * n);
  SkinningJob job;
  job.method = method;
  job.in_px = f, job.in_py = f.subspan(1), job.in_pz = f.subspan(2);
  job.out_px = out, job.out_py = out.subspan(1), job.out_pz = out.subspan(2);
  if (normals) {
    job.in_nx = f.subspan(3), job.in_ny = f.subspan(4), job.in_nz = f.subspan(5);
    job.out_nx = out.subspan(3), job.out_ny = out.subspan(4), job.out_nz = out.subspan(5);
  }
  job.in_positions_stride = job.in_normals_stride = kFloats;
  job.out_positions_stride = job.out_normals_stride = 6;
  job.weights_stride = sizeof(EngineVertex) / sizeof(std::array<float, 4>);   // 3
  job.joints_stride = sizeof(EngineVertex) / sizeof(std::array<std::uint16_t, 4>);  // 6
  job.weights = {&in.front().w, (n - 1) * job.weights_stride + 1};
  job.joints = {&in.front().j, (n - 1) * job.joints_stride + 1};
  return job;
}

}  // namespace cga
