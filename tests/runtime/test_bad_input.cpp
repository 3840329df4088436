// Bad input to the runtime: truncated and corrupt model files, skin weights that are NaN,
// negative, all zero or do not sum to 1 (in a file: the loader repairs them and says so; in a hand-made mesh:
// SkinningJob refuses them), joint indices outside the palette, clips with zero or one key, and times outside
// the clip or not finite. Each must end in a clear error or a documented repair, never a crash or a silent
// wrong pose. Files are derived from Debian's assimp-testmodels and written to a temporary folder.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/io/loader.hpp"
#include "model_files.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;
using baseline::kAllPoseModes;
using baseline::PoseMode;
namespace fs = std::filesystem;

namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();

using cga_test::model;
using cga_test::read_bytes;
using cga_test::temp_file;

// Loading must either throw LoadError naming the path, or give a character that is safe to use.
// Returns true when it threw.
bool load_fails_cleanly(const std::string& path) {
  try {
    const Character ch = load_character(path);
    for (const SkinnedMesh& m : ch.meshes)
      for (std::size_t v = 0; v < m.vertex_count(); ++v)
        for (int k = 0; k < 4; ++k) REQUIRE(m.joints[v][k] < m.joint_remap.size());
    for (const Clip& c : ch.clips)
      for (const JointKeys& k : c.keys) REQUIRE(k.size() >= 1);
    return false;
  } catch (const LoadError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find(path) != std::string::npos);
    return true;
  }
}

// Rewrites every weight of the .X file's SkinWeights blocks: `edit(block, index_in_block, text)` returns the new
// text of the number (without the separator). Layout of a block: `SkinWeights name {`, the bone name, `N;`,
// N vertex-index lines, N weight lines (the last ends with ';'), then the offset matrix.
std::string edit_x_weights(const std::string& text,
                           const std::function<std::string(int, int, const std::string&)>& edit) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t nl = text.find('\n', start);
    lines.push_back(text.substr(start, nl == std::string::npos ? std::string::npos : nl - start));
    if (nl == std::string::npos) break;
    start = nl + 1;
  }
  int block = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (lines[i].find("SkinWeights ") == std::string::npos || lines[i].find('{') == std::string::npos ||
        lines[i].find("template") != std::string::npos)
      continue;
    const int n = std::stoi(lines[i + 2]);
    const std::size_t first_weight = i + 3 + std::size_t(n);
    for (int w = 0; w < n; ++w) {
      std::string& line = lines[first_weight + w];
      const std::size_t begin = line.find_first_not_of(" \t");
      const std::size_t end = line.find_first_of(",;", begin);
      REQUIRE(end != std::string::npos);
      line = line.substr(0, begin) + edit(block, w, line.substr(begin, end - begin)) + line.substr(end);
    }
    ++block;
    i = first_weight + n;
  }
  REQUIRE(block > 0);
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) out += lines[i] + (i + 1 < lines.size() ? "\n" : "");
  return out;
}

bool has_warning(const Character& ch, const std::string& part) {
  for (const std::string& w : ch.warnings)
    if (w.find(part) != std::string::npos) return true;
  return false;
}

// Every vertex: joints in the palette, weights finite, >= 0, summing to 1.
void check_weights_repaired(const Character& ch) {
  for (const SkinnedMesh& m : ch.meshes)
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) {
        INFO("mesh " << m.name << " vertex " << v << " slot " << k);
        REQUIRE(std::isfinite(m.weights[v][k]));
        REQUIRE(m.weights[v][k] >= 0.0f);
        REQUIRE(m.joints[v][k] < m.joint_remap.size());
        sum += m.weights[v][k];
      }
      REQUIRE(std::abs(sum - 1.0f) < 1e-5f);
    }
}

