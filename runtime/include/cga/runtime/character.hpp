// A skinned, animated character in memory: skeleton (parents first), skinned meshes, clips and the warnings
// its importer gave. cga::io's load_character() (cga/io/loader.hpp) fills one from a file; the runtime
// itself reads no files. Also the rest pose as matrices and the character's size.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "cga/runtime/animation.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

struct Character {
  std::string path;
  Skeleton skeleton;
  std::vector<SkinnedMesh> meshes;
  std::vector<Clip> clips;
  std::vector<std::string> warnings;

  const Clip* find_clip(const std::string& name) const {
    for (const Clip& c : clips)
      if (c.name == name) return &c;
    return nullptr;
  }
};

// Rest model-space transforms of every joint (TRS composed down the hierarchy).
std::vector<glm::mat4> rest_model_matrices(const Skeleton& skeleton);
glm::mat4 to_mat4(const Transform& x);

// Length of the diagonal of the box around the rest joints and rest mesh vertices: the "character size"
// tolerances are relative to.
float character_size(const Character& character);

}  // namespace cga
