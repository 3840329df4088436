// cga::io: importing a skinned, animated character with Assimp, apart from the runtime (which reads no files
// and does not link Assimp). Fills a cga::Character (cga/runtime/character.hpp): skeleton (parents first),
// skinned meshes (SoA, at most 4 influences), clips (seconds, rotation keys as rotors) and the warnings about
// everything that had to be approximated (non-uniform scales, more than 4 influences, non-similarity bind
// matrices).
//
// The import runs in a child process (POSIX fork). A model file is untrusted input to a large parser, and
// Assimp's importers crash on some malformed files (Assimp 5.2's .X importer dies by SIGSEGV on a face index
// past the mesh); as browsers run their decoders apart from the page, the loader runs Assimp apart from the
// caller. The child converts the scene to a Character, checks it (indices in range, numbers finite) and
// sends it back over a pipe; the caller only ever sees a Character or a LoadError. A child that dies by a
// signal, fails, or runs past the time limit (60 s; CGA_IMPORT_TIME_LIMIT=SECONDS overrides it) is a
// LoadError naming the file: "FILE: the model importer crashed (SIGSEGV) reading it; the file is malformed".
//
// Numbers that are not finite never reach the Character; each case is a warning naming mesh and vertex:
// a vertex whose position is nan or infinite is dropped with its triangles (the other vertices keep their
// order); a nan or infinite normal becomes the normalized sum of its triangles' normals (+z without any);
// an infinite bone weight is dropped and the vertex's other weights renormalized (like negative ones).
// Triangles whose indices are past the mesh's vertices are dropped (counted in a warning). Elsewhere, each
// named in a warning: a rest transform with a non-finite number becomes the identity, such an offset matrix
// the inverse of the bone's rest pose, an animation key (or its time) the track drops, and a non-finite clip
// duration becomes the clip's last key time.
#pragma once

#include <stdexcept>
#include <string>

#include "cga/runtime/character.hpp"

namespace cga {

// Missing, unreadable or corrupt file, a file without a skeleton, or an importer that crashed or took too
// long on it. The message names the path and carries Assimp's own message where it has one.
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