// A one-joint clip with the given keys (all three tracks at the same times), built like the loader builds it.
Clip one_joint_clip(const std::vector<float>& times, const std::vector<Transform>& keys, float duration) {
  Clip c;
  c.name = "test";
  c.duration = duration;
  c.tracks.resize(1);
  for (std::size_t i = 0; i < times.size(); ++i) {
    c.tracks[0].translations.push_back({times[i], keys[i].translation});
    c.tracks[0].rotations.push_back({times[i], keys[i].rotation, rotor_from_quat(keys[i].rotation)});
    c.tracks[0].scales.push_back({times[i], keys[i].scale});
  }
  build_joint_keys(c);
  return c;
}

// The sampling job of the mode's representation: the runtime's motor job or a GLM baseline.
struct Sampler {
  const Clip* clip;
  float time;
  PoseMode mode;
  baseline::PoseBuffer* pose;
  bool Validate() const {
    switch (mode) {
      case PoseMode::glm_matrix: return baseline::TransformSamplingJob{clip, time, pose->transforms}.Validate();
      case PoseMode::glm_dualquat:
        return baseline::DualQuatSamplingJob{clip, time, pose->dual_quats, pose->scales}.Validate();
      default: return SamplingJob{clip, time, baseline::to_interpolation(mode), pose->motors}.Validate();
    }
  }
  bool Run() const { return baseline::sample(mode, *clip, time, *pose); }
};
Sampler sampler(const Clip& clip, float t, PoseMode mode, baseline::PoseBuffer& pose) {
  return {&clip, t, mode, &pose};
}

// Where joint 0's sampled transform puts point p, in the pose's own representation.
glm::vec3 apply(PoseMode mode, const baseline::PoseBuffer& pose, glm::vec3 p) {
  switch (mode) {
    case PoseMode::glm_matrix: return glm::vec3(to_mat4(pose.transforms[0]) * glm::vec4(p, 1.0f));
    case PoseMode::glm_dualquat:
      return pose.dual_quats[0].real * (pose.scales[0] * p) + baseline::dual_quat_translation(pose.dual_quats[0]);
    default: return motor_transform_point(pose.motors[0], p);
  }
}

Transform key(glm::vec3 t, float angle, float scale) {
  Transform x;
  x.translation = t;
  x.rotation = glm::angleAxis(angle, glm::normalize(glm::vec3(1, 2, 3)));
  x.scale = scale;
  return x;
}

}  // namespace

// ------------------------------------------------------------------------------------------ model files

TEST_CASE("model files truncated anywhere give a LoadError naming the file or a usable character") {
  const char* models[] = {"X/BCN_Epileptic.X", "X/Testwuson.X", "FBX/animation_with_skeleton.fbx", "BVH/01_01.bvh"};
  for (const char* rel : models) {
    const std::string bytes = read_bytes(model(rel));
    const std::string ext = fs::path(rel).extension().string();
    int failed = 0;
    // 0 bytes, a few bytes, and cuts spread over the file (the tail of a text file is where parsers trust
    // counts they read earlier).
    std::vector<std::size_t> cuts = {0, 1, 16, 64};
    for (int k = 1; k < 20; ++k) cuts.push_back(bytes.size() * std::size_t(k) / 20);
    cuts.push_back(bytes.size() - 1);
    for (std::size_t cut : cuts) {
      INFO(rel << " cut at " << cut << " of " << bytes.size() << " bytes");
      const std::string p = temp_file("truncated_" + std::to_string(cut) + ext, bytes.substr(0, cut));
      failed += load_fails_cleanly(p);
    }
    INFO(rel);
    // A file cut before its skeleton is complete cannot load: at least the short prefixes must fail.
    CHECK(failed >= 4);
  }
}

