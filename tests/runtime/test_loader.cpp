// Loading the four assimp-testmodels characters (skeleton order, bone counts, clips, weights) and refusing
// bad files with a LoadError instead of crashing.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <set>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/io/loader.hpp"
#include "cga/runtime/skinning.hpp"

using namespace cga;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

// Structural invariants every loaded character must satisfy.
void check_character(const Character& ch) {
  const Skeleton& sk = ch.skeleton;
  REQUIRE(sk.joint_count() > 0);
  REQUIRE(sk.names.size() == sk.parents.size());
  REQUIRE(sk.rest_local.size() == sk.parents.size());
  CHECK(sk.parents[0] == -1);
  for (int j = 0; j < sk.joint_count(); ++j) {
    INFO("joint " << j << " " << sk.names[j]);
    CHECK(sk.parents[j] < j);
    CHECK(std::abs(glm::length(sk.rest_local[j].rotation) - 1.0f) < 1e-5f);
  }
  for (const SkinnedMesh& mesh : ch.meshes) {
    INFO("mesh " << mesh.name);
    REQUIRE(mesh.joints.size() == mesh.vertex_count());
    REQUIRE(mesh.weights.size() == mesh.vertex_count());
    REQUIRE(mesh.inverse_bind.size() == mesh.joint_remap.size());
    REQUIRE(mesh.inverse_bind_matrix.size() == mesh.joint_remap.size());
    for (int j : mesh.joint_remap) CHECK((j >= 0 && j < sk.joint_count()));
    CHECK(mesh.indices.size() % 3 == 0);
    for (std::uint32_t i : mesh.indices) REQUIRE(i < mesh.vertex_count());
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) {
        REQUIRE(mesh.weights[v][k] >= 0.0f);
        REQUIRE(mesh.joints[v][k] < mesh.joint_remap.size());
        sum += mesh.weights[v][k];
      }
      REQUIRE(std::abs(sum - 1.0f) < 1e-5f);
    }
  }
  for (const Clip& clip : ch.clips) {
    INFO("clip " << clip.name);
    CHECK(clip.duration >= 0.0f);
    REQUIRE(clip.tracks.size() == std::size_t(sk.joint_count()));
    REQUIRE(clip.keys.size() == std::size_t(sk.joint_count()));
    for (const JointKeys& k : clip.keys) {
      REQUIRE(k.size() >= 1);
      REQUIRE(k.transforms.size() == k.size());
      for (std::size_t i = 1; i < k.size(); ++i) REQUIRE(k.times[i] > k.times[i - 1]);
      REQUIRE(k.times.back() <= clip.duration + 1e-4f);
    }
    for (const JointTrack& t : clip.tracks)
      for (const RotationKey& r : t.rotations) {
        // The rotor is the quaternion, converted once: R = w - x e23 - y e31 - z e12.
        CHECK(r.rotor[0] == r.value.w);
        CHECK(r.rotor[1] == -r.value.z);
        CHECK(r.rotor[2] == r.value.y);
        CHECK(r.rotor[3] == -r.value.x);
      }
  }
}

std::set<std::string> mesh_bones(const Character& ch) {
  std::set<std::string> names;
  for (const SkinnedMesh& m : ch.meshes)
    for (int j : m.joint_remap) names.insert(ch.skeleton.names[j]);
  return names;
}

std::vector<std::string> clip_names(const Character& ch) {
  std::vector<std::string> names;
  for (const Clip& c : ch.clips) names.push_back(c.name);
  return names;
}

std::string temp_file(const std::string& name, const std::string& bytes) {
  // Per process: ctest runs test cases as parallel processes.
  const auto path =
      std::filesystem::temp_directory_path() / ("cga_runtime_test_" + std::to_string(::getpid()) + "_" + name);
  std::ofstream(path, std::ios::binary) << bytes;
  return path.string();
}

}  // namespace

TEST_CASE("BCN_Epileptic.X: 54 bones, three skinned meshes, one clip") {
  const Character ch = load_character(model("X/BCN_Epileptic.X"));
  check_character(ch);
  CHECK(mesh_bones(ch).size() == 54);  // BCN_Epileptic's 54 skinned bones
  CHECK(ch.meshes.size() == 3);
  REQUIRE(ch.clips.size() == 1);
  CHECK(ch.clips[0].duration > 0.0f);
  CHECK(character_size(ch) > 0.0f);
}

