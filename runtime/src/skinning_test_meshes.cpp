// The two-bone twist cylinder (see skinning_test_meshes.hpp).
#include "cga/runtime/skinning_test_meshes.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <glm/gtc/matrix_transform.hpp>

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
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < spec.segments; ++s) {
      m.indices.insert(m.indices.end(), {at(r, s), at(r, s + 1), at(r + 1, s + 1)});
      m.indices.insert(m.indices.end(), {at(r, s), at(r + 1, s + 1), at(r + 1, s)});
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

}  // namespace cga