TEST_CASE("model files with corrupted bytes give a LoadError naming the file or a usable character") {
  const char* models[] = {"X/BCN_Epileptic.X", "FBX/animation_with_skeleton.fbx", "BVH/01_01.bvh"};
  for (const char* rel : models) {
    const std::string bytes = read_bytes(model(rel));
    const std::string ext = fs::path(rel).extension().string();
    // Overwrite a 64-byte window at several places with bytes that are neither numbers nor structure.
    for (int k = 1; k < 10; ++k) {
      std::string bad = bytes;
      const std::size_t at = bytes.size() * std::size_t(k) / 10;
      for (std::size_t i = at; i < std::min(bad.size(), at + 64); ++i) bad[i] = char(0x80 + (i * 37) % 0x7f);
      INFO(rel << " corrupted at " << at);
      load_fails_cleanly(temp_file("corrupt_" + std::to_string(k) + ext, bad));
    }
    // Header only, then garbage.
    std::string bad = bytes.substr(0, std::min<std::size_t>(bytes.size(), 32)) + std::string(4096, '\x7f');
    INFO(rel << " header then garbage");
    CHECK(load_fails_cleanly(temp_file("header_garbage" + ext, bad)));
  }
  SECTION("an empty file, a folder") {
    CHECK(load_fails_cleanly(temp_file("empty.x", "")));
    const fs::path dir = fs::path(temp_file("placeholder", "")).parent_path() / "folder.x";
    fs::create_directories(dir);
    CHECK(load_fails_cleanly(dir.string()));
  }
}

// ------------------------------------------------------------------------------ skin weights in files
// The loader's documented repair (docs/runtime.md, loader.hpp): influences whose weight is not > 0 (NaN,
// negative, zero) are dropped, the rest renormalized to sum 1; a vertex left without influence is bound to
// the mesh's first bone with weight 1. Each repair is reported in Character::warnings.

TEST_CASE("weights in a file that do not sum to 1 are renormalized") {
  const std::string text = read_bytes(model("X/BCN_Epileptic.X"));
  const Character original = load_character(model("X/BCN_Epileptic.X"));
  // Every weight times 3 (and, in the first block, times 7): the loader must give back the original weights.
  const std::string scaled = edit_x_weights(text, [](int block, int, const std::string& w) {
    return std::to_string(std::stod(w) * (block == 0 ? 7.0 : 3.0));
  });
  const Character ch = load_character(temp_file("weights_scaled.x", scaled));
  check_weights_repaired(ch);
  REQUIRE(ch.meshes.size() == original.meshes.size());
  for (std::size_t m = 0; m < ch.meshes.size(); ++m)
    for (std::size_t v = 0; v < ch.meshes[m].vertex_count(); ++v)
      for (int k = 0; k < 4; ++k) {
        INFO("mesh " << m << " vertex " << v << " slot " << k);
        // Block 0 scaled differently changes the ratios of vertices it shares with other bones, so only
        // vertices whose weights are all from other blocks compare exactly; the rest must still be valid.
        if (ch.meshes[m].joints[v] == original.meshes[m].joints[v] &&
            std::none_of(ch.meshes[m].joints[v].begin(), ch.meshes[m].joints[v].end(),
                         [](std::uint16_t j) { return j == 0; }))
          CHECK(ch.meshes[m].weights[v][k] == Approx(original.meshes[m].weights[v][k]).margin(1e-5));
      }
}

TEST_CASE("all-zero weights in a file: vertices go to the first bone, weightless meshes are left out, both said") {
  const std::string text = read_bytes(model("X/BCN_Epileptic.X"));
  const Character original = load_character(model("X/BCN_Epileptic.X"));
  SECTION("one bone's weights all zero") {
    // Assimp drops a bone without weight; vertices that only it moved have no influence left.
    const std::string zero = edit_x_weights(text, [](int block, int, const std::string& w) {
      return block == 0 ? std::string("0.0") : w;
    });
    const Character ch = load_character(temp_file("weights_zero_one_bone.x", zero));
    check_weights_repaired(ch);
    CHECK(ch.meshes.size() == original.meshes.size());
    CHECK(has_warning(ch, "no bone weight; bound to bone"));
  }
  SECTION("every weight zero") {
    // No mesh has a bone left: none is loaded (it cannot be skinned), and each one is named in a warning.
    const std::string zero = edit_x_weights(text, [](int, int, const std::string&) { return std::string("0.0"); });
    const Character ch = load_character(temp_file("weights_zero.x", zero));
    check_weights_repaired(ch);
    for (const SkinnedMesh& m : original.meshes) {
      INFO("mesh " << m.name);
      const bool loaded = std::any_of(ch.meshes.begin(), ch.meshes.end(),
                                      [&](const SkinnedMesh& x) { return x.name == m.name; });
      CHECK((loaded || has_warning(ch, "mesh '" + m.name + "' has no bones; not loaded")));
    }
  }
}