TEST_CASE("Testwuson.X: 37 bones, clips Wuson_Run and Wuson_Walk") {
  const Character ch = load_character(model("X/Testwuson.X"));
  check_character(ch);
  CHECK(mesh_bones(ch).size() == 37);
  const auto names = clip_names(ch);
  CHECK(std::count(names.begin(), names.end(), "Wuson_Run") == 1);
  CHECK(std::count(names.begin(), names.end(), "Wuson_Walk") == 1);
  // Run is shorter than Walk in this file (4640 vs 17280 ticks at 4800 per second).
  REQUIRE(ch.find_clip("Wuson_Run"));
  CHECK(ch.find_clip("Wuson_Run")->duration == Approx(4640.0 / 4800.0));
  CHECK(ch.find_clip("Wuson_Walk")->duration == Approx(17280.0 / 4800.0));
}

TEST_CASE("animation_with_skeleton.fbx loads a skinned mesh and a clip") {
  const Character ch = load_character(model("FBX/animation_with_skeleton.fbx"));
  check_character(ch);
  CHECK(mesh_bones(ch).size() == 14);
  CHECK(ch.meshes.size() == 1);
  CHECK(ch.clips.size() == 1);
}

TEST_CASE("01_01.bvh: skeleton and clip, no mesh") {
  const Character ch = load_character(model("BVH/01_01.bvh"));
  check_character(ch);
  CHECK(ch.meshes.empty());
  REQUIRE(ch.clips.size() == 1);
  CHECK(ch.skeleton.find("Hips") >= 0);
  // 2752 frames at 120 frames per second.
  const Clip& clip = ch.clips[0];
  const JointKeys& hips = clip.keys[ch.skeleton.find("Hips")];
  CHECK(hips.size() == 2752);
  CHECK(clip.duration == Approx(2751.0 / 120.0).epsilon(1e-4));
}

TEST_CASE("a non-uniform scale key is reported by bone and key index and replaced by the geometric mean") {
  const std::string x = R"(xof 0303txt 0032
Frame Root {
  FrameTransformMatrix {
    1.000000,0.000000,0.000000,0.000000,0.000000,1.000000,0.000000,0.000000,0.000000,0.000000,1.000000,0.000000,0.000000,0.000000,0.000000,1.000000;;
  }
  Frame Bone {
    FrameTransformMatrix {
      1.000000,0.000000,0.000000,0.000000,0.000000,1.000000,0.000000,0.000000,0.000000,0.000000,1.000000,0.000000,0.000000,1.000000,0.000000,1.000000;;
    }
  }
}
AnimationSet Clip {
  Animation {
    { Bone }
    AnimationKey {
      1;
      2;
      0;3;1.000000,1.000000,1.000000;;,
      10;3;1.000000,2.000000,4.000000;;;
    }
  }
}
)";
  const Character ch = load_character(temp_file("scale.x", x));
  bool named = false;
  for (const std::string& w : ch.warnings)
    if (w.find("Bone") != std::string::npos && w.find("scale key 1") != std::string::npos) named = true;
  INFO("warnings: " << ch.warnings.size());
  CHECK(named);
  const Clip& clip = ch.clips.at(0);
  const JointTrack& t = clip.tracks.at(ch.skeleton.find("Bone"));
  REQUIRE(t.scales.size() == 2);
  CHECK(t.scales[1].value == Approx(2.0f));  // geometric mean of 1, 2, 4
}

