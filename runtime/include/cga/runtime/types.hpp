// The runtime's small value types, shared by every job: Motor (a CGA similarity versor), Transform (TRS with
// uniform scale), Skeleton, SkinnedMesh (structure of arrays) and the skinning palettes of each method.
// Jobs (sampling, blending, local-to-model, skinning) take non-owning spans of these, like ozz-animation's.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtx/dual_quaternion.hpp>

namespace cga {

// A motor M = T·R·D: translation, rotation, dilation (uniform scale). Exactly 12 blades of the null basis,
// stored in Gaalop's blade order (the order of every generated kernel's motor inputs/outputs):
//   c[0] 1        c[1] e1^e2      c[2]  e1^e3      c[3]  e1^einf
//   c[4] e2^e3    c[5] e2^einf    c[6]  e3^einf    c[7]  einf^e0
//   c[8] e1^e2^e3^einf            c[9]  e1^e2^einf^e0
//   c[10] e1^e3^einf^e0           c[11] e2^e3^einf^e0
// The paper packs the same 12 numbers in a GLSL mat3x4: blade k at column k/4, row k%4.
struct Motor {
  std::array<float, 12> c{1, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  static Motor identity() { return {}; }
};

namespace blade {
enum : int { s = 0, e12, e13, e1inf, e23, e2inf, e3inf, einf0, e123inf, e12inf0, e13inf0, e23inf0 };
}

// A key or local pose: translation, unit rotation, uniform scale (the similarity a motor represents).
struct Transform {
  glm::vec3 translation{0.0f};
  glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
  float scale = 1.0f;
};

// Joints in an order where every parent comes before its children (parents[i] < i; the root has -1).
struct Skeleton {
  std::vector<std::string> names;
  std::vector<int> parents;
  std::vector<Transform> rest_local;    // local transform of each joint in the rest pose
  int joint_count() const { return static_cast<int>(parents.size()); }
  int find(const std::string& name) const {
    for (int i = 0; i < joint_count(); ++i)
      if (names[i] == name) return i;
    return -1;
  }
};

// A skinned mesh as structure of arrays, up to 4 influences per vertex; weights of a vertex sum to 1 and
// unused slots have weight 0 (and joint 0). joints index the mesh's palette (see SkinnedMesh::joint_remap).
struct SkinnedMesh {
  std::string name;
  std::vector<float> px, py, pz;  // rest positions (mesh space)
  std::vector<float> nx, ny, nz;  // rest normals (may be empty)
  std::vector<std::array<std::uint16_t, 4>> joints;
  std::vector<std::array<float, 4>> weights;
  std::vector<std::uint32_t> indices;  // triangles
  // Palette entry k of this mesh is skeleton joint joint_remap[k], with inverse bind inverse_bind[k].
  std::vector<int> joint_remap;
  std::vector<glm::mat4> inverse_bind_matrix;  // Assimp's offset matrices (mesh space -> joint space)
  std::vector<Transform> inverse_bind;          // the same as TRS (uniform scale), for motors/dual quaternions
  std::size_t vertex_count() const { return px.size(); }
  bool has_normals() const { return !nx.empty(); }
};

// Skinning palettes, one entry per palette joint, in each method's representation.
using MatrixPalette = std::vector<glm::mat3x4>;   // row-major 3x4: row r = (m[r][0], m[r][1], m[r][2], m[r][3]); p' = M * (p,1)
using DualQuatPalette = std::vector<glm::dualquat>;
using MotorPalette = std::vector<Motor>;

}  // namespace cga
