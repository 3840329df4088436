// Skin data for the crowd benchmarks: how coherent a mesh's joint indices are across the vertices one GPU
// warp skins together (the statistic that decides how a warp's palette reads spread over the memory banks),
// and a deterministic synthetic mesh whose neighbouring vertices share bones the way exported characters
// (BCN_Epileptic, Testwuson) do, next to make_random_skinned_mesh's worst case of 4 random bones per vertex.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

#include "cga/runtime/skinning.hpp"

namespace cga {

// Distinct joint indices per group of `group` consecutive vertices (a warp: 32), counted over all 4 slots
// (the kernels read every slot, weight 0 or not) and per slot k (what one palette-read instruction of a warp
// touches: lane i reads joint slot k of vertex i). Means over the full groups; a mesh shorter than one group
// counts as one group.
struct JointCoherence {
  std::size_t group = 32;
  double distinct_per_group = 0.0;  // mean, all slots together
  double distinct_per_slot = 0.0;   // mean over groups and the 4 slots
  std::size_t max_per_group = 0;
  std::size_t groups = 0;
};
JointCoherence joint_coherence(const SkinnedMesh& mesh, std::size_t group = 32);
// "6.0 distinct joints per 32 consecutive vertices (max 10), 2.9 per joint slot", for benchmark headers.
std::string describe(const JointCoherence& c);

// A deterministic synthetic character-like skinned mesh: vertices come in runs along the bones of a
// branching chain skeleton of `joint_count` joints (as exporters write a limb's skin region after another),
// each vertex weighted to its run's bone, the bone's parent and, near the ends of the run, the next bone in
// the chain and one more neighbour, with smooth weights summing to 1, heaviest first (unused slots weight 0
// on joint 0, as the loader gives). Each run is a tube around the bone's segment (rings of 4 vertices,
// triangles between them: a mesh that can be drawn), positions in [-extent, extent]^3, unit normals. `run`
// is the mean number of consecutive vertices per bone region: 12 gives 6.0 distinct joints per 32 vertices
// and 2.9 per slot at 64 joints, where the meshes of BCN_Epileptic and Testwuson give 4.1-6.8 and 2.1-3.6
// (6.1 and 3.2 weighted by vertices). Same seed, same mesh, on every platform.
SkinnedMesh make_coherent_skinned_mesh(std::size_t vertex_count, int joint_count, std::uint32_t seed,
                                       float extent = 1.0f, std::size_t run = 12);

}  // namespace cga