// tests/data/bone_without_node.x: a strip skinned to joint1 (y = 0), joint2 (y = 1) and joint3 (y = 2); the
// scene has no node joint3. The clip turns joint2 by 90 degrees about z.
TEST_CASE("a skinned bone without a node loads as a static joint, with a warning naming it") {
  const Character ch = load_character(std::string(CGA_TEST_DATA_DIR) + "/bone_without_node.x");
  check_character(ch);
  bool named = false;
  for (const std::string& w : ch.warnings)
    if (w.find("'joint3'") != std::string::npos && w.find("no node") != std::string::npos) named = true;
  INFO("warnings: " << ch.warnings.size());
  CHECK(named);
  const int j3 = ch.skeleton.find("joint3");
  REQUIRE(j3 >= 0);
  CHECK(ch.skeleton.parents[j3] == -1);
  REQUIRE(ch.meshes.size() == 1);
  REQUIRE(ch.clips.size() == 1);
  const SkinnedMesh& mesh = ch.meshes[0];
  CHECK(mesh_bones(ch) == std::set<std::string>{"joint1", "joint2", "joint3"});
  const Clip& clip = ch.clips[0];
  const baseline::InverseBind ib = baseline::make_inverse_bind(mesh);
  // Every method through its own pipeline at the end of the clip (joint2 turned by 90 degrees).
  for (SkinningMethod method : kAllSkinningMethods) {
    INFO("method " << to_string(method));
    using baseline::PoseMode;
    const PoseMode mode = method == SkinningMethod::lbs   ? PoseMode::glm_matrix
                          : method == SkinningMethod::dqs ? PoseMode::glm_dualquat
                                                          : PoseMode::paper;
    const std::size_t n = static_cast<std::size_t>(ch.skeleton.joint_count());
    baseline::PoseBuffer local(n), model(n);
    REQUIRE(baseline::sample(mode, clip, clip.duration, local));
    REQUIRE(baseline::local_to_model(mode, ch.skeleton, local, model));
    baseline::PaletteBuffer pal(mesh.joint_remap.size());
    REQUIRE(baseline::palette(mode, mesh.joint_remap, ib, model, pal));
    const MatrixPalette& matrices = pal.matrices;
    const DualQuatPalette& dual_quats = pal.dual_quats;
    const MotorPalette& motors = pal.motors;
    SkinnedOutput out;
    out.resize_for(mesh);
    SkinningJob job = make_skinning_job(method, mesh, out);
    job.matrices = matrices, job.dual_quats = dual_quats, job.motors = motors;
    REQUIRE(job.Run());
    int moved = 0, still = 0;
    for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
      const glm::vec3 rest(mesh.px[v], mesh.py[v], mesh.pz[v]), now(out.px[v], out.py[v], out.pz[v]);
      const std::string bone = ch.skeleton.names[mesh.joint_remap[mesh.joints[v][0]]];
      INFO("vertex " << v << " of " << bone << " at " << rest.x << " " << rest.y << " " << rest.z);
      if (bone == "joint2") {
        CHECK(glm::length(now - rest) > 0.5f);  // turned about z around (0, 1, 0): |x| = 0.5 goes onto y
        ++moved;
      } else {
        CHECK(glm::length(now - rest) < 1e-5f);  // joint1 is not animated; joint3 stays at its bind pose
        ++still;
      }
    }
    CHECK(moved > 0);
    CHECK(still > 0);
  }
}

TEST_CASE("an animation channel of a node the scene lacks is ignored with a warning (no mesh bones)") {
  const std::string x = R"(xof 0303txt 0032
Frame Root {
  FrameTransformMatrix {
    1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0;;
  }
  Frame Bone {
    FrameTransformMatrix {
      1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,0.0,0.0,1.0,0.0,0.0,1.0,0.0,1.0;;
    }
  }
}
AnimationSet Clip {
  Animation {
    { Bone }
    AnimationKey { 2; 2; 0;3;0.0,1.0,0.0;;, 10;3;0.0,2.0,0.0;;; }
  }
  Animation {
    { Ghost }
    AnimationKey { 2; 2; 0;3;0.0,1.0,0.0;;, 10;3;0.0,2.0,0.0;;; }
  }
}
)";
  const Character ch = load_character(temp_file("ghost.x", x));
  check_character(ch);
  CHECK(ch.skeleton.find("Bone") >= 0);
  CHECK(ch.skeleton.find("Ghost") < 0);
  bool named = false;
  for (const std::string& w : ch.warnings)
    if (w.find("'Ghost'") != std::string::npos) named = true;
  CHECK(named);
}

TEST_CASE("bad files throw LoadError naming the path") {
  SECTION("missing file") {
    const std::string p = "/nonexistent/dir/character.x";
    try {
      load_character(p);
      FAIL("no exception");
    } catch (const LoadError& e) {
      CHECK(std::string(e.what()).find(p) != std::string::npos);
    }
  }
  SECTION("a directory") {
    const std::string p = std::filesystem::temp_directory_path().string();
    try {
      load_character(p);
      FAIL("no exception");
    } catch (const LoadError& e) {
      CHECK(std::string(e.what()).find(p + ": cannot load character: is a directory") != std::string::npos);
    }
  }
  SECTION("truncated copy of a real .X file") {
    std::ifstream in(model("X/BCN_Epileptic.X"), std::ios::binary);
    std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    REQUIRE(bytes.size() > 1000);
    const std::string p = temp_file("truncated.x", bytes.substr(0, bytes.size() / 3));
    CHECK_THROWS_AS(load_character(p), LoadError);
  }
  SECTION("random bytes") {
    std::mt19937 rng(7);
    std::string bytes(4096, '\0');
    for (char& c : bytes) c = static_cast<char>(rng() & 0xff);
    const std::string p = temp_file("random.x", bytes);
    try {
      load_character(p);
      FAIL("no exception");
    } catch (const LoadError& e) {
      CHECK(std::string(e.what()).find(p) != std::string::npos);
    }
  }
  SECTION("a file without skeleton") {
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    CHECK_THROWS_AS(load_character(temp_file("noskel.obj", obj)), LoadError);
  }
}
