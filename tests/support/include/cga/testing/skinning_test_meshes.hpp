// Meshes made in code for skinning tests, pictures, demos and benchmarks: the two-bone twist cylinder, the
// classic case where linear blend skinning collapses ("candy wrapper") and motor / dual-quaternion blending
// does not, and deterministic random meshes and poses.
#pragma once

#include <array>
#include <cstdint>
#include <span>
#include <vector>

#include "cga/runtime/skinning.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

struct TwistCylinderSpec {
  float radius = 1.0f;
  float length = 4.0f;       // along +z, from z = 0
  int segments = 32;         // vertices around
  // Vertex rings along z; made odd so one ring sits exactly at z = length / 2. 65 rings: at 180 degrees two
  // neighbouring rings in the blend zone turn about as far apart (11.25 degrees) as two neighbouring vertices
  // of a ring, so the twisted triangles stay small; fewer rings make them slivers whose edges cut into the
  // surface (notches in the silhouette, saw-tooth shading in the pictures).
  int rings = 65;
  float blend_width = 1.0f;  // the weight of bone 1 ramps linearly from 0 to 1 over this length around the middle
};

// A cylinder side along z skinned to two joints: joint 0 at the origin, joint 1 (child) at z = length / 2.
// Weights: joint 1's weight w1 = clamp((z - (length - blend_width) / 2) / blend_width, 0, 1), joint 0 has
// 1 - w1; the middle ring has 0.5 / 0.5. Normals are radial. The mesh palette is the skeleton (joint_remap
// 0, 1) with inverse binds at the joints' rest positions.
struct TwistCylinder {
  TwistCylinderSpec spec;
  Skeleton skeleton;
  SkinnedMesh mesh;
  std::vector<std::uint32_t> middle_ring;  // vertex indices of the ring at z = length / 2
  std::vector<std::uint32_t> bone0_only;   // vertices with weight 1 on joint 0
  std::vector<std::uint32_t> bone1_only;   // vertices with weight 1 on joint 1
};

// Throws std::invalid_argument on a spec that cannot make a cylinder (radius or length <= 0, < 3 segments,
// < 3 rings, blend_width outside (0, length]).
TwistCylinder make_twist_cylinder(const TwistCylinderSpec& spec = {});

// The mesh-space skinning transforms (palette entries 0 and 1) that twist joint 1 by `angle` radians about
// the cylinder axis and scale it uniformly by `scale` about the joint; joint 0 stays at identity.
std::vector<Transform> twist_cylinder_skinning_transforms(const TwistCylinderSpec& spec, float angle,
                                                          float scale = 1.0f);

// A deterministic random skinned mesh for tests and benchmarks: positions in [-extent, extent]^3, unit normals,
// 4 influences per vertex on distinct joints in [0, joint_count) with weights summing to 1 (about a quarter of
// the vertices use fewer than 4 slots, the rest weight 0 on joint 0). Same seed, same mesh, on every platform.
SkinnedMesh make_random_skinned_mesh(std::size_t vertex_count, int joint_count, std::uint32_t seed,
                                     float extent = 1.0f);

// Deterministic random transforms: unit rotations uniform over SO(3), translations in [-max_translation,
// max_translation]^3, scale 1 or, when max_log_scale > 0, exp(uniform(-max_log_scale, max_log_scale)).
std::vector<Transform> make_random_transforms(int count, std::uint32_t seed, float max_translation = 1.0f,
                                              float max_log_scale = 0.0f);

// `count` distinct random rigid poses of `bones` joints (make_random_transforms with seeds seed, seed + 1, ...,
// translations in [-1, 1]^3), each in every method's palette form: what the crowd benchmarks cycle over their
// instances.
struct RandomPalettes {
  std::vector<MatrixPalette> matrices;
  std::vector<DualQuatPalette> dual_quats;
  std::vector<MotorPalette> motors;
};
RandomPalettes make_random_palettes(int bones, std::size_t count, std::uint32_t seed);

// A vertex as engines store it, skin data included: position, normal, 4 weights, 4 joints in 48 bytes.
struct EngineVertex {
  float p[3], n[3];
  std::array<float, 4> w;
  std::array<std::uint16_t, 4> j;
};
static_assert(sizeof(EngineVertex) == 48);

// The mesh's vertices (normals required) in that layout.
std::vector<EngineVertex> make_engine_vertices(const SkinnedMesh& mesh);

// A job reading `in` through strides (weights and joints spans as short as the size rules allow) and
// writing x y z nx ny nz interleaved into `out` (6 floats per vertex; normals only when `normals`). The
// palette spans are left for the caller.
SkinningJob make_engine_vertex_job(SkinningMethod method, std::span<const EngineVertex> in, std::span<float> out,
                                   bool normals);

}  // namespace cga
