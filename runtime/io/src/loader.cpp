// Assimp -> Character: skeleton, skinned meshes, clips, and the warnings about what had to be approximated.
#include "cga/io/loader.hpp"

#include <algorithm>
#include <chrono>
#include <csignal>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <set>
#include <deque>
#include <unordered_map>

#include <assimp/Importer.hpp>
#include <assimp/config.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <fmt/format.h>

#include "character_wire.hpp"
#include "isolated.hpp"

namespace cga {

namespace {

glm::mat4 to_glm(const aiMatrix4x4& m) {
  glm::mat4 out;  // Assimp is row-major (m[row][col]), GLM column-major (out[col][row])
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) out[c][r] = m[r][c];
  return out;
}

glm::quat to_glm(const aiQuaternion& q) {
  glm::quat out;
  out.w = q.w;
  out.x = q.x;
  out.y = q.y;
  out.z = q.z;
  return out;
}

// Collects warnings, naming the first few of each kind and counting the rest.
class Warnings {
 public:
  Warnings(std::vector<std::string>& out, int limit) : out_(out), limit_(limit) {}
  void add(const std::string& kind, std::string text) {
    if (++counts_[kind] <= limit_) out_.push_back(std::move(text));
  }
  void finish() {
    for (const auto& [kind, n] : counts_)
      if (n > limit_) out_.push_back(fmt::format("{}: {} more like the above not listed", kind, n - limit_));
  }

 private:
  std::vector<std::string>& out_;
  int limit_;
  std::map<std::string, int> counts_;
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
bool finite(const glm::quat& q) { return std::isfinite(q.w) && std::isfinite(q.x) && std::isfinite(q.y) && std::isfinite(q.z); }
bool finite(const Transform& x) { return finite(x.translation) && finite(x.rotation) && std::isfinite(x.scale); }
bool finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// Nearest uniform scale of a 3D scale: the geometric mean of the absolute values.
float uniform_scale(const glm::vec3& s) { return std::cbrt(std::abs(s.x * s.y * s.z)); }
bool is_uniform(const glm::vec3& s) {
  const float lo = std::min({std::abs(s.x), std::abs(s.y), std::abs(s.z)});
  const float hi = std::max({std::abs(s.x), std::abs(s.y), std::abs(s.z)});
  return s.x > 0 && s.y > 0 && s.z > 0 && hi - lo <= 1e-4f * hi;
}

// TRS with uniform scale of an affine matrix. `exact` tells whether the matrix is a similarity (rotation,
// uniform positive scale, translation) up to float rounding.
Transform decompose(const glm::mat4& m, bool& exact) {
  glm::mat3 a(m);
  const float det = glm::determinant(a);
  Transform x;
  x.translation = glm::vec3(m[3]);
  x.scale = std::cbrt(std::abs(det));
  exact = det > 0.0f && x.scale > 0.0f;
  if (x.scale <= 0.0f || !std::isfinite(x.scale)) {
    x.scale = 1.0f;
    return x;
  }
  const glm::mat3 r = a / x.scale;
  const glm::mat3 rtr = glm::transpose(r) * r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (std::abs(rtr[i][j] - (i == j ? 1.0f : 0.0f)) > 1e-3f) exact = false;
  // Nearest rotation of r (polar decomposition by a few Newton steps; exact input converges at once).
  glm::mat3 q = r;
  if (det < 0.0f) q = -q;
  for (int it = 0; it < 20; ++it) q = 0.5f * (q + glm::transpose(glm::inverse(q)));
  x.rotation = glm::normalize(glm::quat_cast(q));
  if (x.rotation.w < 0.0f) x.rotation = -x.rotation;
  return x;
}

// Removes the vertices marked in `drop` from every per-vertex array, and the triangles that use one of them;
// the other triangles' indices follow their vertices.
void drop_vertices(SkinnedMesh& mesh, const std::vector<bool>& drop) {
  const std::size_t nv = mesh.vertex_count();
  std::vector<std::uint32_t> to(nv);
  std::size_t kept = 0;
  for (std::size_t v = 0; v < nv; ++v) {
    to[v] = std::uint32_t(kept);
    if (drop[v]) continue;
    mesh.px[kept] = mesh.px[v], mesh.py[kept] = mesh.py[v], mesh.pz[kept] = mesh.pz[v];
    if (mesh.has_normals()) mesh.nx[kept] = mesh.nx[v], mesh.ny[kept] = mesh.ny[v], mesh.nz[kept] = mesh.nz[v];
    mesh.joints[kept] = mesh.joints[v];
    mesh.weights[kept] = mesh.weights[v];
    ++kept;
  }
  for (auto* a : {&mesh.px, &mesh.py, &mesh.pz}) a->resize(kept);
  if (mesh.has_normals())
    for (auto* a : {&mesh.nx, &mesh.ny, &mesh.nz}) a->resize(kept);
  mesh.joints.resize(kept);
  mesh.weights.resize(kept);
  std::vector<std::uint32_t> indices;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t* tri = &mesh.indices[t];
    if (drop[tri[0]] || drop[tri[1]] || drop[tri[2]]) continue;
    for (int i = 0; i < 3; ++i) indices.push_back(to[tri[i]]);
  }
  mesh.indices = std::move(indices);
}

// Gives each listed vertex the normalized sum of its triangles' normals (area-weighted: the unnormalized cross
// products), or +z when no triangle with an area uses it.
void repair_normals(SkinnedMesh& mesh, const std::vector<unsigned>& vertices) {
  std::unordered_map<unsigned, glm::vec3> sums;
  for (unsigned v : vertices) sums[v] = glm::vec3(0.0f);
  auto pos = [&](std::uint32_t v) { return glm::vec3(mesh.px[v], mesh.py[v], mesh.pz[v]); };
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const std::uint32_t* tri = &mesh.indices[t];
    const glm::vec3 n = glm::cross(pos(tri[1]) - pos(tri[0]), pos(tri[2]) - pos(tri[0]));
    if (!std::isfinite(n.x) || !std::isfinite(n.y) || !std::isfinite(n.z)) continue;
    for (int i = 0; i < 3; ++i)
      if (auto it = sums.find(tri[i]); it != sums.end()) it->second += n;
  }
  for (auto& [v, n] : sums) {
    const float len = glm::length(n);
    const glm::vec3 unit = len > 0.0f && std::isfinite(len) ? n / len : glm::vec3(0.0f, 0.0f, 1.0f);
    mesh.nx[v] = unit.x, mesh.ny[v] = unit.y, mesh.nz[v] = unit.z;
  }
}

