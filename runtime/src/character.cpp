// The rest pose as matrices and the size of a character (see character.hpp).
#include "cga/runtime/character.hpp"

#include <limits>

namespace cga {

glm::mat4 to_mat4(const Transform& x) {
  glm::mat4 m = glm::mat4_cast(x.rotation) * x.scale;
  m[3] = glm::vec4(x.translation, 1.0f);
  return m;
}

std::vector<glm::mat4> rest_model_matrices(const Skeleton& skeleton) {
  std::vector<glm::mat4> model(skeleton.joint_count());
  for (int j = 0; j < skeleton.joint_count(); ++j) {
    const glm::mat4 local = to_mat4(skeleton.rest_local[j]);
    model[j] = skeleton.parents[j] < 0 ? local : model[skeleton.parents[j]] * local;
  }
  return model;
}

float character_size(const Character& character) {
  glm::vec3 lo(std::numeric_limits<float>::max()), hi(-std::numeric_limits<float>::max());
  for (const glm::mat4& m : rest_model_matrices(character.skeleton)) {
    lo = glm::min(lo, glm::vec3(m[3]));
    hi = glm::max(hi, glm::vec3(m[3]));
  }
  for (const SkinnedMesh& mesh : character.meshes)
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::vec3 p(mesh.px[v], mesh.py[v], mesh.pz[v]);
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
  return character.skeleton.joint_count() ? glm::length(hi - lo) : 0.0f;
}

}  // namespace cga