TEST_CASE("negative and NaN weights in a file are dropped, the rest renormalized, weightless vertices reported") {
  const std::string text = read_bytes(model("X/BCN_Epileptic.X"));
  // In every block: the first weight negative, the second NaN.
  const std::string bad = edit_x_weights(text, [](int, int i, const std::string& w) {
    if (i == 0) return std::string("-0.5");
    if (i == 1) return std::string("nan");
    return w;
  });
  const Character ch = load_character(temp_file("weights_negative_nan.x", bad));
  check_weights_repaired(ch);
  // Assimp's .X importer already drops weights that are not > 0, so the loader sees only the vertices left
  // with no influence at all, and reports those (formats that pass such weights through are counted by the
  // loader's own "dropped N negative bone weights" warning, and each non-finite one is named).
  INFO("warnings:\n" << [&] {
    std::string all;
    for (const std::string& w : ch.warnings) all += "  " + w + "\n";
    return all;
  }());
  CHECK(has_warning(ch, "no bone weight; bound to bone"));
  // The repair keeps the mesh whole: same meshes, same vertex counts as the unmodified file.
  const Character original = load_character(model("X/BCN_Epileptic.X"));
  REQUIRE(ch.meshes.size() == original.meshes.size());
  for (std::size_t m = 0; m < ch.meshes.size(); ++m) CHECK(ch.meshes[m].vertex_count() == original.meshes[m].vertex_count());
}

// ------------------------------------------------------------------------ skin weights in a job
// A hand-made mesh reaches SkinningJob without the loader's repair: Validate() must refuse weights that would
// give a wrong pose (lbs and cga-points scale the vertex by the weight sum), naming the vertex.

namespace {

struct SmallJob {
  SkinnedMesh mesh = make_random_skinned_mesh(64, 4, 11);
  std::vector<glm::mat3x4> matrices;
  SkinnedOutput out;
  SmallJob() {
    for (const Transform& x : make_random_transforms(4, 5)) matrices.push_back(to_skinning_matrix(x));
  }
  SkinningJob job() {
    SkinningJob j = make_skinning_job(SkinningMethod::lbs, mesh, out);
    j.matrices = matrices;
    return j;
  }
};

void require_refused(const SkinningJob& j, const std::string& part) {
  const std::string why = j.ValidationError();
  INFO("ValidationError: " << why);
  CHECK_FALSE(j.Validate());
  CHECK(why.find(part) != std::string::npos);
}

}  // namespace

TEST_CASE("SkinningJob refuses NaN, negative, all-zero and unnormalized weights") {
  SmallJob s;
  REQUIRE(s.job().Validate());
  SECTION("NaN") {
    s.mesh.weights[7] = {0.5f, kNaN, 0.5f, 0.0f};
    require_refused(s.job(), "vertex 7");
    CHECK_FALSE(s.job().Run());
  }
  SECTION("negative") {
    s.mesh.weights[9] = {1.5f, -0.5f, 0.0f, 0.0f};  // sums to 1
    require_refused(s.job(), "vertex 9");
  }
  SECTION("all zero") {
    s.mesh.weights[11] = {0.0f, 0.0f, 0.0f, 0.0f};
    require_refused(s.job(), "vertex 11");
  }
  SECTION("sum 2") {
    for (float& w : s.mesh.weights[13]) w *= 2.0f;
    require_refused(s.job(), "vertex 13");
  }
  SECTION("sum 1 within float rounding is fine") {
    s.mesh.weights[15] = {0.1f, 0.2f, 0.3f, 0.4f};
    CHECK(s.job().Validate());
  }
}