// How long an import may take before its process is stopped: CGA_IMPORT_TIME_LIMIT seconds, else 60.
std::chrono::milliseconds import_time_limit() {
  if (const char* env = std::getenv("CGA_IMPORT_TIME_LIMIT")) {
    char* end = nullptr;
    const double s = std::strtod(env, &end);
    if (end != env && s > 0.0 && s < 1e7) return std::chrono::milliseconds(static_cast<long long>(s * 1000.0));
  }
  return std::chrono::seconds(60);
}

std::string ai_error(const Assimp::Importer& importer) {
  const char* e = importer.GetErrorString();
  return e && *e ? e : "no message";
}

// The import proper, run in the importer's child process: Assimp's scene to a Character whose clips have
// their tracks but not yet their keys (the caller builds those, see character_wire.hpp).
Character import_character(const std::string& path, const LoadOptions& options) {
  Assimp::Importer importer;
  // (No aiProcess_ValidateDataStructure: it rejects scenes without meshes, i.e. every BVH file.)
  // BVH has no mesh; without this Assimp invents one to draw the bones.
  importer.SetPropertyBool(AI_CONFIG_IMPORT_NO_SKELETON_MESHES, true);
  const unsigned flags = aiProcess_Triangulate | aiProcess_JoinIdenticalVertices | aiProcess_GenSmoothNormals;
  const aiScene* scene = importer.ReadFile(path, flags);
  if (!scene) throw LoadError(fmt::format("{}: Assimp cannot read it: {}", path, ai_error(importer)));
  if ((scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE) || !scene->mRootNode) {
    // Assimp's catch-all importers take many text files (a README) for an empty scene without a word.
    const char* e = importer.GetErrorString();
    if (!e || !*e) throw LoadError(fmt::format("{}: not a model file Assimp can read (it found no scene in it)", path));
    throw LoadError(fmt::format("{}: Assimp read an incomplete scene: {}", path, e));
  }

  Character ch;
  ch.path = path;
  Warnings warn(ch.warnings, options.max_warnings_per_kind);

  // Which nodes are joints: bones of meshes, else animated nodes; then their ancestors.
  std::set<std::string> wanted;
  for (unsigned m = 0; m < scene->mNumMeshes; ++m)
    for (unsigned b = 0; b < scene->mMeshes[m]->mNumBones; ++b) wanted.insert(scene->mMeshes[m]->mBones[b]->mName.C_Str());
  if (wanted.empty())
    for (unsigned a = 0; a < scene->mNumAnimations; ++a)
      for (unsigned c = 0; c < scene->mAnimations[a]->mNumChannels; ++c)
        wanted.insert(scene->mAnimations[a]->mChannels[c]->mNodeName.C_Str());
  if (wanted.empty())
    throw LoadError(fmt::format("{}: no skeleton (no mesh bones and no animated nodes)", path));

  std::set<const aiNode*> keep;
  std::set<std::string> found;
  std::vector<const aiNode*> stack{scene->mRootNode};
  while (!stack.empty()) {
    const aiNode* n = stack.back();
    stack.pop_back();
    if (wanted.count(n->mName.C_Str())) {
      found.insert(n->mName.C_Str());
      for (const aiNode* a = n; a; a = a->mParent) keep.insert(a);
    }
    for (unsigned i = 0; i < n->mNumChildren; ++i) stack.push_back(n->mChildren[i]);
  }
  // A mesh bone whose node the scene lacks (some exporters write such skins; Assimp's viewer shows them): it
  // becomes a static root joint at its bind pose (the inverse of its offset matrix), added after the others.
  std::vector<std::string> missing;
  for (const std::string& name : wanted)
    if (!found.count(name)) missing.push_back(name);
  const aiNode* root = scene->mRootNode;
  if (!wanted.count(root->mName.C_Str()) && root->mTransformation.IsIdentity()) keep.erase(root);

  // Parents first, in breadth-first order over the scene (as ozz orders its skeletons): consecutive joints
  // are then mostly siblings or cousins, whose local-to-model products do not wait for each other.
  std::unordered_map<const aiNode*, int> index;
  std::deque<std::pair<const aiNode*, int>> todo{{root, -1}};
  while (!todo.empty()) {
    auto [n, parent] = todo.front();
    todo.pop_front();
    int self = parent;
    if (keep.count(n)) {
      self = ch.skeleton.joint_count();
      index[n] = self;
      ch.skeleton.names.push_back(n->mName.C_Str());
      ch.skeleton.parents.push_back(parent);
      bool exact = true;
      const glm::mat4 local = to_glm(n->mTransformation);
      Transform rest;
      if (finite(local)) rest = decompose(local, exact);
      if (!finite(local) || !finite(rest)) {
        rest = Transform{};
        exact = true;
        warn.add("not finite", fmt::format("joint '{}': rest transform has numbers that are not finite; using the "
                                           "identity", n->mName.C_Str()));
      }
      ch.skeleton.rest_local.push_back(rest);
      if (!exact)
        warn.add("rest transform", fmt::format("joint '{}': rest transform is not a similarity (non-uniform "
                                               "scale, shear or mirror); using the nearest uniform scale",
                                               n->mName.C_Str()));
    }
    for (unsigned i = 0; i < n->mNumChildren; ++i) todo.push_back({n->mChildren[i], self});
  }
  std::vector<bool> static_joint(ch.skeleton.joint_count(), false);
  for (const std::string& name : missing) {
    const aiBone* bone = nullptr;
    for (unsigned m = 0; m < scene->mNumMeshes && !bone; ++m)
      for (unsigned b = 0; b < scene->mMeshes[m]->mNumBones && !bone; ++b)
        if (name == scene->mMeshes[m]->mBones[b]->mName.C_Str()) bone = scene->mMeshes[m]->mBones[b];
    if (!bone) {  // no mesh has bones and an animation channel names a node the scene lacks
      warn.add("channel without node", fmt::format("animated node '{}' is not in the scene; its channel is "
                                                   "ignored", name));
      continue;
    }
    ch.skeleton.names.push_back(name);
    ch.skeleton.parents.push_back(-1);
    bool exact = true;
    const glm::mat4 bind = glm::inverse(to_glm(bone->mOffsetMatrix));
    Transform rest;
    if (finite(bind)) rest = decompose(bind, exact);
    if (!finite(bind) || !finite(rest)) {
      rest = Transform{};
      warn.add("not finite", fmt::format("bone '{}': offset matrix is not finite or not invertible; its static "
                                         "joint is at the origin", name));
    }
    ch.skeleton.rest_local.push_back(rest);
    static_joint.push_back(true);
    warn.add("bone without node", fmt::format("bone '{}' has no node in the scene; its vertices stay at their "
                                              "bind pose (a static joint)", name));
  }
  if (ch.skeleton.joint_count() == 0) throw LoadError(fmt::format("{}: no skeleton", path));
  if (ch.skeleton.joint_count() > 65535) throw LoadError(fmt::format("{}: too many joints", path));

  if (options.meshes) {
    // The bind pose an offset matrix with non-finite numbers is replaced by: the bone's rest pose.
    const std::vector<glm::mat4> rest_model = rest_model_matrices(ch.skeleton);
    for (unsigned mi = 0; mi < scene->mNumMeshes; ++mi) {
      const aiMesh* am = scene->mMeshes[mi];
      if (am->mNumBones == 0) {
        warn.add("unskinned mesh", fmt::format("mesh '{}' has no bones; not loaded", am->mName.C_Str()));
        continue;
      }
      SkinnedMesh mesh;
      mesh.name = am->mName.C_Str();
      const unsigned nv = am->mNumVertices;
      // A vertex whose position is not finite (a "nan" or an overflowing "1e39" in the file) has no place to
      // be drawn: it is dropped with its triangles (below), each named in a warning.
      std::vector<bool> dropped(nv, false);
      unsigned n_dropped = 0;
      for (unsigned v = 0; v < nv; ++v) {
        const aiVector3D& p = am->mVertices[v];
        if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) continue;
        dropped[v] = true;
        ++n_dropped;
        warn.add("not finite", fmt::format("mesh '{}', vertex {}: position ({}, {}, {}) is not finite; dropped the "
                                           "vertex and its triangles", mesh.name, v, p.x, p.y, p.z));
      }
      if (n_dropped == nv && nv > 0) {
        warn.add("not finite", fmt::format("mesh '{}': no vertex has a finite position; not loaded", mesh.name));
        continue;
      }
      mesh.px.resize(nv), mesh.py.resize(nv), mesh.pz.resize(nv);
      for (unsigned v = 0; v < nv; ++v)
        mesh.px[v] = am->mVertices[v].x, mesh.py[v] = am->mVertices[v].y, mesh.pz[v] = am->mVertices[v].z;
      std::vector<unsigned> bad_normals;  // rebuilt from the vertex's triangles once the mesh is complete
      if (am->mNormals) {
        mesh.nx.resize(nv), mesh.ny.resize(nv), mesh.nz.resize(nv);
        for (unsigned v = 0; v < nv; ++v) {
          const aiVector3D& n = am->mNormals[v];
          mesh.nx[v] = n.x, mesh.ny[v] = n.y, mesh.nz[v] = n.z;
          if (dropped[v] || (std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z))) continue;
          bad_normals.push_back(v);
          warn.add("not finite", fmt::format("mesh '{}', vertex {}: normal ({}, {}, {}) is not finite; replaced by "
                                             "the normalized sum of its triangles' normals", mesh.name, v, n.x, n.y, n.z));
        }
      }
      // Assimp does not check face indices against the vertex count (it runs no validation step, see above).
      int bad_faces = 0;
      for (unsigned f = 0; f < am->mNumFaces; ++f) {
        const aiFace& face = am->mFaces[f];
        if (face.mNumIndices != 3) continue;
        if (face.mIndices[0] >= nv || face.mIndices[1] >= nv || face.mIndices[2] >= nv) {
          ++bad_faces;
          continue;
        }
        for (int i = 0; i < 3; ++i) mesh.indices.push_back(face.mIndices[i]);
      }

      std::vector<std::vector<std::pair<float, std::uint16_t>>> influences(nv);
      int bad_weights = 0, bad_vertex_ids = 0;
      for (unsigned b = 0; b < am->mNumBones; ++b) {
        const aiBone* bone = am->mBones[b];
        mesh.joint_remap.push_back(ch.skeleton.find(bone->mName.C_Str()));
        glm::mat4 offset = to_glm(bone->mOffsetMatrix);
        bool exact = true;
        Transform inverse_bind;
        if (finite(offset)) inverse_bind = decompose(offset, exact);
        if (!finite(offset) || !finite(inverse_bind)) {
          const int j = mesh.joint_remap.back();
          offset = j >= 0 ? glm::inverse(rest_model[j]) : glm::mat4(1.0f);
          if (!finite(offset)) offset = glm::mat4(1.0f);
          exact = true;
          inverse_bind = decompose(offset, exact);
          warn.add("not finite", fmt::format("mesh '{}', bone '{}': offset matrix has numbers that are not finite; "
                                             "using the inverse of the bone's rest pose", mesh.name,
                                             bone->mName.C_Str()));
        }
        mesh.inverse_bind_matrix.push_back(offset);
        mesh.inverse_bind.push_back(inverse_bind);
        if (!exact)
          warn.add("bind matrix", fmt::format("mesh '{}', bone '{}': offset matrix is not a similarity; "
                                              "motors and dual quaternions use the nearest uniform scale",
                                              mesh.name, bone->mName.C_Str()));
        for (unsigned w = 0; w < bone->mNumWeights; ++w) {
          const aiVertexWeight& vw = bone->mWeights[w];
          if (vw.mVertexId >= nv) {
            ++bad_vertex_ids;
          } else if (vw.mWeight > 0.0f && std::isfinite(vw.mWeight)) {
            influences[vw.mVertexId].push_back({vw.mWeight, std::uint16_t(b)});
          } else if (!std::isfinite(vw.mWeight)) {
            if (!dropped[vw.mVertexId])
              warn.add("not finite", fmt::format("mesh '{}', vertex {}: bone '{}' has weight {}, not finite; "
                                                 "dropped, the vertex's other weights renormalized",
                                                 mesh.name, vw.mVertexId, bone->mName.C_Str(), vw.mWeight));
          } else if (vw.mWeight != 0.0f) {
            ++bad_weights;  // negative: dropped, the vertex's other weights renormalized
          }
        }
      }
      mesh.joints.assign(nv, {0, 0, 0, 0});
      mesh.weights.assign(nv, {0, 0, 0, 0});
      int over4 = 0, unweighted = 0;
      for (unsigned v = 0; v < nv; ++v) {
        auto& inf = influences[v];
        std::stable_sort(inf.begin(), inf.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
        if (inf.size() > 4) ++over4, inf.resize(4);
        if (inf.empty()) {
          if (!dropped[v]) ++unweighted;
          mesh.weights[v] = {1, 0, 0, 0};  // follows palette entry 0 rather than collapsing to the origin
          continue;
        }
        float sum = 0.0f;
        for (const auto& p : inf) sum += p.first;
        if (!std::isfinite(sum)) {  // finite weights near FLT_MAX: relative to the largest, they sum to <= 4
          const float largest = inf[0].first;
          sum = 0.0f;
          for (auto& p : inf) sum += (p.first /= largest);
        }
        for (std::size_t k = 0; k < inf.size(); ++k) {
          mesh.joints[v][k] = inf[k].second;
          mesh.weights[v][k] = inf[k].first / sum;
        }
      }
      if (n_dropped) drop_vertices(mesh, dropped);
      if (!bad_normals.empty()) {
        // Indices after dropping: the old index minus the dropped vertices before it.
        std::vector<unsigned> shift(nv + 1, 0);
        for (unsigned v = 0; v < nv; ++v) shift[v + 1] = shift[v] + (dropped[v] ? 1 : 0);
        for (unsigned& v : bad_normals) v -= shift[v];
        repair_normals(mesh, bad_normals);
      }
      if (bad_faces)
        warn.add("faces", fmt::format("mesh '{}': dropped {} triangles whose vertex indices are past its {} vertices",
                                      mesh.name, bad_faces, nv));
      if (bad_weights)
        warn.add("influences", fmt::format("mesh '{}': dropped {} negative bone weights; renormalized "
                                           "the vertices' other weights", mesh.name, bad_weights));
      if (bad_vertex_ids)
        warn.add("influences", fmt::format("mesh '{}': dropped {} bone weights of vertices that do not exist",
                                           mesh.name, bad_vertex_ids));
      if (over4)
        warn.add("influences", fmt::format("mesh '{}': {} vertices had more than 4 influences; kept the 4 "
                                           "largest and renormalized", mesh.name, over4));
      if (unweighted)
        warn.add("influences", fmt::format("mesh '{}': {} vertices had no bone weight; bound to bone '{}'",
                                           mesh.name, unweighted, am->mBones[0]->mName.C_Str()));
      ch.meshes.push_back(std::move(mesh));
    }
  }

  if (options.animations) {
    for (unsigned ai = 0; ai < scene->mNumAnimations; ++ai) {
      const aiAnimation* an = scene->mAnimations[ai];
      Clip clip;
      clip.name = an->mName.C_Str();
      // Assimp leaves ticks per second 0 when the file does not say; 25 is its documented default.
      clip.ticks_per_second = an->mTicksPerSecond > 0.0 ? float(an->mTicksPerSecond) : 25.0f;
      const double tps = clip.ticks_per_second;
      clip.duration = float(an->mDuration / tps);
      clip.tracks.resize(ch.skeleton.joint_count());
      std::vector<bool> animated(ch.skeleton.joint_count(), false);
      for (unsigned c = 0; c < an->mNumChannels; ++c) {
        const aiNodeAnim* na = an->mChannels[c];
        const int j = ch.skeleton.find(na->mNodeName.C_Str());
        if (j < 0) continue;  // an animated node outside the skeleton (e.g. a mesh's own node)
        if (static_joint[j]) continue;  // a bone without node: kept at its bind pose
        animated[j] = true;
        JointTrack& tr = clip.tracks[j];
        // A key with a time or value that is not finite (or a rotation of length 0) is dropped: the track
        // interpolates across it, or holds the rest value when no key is left.
        auto dropped_key = [&](const char* what, unsigned k, const std::string& value, float time) {
          warn.add("not finite", fmt::format("clip '{}', bone '{}', {} key {}: {} at time {} is not finite; dropped",
                                             clip.name, na->mNodeName.C_Str(), what, k, value, time));
        };
        for (unsigned k = 0; k < na->mNumPositionKeys; ++k) {
          const aiVectorKey& key = na->mPositionKeys[k];
          const float t = float(key.mTime / tps);
          const glm::vec3 v(key.mValue.x, key.mValue.y, key.mValue.z);
          if (!std::isfinite(t) || !finite(v)) {
            dropped_key("translation", k, fmt::format("({}, {}, {})", v.x, v.y, v.z), t);
            continue;
          }
          tr.translations.push_back({t, v});
        }
        for (unsigned k = 0; k < na->mNumRotationKeys; ++k) {
          const aiQuatKey& key = na->mRotationKeys[k];
          const float t = float(key.mTime / tps);
          const glm::quat raw = to_glm(key.mValue);
          const float length = glm::length(raw);
          glm::quat q = glm::normalize(raw);
          if (!std::isfinite(t) || !(length > 0.0f) || !std::isfinite(length) || !finite(q)) {
            dropped_key("rotation", k, fmt::format("({}, {}, {}, {}) (length {})", raw.w, raw.x, raw.y, raw.z, length), t);
            continue;
          }
          // q and -q are one rotation; keep neighbours on the same side so lerps take the short way.
          if (!tr.rotations.empty() && glm::dot(tr.rotations.back().value, q) < 0.0f) q = -q;
          tr.rotations.push_back({t, q, rotor_from_quat(q)});
        }
        for (unsigned k = 0; k < na->mNumScalingKeys; ++k) {
          const aiVectorKey& key = na->mScalingKeys[k];
          const float t = float(key.mTime / tps);
          const glm::vec3 s(key.mValue.x, key.mValue.y, key.mValue.z);
          float u = uniform_scale(s);
          if (!std::isfinite(t) || !finite(s) || !std::isfinite(u)) {
            dropped_key("scale", k, fmt::format("({}, {}, {})", s.x, s.y, s.z), t);
            continue;
          }
          if (!is_uniform(s)) {
            warn.add("scale key " + clip.name,
                     fmt::format("clip '{}', bone '{}', scale key {}: non-uniform scale ({}, {}, {}) cannot be a "
                                 "motor; using the uniform scale {} (geometric mean)",
                                 clip.name, na->mNodeName.C_Str(), k, s.x, s.y, s.z, u));
          }
          if (!(u > 0.0f)) u = 1.0f;
          tr.scales.push_back({t, u});
        }
      }
      // Tracks the file leaves empty hold the rest value.
      for (int j = 0; j < ch.skeleton.joint_count(); ++j) {
        JointTrack& tr = clip.tracks[j];
        const Transform& rest = ch.skeleton.rest_local[j];
        if (tr.translations.empty()) tr.translations.push_back({0.0f, rest.translation});
        if (tr.rotations.empty()) tr.rotations.push_back({0.0f, rest.rotation, rotor_from_quat(rest.rotation)});
        if (tr.scales.empty()) tr.scales.push_back({0.0f, rest.scale});
        auto by_time = [](const auto& a, const auto& b) { return a.time < b.time; };
        std::stable_sort(tr.translations.begin(), tr.translations.end(), by_time);
        std::stable_sort(tr.rotations.begin(), tr.rotations.end(), by_time);
        std::stable_sort(tr.scales.begin(), tr.scales.end(), by_time);
      }
      if (!std::isfinite(clip.duration)) {
        float last = 0.0f;
        for (const JointTrack& tr : clip.tracks) {
          for (const auto& key : tr.translations) last = std::max(last, key.time);
          for (const auto& key : tr.rotations) last = std::max(last, key.time);
          for (const auto& key : tr.scales) last = std::max(last, key.time);
        }
        warn.add("not finite", fmt::format("clip '{}': duration {} s is not finite; using its last key time, {} s",
                                           clip.name, clip.duration, last));
        clip.duration = last;
      }
      ch.clips.push_back(std::move(clip));
    }
  }
  warn.finish();
  return ch;
}

}  // namespace

