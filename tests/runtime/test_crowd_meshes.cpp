// The crowd benchmarks' meshes: joint_coherence() counts what it says on hand-made meshes; the coherent
// synthetic mesh shares bones between neighbouring vertices within the range the real characters'
// meshes (BCN_Epileptic, Testwuson) show, the random mesh does not, and both are deterministic and valid.
#include <catch2/catch.hpp>

#include <string>

#include "cga/io/loader.hpp"
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

SkinnedMesh with_joints(std::initializer_list<std::array<std::uint16_t, 4>> joints) {
  SkinnedMesh m;
  for (const auto& j : joints) {
    m.px.push_back(0), m.py.push_back(0), m.pz.push_back(0);
    m.joints.push_back(j);
    m.weights.push_back({1, 0, 0, 0});
  }
  return m;
}

}  // namespace

TEST_CASE("joint_coherence counts distinct joints per group and per slot") {
  const SkinnedMesh m = with_joints({{1, 2, 0, 0}, {1, 3, 0, 0}, {4, 2, 0, 0}, {4, 2, 0, 0}});
  const JointCoherence c = joint_coherence(m, 2);
  CHECK(c.groups == 2);
  // Group 0: {0, 1, 2, 3} = 4; group 1: {0, 2, 4} = 3. Slots: group 0 1+2+1+1, group 1 1+1+1+1.
  CHECK(c.distinct_per_group == Approx(3.5));
  CHECK(c.max_per_group == 4);
  CHECK(c.distinct_per_slot == Approx((5.0 + 4.0) / 8.0));
  CHECK_THROWS_AS(joint_coherence(m, 0), std::invalid_argument);
}

TEST_CASE("the coherent crowd mesh shares bones like the real characters, the random one does not") {
  double lo = 1e9, hi = 0.0, slot_lo = 1e9, slot_hi = 0.0;
  for (const char* file : {"X/BCN_Epileptic.X", "X/Testwuson.X"})
    for (const SkinnedMesh& m : load_character(model(file)).meshes) {
      const JointCoherence c = joint_coherence(m);
      lo = std::min(lo, c.distinct_per_group), hi = std::max(hi, c.distinct_per_group);
      slot_lo = std::min(slot_lo, c.distinct_per_slot), slot_hi = std::max(slot_hi, c.distinct_per_slot);
    }
  INFO("real meshes: " << lo << ".." << hi << " per 32 vertices, " << slot_lo << ".." << slot_hi << " per slot");
  const SkinnedMesh coherent = make_coherent_skinned_mesh(16384, 64, 1234u);
  const JointCoherence c = joint_coherence(coherent);
  INFO("coherent: " << describe(c));
  CHECK(c.distinct_per_group >= 0.8 * lo);
  CHECK(c.distinct_per_group <= 1.2 * hi);
  CHECK(c.distinct_per_slot >= 0.8 * slot_lo);
  CHECK(c.distinct_per_slot <= 1.2 * slot_hi);
  const JointCoherence r = joint_coherence(make_random_skinned_mesh(16384, 64, 1234u));
  CHECK(r.distinct_per_slot > 4.0 * slot_hi);

  // Valid skin data: joints in range, weights >= 0 summing to 1, same mesh for the same seed.
  for (std::size_t v = 0; v < coherent.vertex_count(); ++v) {
    float sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      REQUIRE(coherent.joints[v][k] < 64);
      REQUIRE(coherent.weights[v][k] >= 0.0f);
      sum += coherent.weights[v][k];
    }
    REQUIRE(sum == Approx(1.0f).margin(1e-5));
    REQUIRE(std::abs(coherent.px[v]) <= 1.0f);
  }
  const SkinnedMesh again = make_coherent_skinned_mesh(16384, 64, 1234u);
  CHECK(again.joints == coherent.joints);
  CHECK(again.px == coherent.px);
  CHECK_THROWS_AS(make_coherent_skinned_mesh(10, 3, 1u), std::invalid_argument);
}