TEST_CASE("joint indices outside the palette: Validate names the vertex, Run refuses, outputs not read past") {
  SmallJob s;
  s.mesh.joints[21] = {0, 1, 4, 2};  // the palette has 4 entries
  const SkinningJob j = s.job();
  require_refused(j, "vertex 21");
  CHECK_FALSE(j.Run());
  // Every method refuses, with a palette of its own kind too short.
  s.mesh.joints[21] = {0, 1, 2, 3};
  std::vector<glm::dualquat> dq(3, glm::dualquat(glm::quat(1, 0, 0, 0), glm::vec3(0.0f)));
  SkinningJob d = make_skinning_job(SkinningMethod::dqs, s.mesh, s.out);
  d.dual_quats = dq;
  CHECK_FALSE(d.Validate());
  CHECK_FALSE(d.Run());
  // A skinning palette job whose joint map points outside the skeleton refuses too.
  const std::vector<int> remap = {0, 5}, negative = {0, -1};
  const std::vector<Motor> ib(2), model(3);
  std::vector<Motor> out(2);
  SkinningPaletteJob p{remap, ib, model, out};
  CHECK_FALSE(p.Validate());
  CHECK_FALSE(p.Run());
  p.joint_remap = negative;
  CHECK_FALSE(p.Run());
  // ... and so does the GLM baseline's.
  const std::vector<glm::mat4> ib_matrices(2, glm::mat4(1.0f)), model_matrices(3, glm::mat4(1.0f));
  std::vector<glm::mat3x4> out_matrices(2);
  baseline::MatrixPaletteJob m{remap, ib_matrices, model_matrices, out_matrices};
  CHECK_FALSE(m.Validate());
  CHECK_FALSE(m.Run());
  m.joint_remap = negative;
  CHECK_FALSE(m.Run());
}

// ---------------------------------------------------------------------------------------------- clips

TEST_CASE("a clip with zero keys is refused") {
  SECTION("an empty track cannot be built into keys") {
    Clip c;
    c.name = "empty";
    c.tracks.resize(2);
    c.tracks[0].translations.push_back({0.0f, glm::vec3(0.0f)});
    c.tracks[0].rotations.push_back({0.0f, glm::quat(1, 0, 0, 0), {1, 0, 0, 0}});
    c.tracks[0].scales.push_back({0.0f, 1.0f});
    try {
      build_joint_keys(c);
      FAIL("no exception");
    } catch (const std::invalid_argument& e) {
      CHECK(std::string(e.what()).find("'empty': joint 1") != std::string::npos);
    }
  }
  SECTION("a sampling job on a clip whose keys were never built") {
    Clip c;
    c.name = "unbuilt";
    c.duration = 1.0f;
    c.keys.resize(1);  // a joint with no keys at all
    baseline::PoseBuffer pose(1);
    for (PoseMode mode : kAllPoseModes) {
      INFO(to_string(mode));
      const Sampler s = sampler(c, 0.5f, mode, pose);
      CHECK_FALSE(s.Validate());
      if (!s.Validate()) CHECK_FALSE(s.Run());  // Run on a job that validates would read keys that do not exist
    }
  }
}