Character load_character(const std::string& path, const LoadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec))
    throw LoadError(fmt::format("{}: cannot load character: is a directory", path));
  if (!std::filesystem::is_regular_file(path, ec))
    throw LoadError(fmt::format("{}: cannot load character: no such file", path));

  // In the child: 'C' and the character, or 'E' and the error message.
  auto import = [&]() -> std::string {
    try {
      return 'C' + io_detail::encode_character(import_character(path, options));
    } catch (const LoadError& e) {
      return std::string("E") + e.what();
    } catch (const std::bad_alloc&) {
      return fmt::format("E{}: the model importer ran out of memory reading it", path);
    } catch (const std::exception& e) {
      return fmt::format("E{}: cannot load character: {}", path, e.what());
    }
  };
  const auto limit = import_time_limit();
  const io_detail::ChildOutcome out = io_detail::run_in_child(import, limit);
  using Kind = io_detail::ChildOutcome::Kind;
  switch (out.kind) {
    case Kind::finished: break;
    case Kind::signaled:
      if (out.code == SIGKILL)
        throw LoadError(fmt::format("{}: the model importer was killed (SIGKILL) reading it; the system may have "
                                    "run out of memory", path));
      throw LoadError(fmt::format("{}: the model importer crashed ({}) reading it; the file is malformed", path,
                                  io_detail::signal_name(out.code)));
    case Kind::exited:
      throw LoadError(fmt::format("{}: the model importer failed (exit status {}) reading it; the file is "
                                  "malformed", path, out.code));
    case Kind::timed_out:
      throw LoadError(fmt::format("{}: the model importer took longer than {} s reading it; stopped it", path,
                                  std::chrono::duration_cast<std::chrono::seconds>(limit).count()));
    case Kind::failed:
      throw LoadError(fmt::format("{}: cannot start the model importer's process ({})", path, out.output));
  }
  if (out.output.empty() || out.output[0] != 'C') throw LoadError(out.output.empty() ? path + ": no result" : out.output.substr(1));
  Character ch;
  try {
    ch = io_detail::decode_character(std::string_view(out.output).substr(1));
  } catch (const std::exception& e) {
    throw LoadError(fmt::format("{}: the model importer's result is unreadable: {}", path, e.what()));
  }
  for (Clip& clip : ch.clips) {
    try {
      build_joint_keys(clip);
    } catch (const std::exception& e) {
      throw LoadError(fmt::format("{}: clip '{}': {}", path, clip.name, e.what()));
    }
  }
  return ch;
}

}  // namespace cga
