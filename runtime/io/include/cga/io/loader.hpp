// cga::io: importing a skinned, animated character with Assimp, apart from the runtime (which reads no files
// and does not link Assimp). Fills a cga::Character (cga/runtime/character.hpp): skeleton (parents first),
// skinned meshes (SoA, at most 4 influences), clips (seconds, rotation keys as rotors) and the warnings about
// everything that had to be approximated (non-uniform scales, more than 4 influences, non-similarity bind
// matrices).
#pragma once

#include <stdexcept>
#include <string>

#include "cga/runtime/character.hpp"

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

// Joints: every node that is a mesh bone, or every animated node when no mesh has bones (BVH), plus all
// their ancestors; the scene root only when its transform is not the identity. Parents come first.
// Model space is the scene's root space; skinned positions land there.
Character load_character(const std::string& path, const LoadOptions& options = {});

}  // namespace cga