TEST_CASE("a clip with one key holds it at every time, in every mode") {
  const Transform k = key({0.3f, -1.0f, 2.0f}, 0.7f, 1.5f);
  const Clip clip = one_joint_clip({0.25f}, {k}, 2.0f);
  baseline::PoseBuffer pose(1);
  const glm::vec3 p(0.5f, 0.25f, -1.0f);
  const glm::vec3 want = glm::vec3(to_mat4(k) * glm::vec4(p, 1.0f));
  for (PoseMode mode : kAllPoseModes) {
    for (float t : {-3.0f, 0.0f, 0.25f, 1.0f, 2.0f, 100.0f}) {
      INFO(to_string(mode) << " t=" << t);
      REQUIRE(sampler(clip, t, mode, pose).Run());
      // glm-dualquat carries the scale apart from the rigid part; every mode must place p where the key does.
      CHECK(glm::length(apply(mode, pose, p) - want) < 1e-5f);
    }
  }
}

TEST_CASE("times outside the clip are clamped to its first and last key, non-finite times are refused") {
  // Keys that start after 0 and end before the duration: before the first key, the first key holds.
  const Transform a = key({1, 0, 0}, 0.2f, 1.0f), b = key({0, 2, 0}, 1.1f, 1.0f);
  const Clip clip = one_joint_clip({0.5f, 1.5f}, {a, b}, 2.0f);
  baseline::PoseBuffer pose(1);
  const glm::vec3 p(0.1f, 0.2f, 0.3f);
  const glm::vec3 at_a = glm::vec3(to_mat4(a) * glm::vec4(p, 1.0f));
  const glm::vec3 at_b = glm::vec3(to_mat4(b) * glm::vec4(p, 1.0f));
  for (PoseMode mode : kAllPoseModes) {
    for (float t : {-1e30f, -1.0f, 0.0f, 0.5f}) {
      INFO(to_string(mode) << " t=" << t);
      REQUIRE(sampler(clip, t, mode, pose).Run());
      CHECK(glm::length(apply(mode, pose, p) - at_a) < 1e-5f);
    }
    for (float t : {1.5f, 2.0f, 3.0f, 1e30f}) {
      INFO(to_string(mode) << " t=" << t);
      REQUIRE(sampler(clip, t, mode, pose).Run());
      CHECK(glm::length(apply(mode, pose, p) - at_b) < 1e-5f);
    }
    for (float t : {kNaN, std::numeric_limits<float>::infinity(), -std::numeric_limits<float>::infinity()}) {
      INFO(to_string(mode) << " t=" << t);
      const Sampler s = sampler(clip, t, mode, pose);
      CHECK_FALSE(s.Validate());
      CHECK_FALSE(s.Run());
    }
  }
}

TEST_CASE("a cross-fade whose weights are all zero, negative or NaN is refused") {
  baseline::PoseBuffer x(2), y(2), out(2);
  for (const std::vector<float>& w : std::vector<std::vector<float>>{{0.0f, 0.0f}, {-1.0f, 0.0f}, {kNaN, 1.0f}}) {
    for (PoseMode mode : kAllPoseModes) {
      INFO(to_string(mode) << " weights " << w[0] << ", " << w[1]);
      const BlendLayer motor_layers[2] = {{w[0], x.motors}, {w[1], y.motors}};
      const baseline::TransformLayer trs_layers[2] = {{w[0], x.transforms}, {w[1], y.transforms}};
      const baseline::DualQuatLayer dq_layers[2] = {{w[0], x.dual_quats, x.scales}, {w[1], y.dual_quats, y.scales}};
      const bool valid = mode == PoseMode::glm_matrix
                             ? baseline::TransformBlendingJob{trs_layers, out.transforms}.Validate()
                         : mode == PoseMode::glm_dualquat
                             ? baseline::DualQuatBlendingJob{dq_layers, out.dual_quats, out.scales}.Validate()
                             : BlendingJob{baseline::to_interpolation(mode), motor_layers, out.motors}.Validate();
      CHECK_FALSE(valid);
      const baseline::PoseLayer layers[2] = {{w[0], &x}, {w[1], &y}};
      CHECK_FALSE(baseline::blend(mode, layers, out));
    }
  }
}
