// joint_coherence() and make_coherent_skinned_mesh() of crowd_meshes.hpp.
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/seeded_random.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <glm/glm.hpp>

namespace cga {

JointCoherence joint_coherence(const SkinnedMesh& mesh, std::size_t group) {
  if (group == 0) throw std::invalid_argument("joint_coherence: group size 0");
  JointCoherence c;
  c.group = group;
  const std::size_t n = mesh.joints.size();
  const std::size_t groups = std::max<std::size_t>(n / group, n > 0 ? 1 : 0);
  std::vector<std::uint16_t> all, slot;
  double sum_all = 0.0, sum_slot = 0.0;
  for (std::size_t g = 0; g < groups; ++g) {
    const std::size_t lo = g * group, hi = std::min(n, lo + group);
    all.clear();
    for (int k = 0; k < 4; ++k) {
      slot.clear();
      for (std::size_t v = lo; v < hi; ++v) slot.push_back(mesh.joints[v][k]);
      std::sort(slot.begin(), slot.end());
      slot.erase(std::unique(slot.begin(), slot.end()), slot.end());
      sum_slot += static_cast<double>(slot.size());
      all.insert(all.end(), slot.begin(), slot.end());
    }
    std::sort(all.begin(), all.end());
    all.erase(std::unique(all.begin(), all.end()), all.end());
    sum_all += static_cast<double>(all.size());
    c.max_per_group = std::max(c.max_per_group, all.size());
  }
  c.groups = groups;
  if (groups > 0) {
    c.distinct_per_group = sum_all / static_cast<double>(groups);
    c.distinct_per_slot = sum_slot / (4.0 * static_cast<double>(groups));
  }
  return c;
}

std::string describe(const JointCoherence& c) {
  return fmt::format("{:.1f} distinct joints per {} consecutive vertices (max {}), {:.1f} per joint slot",
                     c.distinct_per_group, c.group, c.max_per_group, c.distinct_per_slot);
}

namespace {

using Random = testing::SeededRandom;

}  // namespace

SkinnedMesh make_coherent_skinned_mesh(std::size_t vertex_count, int joint_count, std::uint32_t seed, float extent,
                                       std::size_t run) {
  if (joint_count < 4 || joint_count > 65536)
    throw std::invalid_argument(
        fmt::format("make_coherent_skinned_mesh: joint_count {} outside [4, 65536]", joint_count));
  if (run == 0) throw std::invalid_argument("make_coherent_skinned_mesh: run length 0");
  Random rng(seed);
  const auto joints = static_cast<std::size_t>(joint_count);
  // A branching chain: mostly parent = previous joint, every sixth joint starts a new limb off an earlier one.
  std::vector<std::size_t> parent(joints, 0);
  std::vector<glm::vec3> at(joints, glm::vec3(0.0f));
  for (std::size_t b = 1; b < joints; ++b) {
    parent[b] = b % 6 == 0 ? rng.below(static_cast<std::uint32_t>(b)) : b - 1;
    const glm::vec3 step(rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f), rng.uniform(-0.4f, 0.4f));
    at[b] = glm::clamp(at[parent[b]] + step * extent, glm::vec3(-0.8f * extent), glm::vec3(0.8f * extent));
  }
  std::vector<std::size_t> child(joints, 0);  // the first child, or the joint itself at a chain's end
  for (std::size_t b = 0; b < joints; ++b) child[b] = b;
  for (std::size_t b = joints; b-- > 1;) child[parent[b]] = b;

  SkinnedMesh m;
  m.name = fmt::format("coherent_{}_{}", vertex_count, seed);
  std::size_t bone = 0;
  while (m.px.size() < vertex_count) {
    // A tube around the bone: rings of kAround vertices, whole rings only, triangles between the rings.
    constexpr std::size_t kAround = 4;
    const auto rings = std::max<std::size_t>(
        2, static_cast<std::size_t>(static_cast<float>(run) * rng.uniform(0.5f, 1.5f) / kAround + 0.5f));
    const std::size_t length = rings * kAround;
    const std::size_t p = parent[bone], c = child[bone], extra = parent[p];
    const glm::vec3 a = at[p], b = at[bone];
    const float radius = 0.1f * extent;
    const auto first = static_cast<std::uint32_t>(m.px.size());
    for (std::size_t t = 0; t < length && m.px.size() < vertex_count; ++t) {
      const float u = (static_cast<float>(t / kAround) + 0.5f) / static_cast<float>(rings);
      const float phi = 2.0f * std::numbers::pi_v<float> * static_cast<float>(t % kAround) / kAround;
      const glm::vec3 axis = b - a;
      const glm::vec3 side = glm::length(glm::cross(axis, glm::vec3(0, 0, 1))) > 1e-4f
                                 ? glm::normalize(glm::cross(axis, glm::vec3(0, 0, 1)))
                                 : glm::vec3(1, 0, 0);
      const glm::vec3 up = glm::length(axis) > 1e-6f ? glm::normalize(glm::cross(side, axis)) : glm::vec3(0, 1, 0);
      const glm::vec3 n = std::cos(phi) * side + std::sin(phi) * up;
      const glm::vec3 pos = glm::clamp(glm::mix(a, b, u) + radius * n, glm::vec3(-extent), glm::vec3(extent));
      m.px.push_back(pos.x), m.py.push_back(pos.y), m.pz.push_back(pos.z);
      m.nx.push_back(n.x), m.ny.push_back(n.y), m.nz.push_back(n.z);
      // Influences: the bone, its parent near the start, its child near the end, the grandparent a little.
      std::array<std::pair<float, std::size_t>, 4> inf{{{1.0f, bone},
                                                         {std::max(0.0f, 0.6f - u), p},
                                                         {std::max(0.0f, u - 0.6f), c},
                                                         {u < 0.25f ? 0.1f : 0.0f, extra}}};
      std::array<std::uint16_t, 4> j{0, 0, 0, 0};
      std::array<float, 4> w{0, 0, 0, 0};
      int used = 0;
      float sum = 0.0f;
      // Heaviest first, as exporters list them; a joint listed twice (chain ends) merges into one slot.
      std::sort(inf.begin(), inf.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
      for (const auto& [weight, joint] : inf) {
        if (weight <= 0.0f) continue;
        const auto index = static_cast<std::uint16_t>(joint);
        int slot = 0;
        while (slot < used && j[slot] != index) ++slot;
        if (slot == used) j[used++] = index;
        w[slot] += weight;
        sum += weight;
      }
      for (int k = 0; k < used; ++k) w[k] /= sum;
      m.joints.push_back(j);
      m.weights.push_back(w);
    }
    const auto made = static_cast<std::uint32_t>(m.px.size()) - first;
    for (std::uint32_t r = 0; (r + 2) * kAround <= made; ++r)
      for (std::uint32_t k = 0; k < kAround; ++k) {
        const auto at_ = [&](std::uint32_t ring, std::uint32_t s) {
          return first + ring * static_cast<std::uint32_t>(kAround) + s % static_cast<std::uint32_t>(kAround);
        };
        m.indices.insert(m.indices.end(), {at_(r, k), at_(r, k + 1), at_(r + 1, k + 1)});
        m.indices.insert(m.indices.end(), {at_(r, k), at_(r + 1, k + 1), at_(r + 1, k)});
      }
    bone = (bone + 1) % joints;
  }
  return m;
}

}  // namespace cga
