// Loading a skinned, animated character with Assimp: skeleton (parents first), skinned meshes (SoA, at most
// 4 influences), clips (seconds, rotation keys as rotors) and the warnings about everything that had to be
// approximated (non-uniform scales, more than 4 influences, non-similarity bind matrices).
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "cga/runtime/animation.hpp"
#include "cga/runtime/types.hpp"

namespace cga {

// Missing, unreadable or corrupt file, or a file without a skeleton. The message names the path and
// carries Assimp's own message.
struct LoadError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct LoadOptions {
  bool meshes = true;
  bool animations = true;
  // Each kind of warning names its first occurrences one by one, then counts the rest in one line.
  int max_warnings_per_kind = 20;
};

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

// Joints: every node that is a mesh bone, or every animated node when no mesh has bones (BVH), plus all
// their ancestors; the scene root only when its transform is not the identity. Parents come first.
// Model space is the scene's root space; skinned positions land there.
Character load_character(const std::string& path, const LoadOptions& options = {});

// Rest model-space transforms of every joint (TRS composed down the hierarchy).
std::vector<glm::mat4> rest_model_matrices(const Skeleton& skeleton);
glm::mat4 to_mat4(const Transform& x);

// Length of the diagonal of the box around the rest joints and rest mesh vertices: the "character size"
// tolerances are relative to.
float character_size(const Character& character);

}  // namespace cga
