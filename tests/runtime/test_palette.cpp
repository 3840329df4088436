// Hierarchy and palettes: on every key frame of BCN_Epileptic and Testwuson, the motor palette (local motors
// composed by the generated motor product, times the inverse bind motor) moves the mesh vertices where the
// GLM matrix palette moves them, within 1e-5 of the character's size; the dual-quaternion palette agrees on
// these scale-free characters too.
#include <catch2/catch.hpp>

#include <random>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/io/loader.hpp"
#include "cga/testing/nan_max.hpp"

using namespace cga;

namespace {

std::string model(const char* rel) { return std::string(CGA_MODELS_DIR) + "/" + rel; }

glm::vec3 apply(const glm::mat3x4& m, const glm::vec3& p) {
  return {glm::dot(m[0], glm::vec4(p, 1.0f)), glm::dot(m[1], glm::vec4(p, 1.0f)), glm::dot(m[2], glm::vec4(p, 1.0f))};
}

struct Palettes {
  MotorPalette motors;
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
};

// Samples `clip` at t in `mode`, runs the hierarchy and the palette of `mesh`.
void pose_palette(const Character& ch, const Clip& clip, float t, baseline::PoseMode mode, const SkinnedMesh& mesh,
                  const baseline::InverseBind& ib, baseline::PoseBuffer& local, baseline::PoseBuffer& model_pose,
                  Palettes& out) {
  REQUIRE(baseline::sample(mode, clip, t, local));
  REQUIRE(baseline::local_to_model(mode, ch.skeleton, local, model_pose));
  baseline::PaletteBuffer pal(mesh.joint_remap.size());
  REQUIRE(baseline::palette(mode, mesh.joint_remap, ib, model_pose, pal));
  out.motors = std::move(pal.motors);
  out.matrices = std::move(pal.matrices);
  out.dual_quats = std::move(pal.dual_quats);
}

}  // namespace

TEST_CASE("motor palette equals matrix palette on every key frame") {
  for (const char* file : {"X/BCN_Epileptic.X", "X/Testwuson.X"}) {
    const Character ch = load_character(model(file));
    const float size = character_size(ch);
    const float tol = 1e-5f * size;
    const std::size_t n = ch.skeleton.joint_count();
    baseline::PoseBuffer local(n), model_pose(n);
    Palettes cga_pal, glm_pal, dq_pal;
    for (const SkinnedMesh& mesh : ch.meshes) {
      const baseline::InverseBind ib = baseline::make_inverse_bind(mesh);
      for (const Clip& clip : ch.clips) {
        // Every key time of any joint of the clip.
        std::vector<float> times;
        for (const JointKeys& k : clip.keys) times.insert(times.end(), k.times.begin(), k.times.end());
        std::sort(times.begin(), times.end());
        times.erase(std::unique(times.begin(), times.end()), times.end());
        INFO(file << " mesh " << mesh.name << " clip " << clip.name << ", " << times.size() << " key times");
        float worst = 0.0f, worst_dq = 0.0f;
        for (float t : times) {
          pose_palette(ch, clip, t, baseline::PoseMode::paper, mesh, ib, local, model_pose, cga_pal);
          pose_palette(ch, clip, t, baseline::PoseMode::glm_matrix, mesh, ib, local, model_pose, glm_pal);
          pose_palette(ch, clip, t, baseline::PoseMode::glm_dualquat, mesh, ib, local, model_pose, dq_pal);
          std::vector<glm::mat3x4> from_motors(cga_pal.motors.size());
          for (std::size_t k = 0; k < from_motors.size(); ++k) from_motors[k] = motor_matrix(cga_pal.motors[k]);
          for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
            const glm::vec3 p(mesh.px[v], mesh.py[v], mesh.pz[v]);
            for (int i = 0; i < 4; ++i) {
              if (mesh.weights[v][i] == 0.0f) continue;
              const std::size_t k = mesh.joints[v][i];
              const glm::vec3 ref = apply(glm_pal.matrices[k], p);
              worst = testing::nan_max(worst, glm::length(apply(from_motors[k], p) - ref));
              worst = testing::nan_max(worst, glm::length(motor_transform_point(cga_pal.motors[k], p) - ref));
              const glm::dualquat& q = dq_pal.dual_quats[k];
              worst_dq = testing::nan_max(worst_dq, glm::length(q.real * p + baseline::dual_quat_translation(q) - ref));
            }
          }
        }
        INFO("worst motor error " << worst << ", dual quaternion " << worst_dq << ", tolerance " << tol);
        CHECK(worst <= tol);
        CHECK(worst_dq <= tol);
      }
    }
  }
}

TEST_CASE("hierarchy and palette: rigid fast paths and mixed scaled joints equal chains of motor_mul") {
  // Four joints (0 <- 1 <- 2, 0 <- 3) with a scale on joint 2 only in the second round: the jobs then take the
  // 12-blade product for that branch and the rigid one elsewhere; both must equal plain motor_mul chains.
  Skeleton sk;
  sk.names = {"root", "a", "b", "c"};
  sk.parents = {-1, 0, 1, 0};
  sk.rest_local.resize(4);
  std::mt19937 rng(21);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  for (bool scaled : {false, true}) {
    INFO("scaled " << scaled);
    std::vector<Motor> local(4), model(4), palette(3), want_model(4);
    for (int j = 0; j < 4; ++j) {
      Transform x;
      x.translation = glm::vec3(u(rng), u(rng), u(rng));
      x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
      x.scale = scaled && j == 2 ? 1.7f : 1.0f;
      local[j] = motor_from_transform(x);
    }
    LocalToModelJob l2m;
    l2m.skeleton = &sk, l2m.input = local, l2m.output = model;
    REQUIRE(l2m.Run());
    for (int j = 0; j < 4; ++j) {
      want_model[j] = sk.parents[j] < 0 ? local[j] : motor_mul(want_model[sk.parents[j]], local[j]);
      for (int c = 0; c < 12; ++c) REQUIRE(model[j].c[c] == Approx(want_model[j].c[c]).margin(1e-5));
    }
    std::vector<Motor> ib;
    const std::vector<int> remap = {3, 2, 1};
    for (int k = 0; k < 3; ++k) {
      Transform x;
      x.translation = glm::vec3(u(rng), u(rng), u(rng));
      x.scale = k == 0 ? 0.5f : 1.0f;  // one scaled inverse bind
      ib.push_back(motor_from_transform(x));
    }
    SkinningPaletteJob pal;
    pal.joint_remap = remap, pal.inverse_bind = ib, pal.model = model, pal.output = palette;
    REQUIRE(pal.Run());
    for (int k = 0; k < 3; ++k) {
      const Motor want = motor_mul(model[remap[k]], ib[k]);
      for (int c = 0; c < 12; ++c) REQUIRE(palette[k].c[c] == Approx(want.c[c]).margin(1e-5));
    }
  }
}

TEST_CASE("joints are ordered breadth-first with parents first") {
  for (const char* file : {"X/BCN_Epileptic.X", "X/Testwuson.X", "BVH/01_01.bvh"}) {
    const Character ch = load_character(model(file), {});
    const Skeleton& sk = ch.skeleton;
    std::vector<int> depth(sk.joint_count());
    for (int j = 0; j < sk.joint_count(); ++j) {
      REQUIRE(sk.parents[j] < j);
      depth[j] = sk.parents[j] < 0 ? 0 : depth[sk.parents[j]] + 1;
      if (j > 0) CHECK(depth[j] >= depth[j - 1]);
    }
  }
}

TEST_CASE("palette: blocks of 8 rigid entries (structure of arrays) and their remainders equal motor_mul per entry") {
  // 1..27 entries cover no block, whole blocks of 8 and every remainder; the remap gathers model motors in
  // any order (repeats included). A non-rigid entry in the model or the inverse binds sends the whole run
  // to the per-entry loop, which must agree too.
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::uniform_int_distribution<int> pick(0, 29);
  auto random_motor = [&](float scale) {
    Transform x;
    x.translation = glm::vec3(u(rng), u(rng), u(rng)) * 2.0f;
    x.rotation = glm::normalize(glm::quat(u(rng), u(rng), u(rng), u(rng)));
    x.scale = scale;
    return motor_from_transform(x);
  };
  std::vector<Motor> model(30);
  for (Motor& m : model) m = random_motor(1.0f);
  for (int variant = 0; variant < 3; ++variant) {  // all rigid; one scaled model motor; one scaled inverse bind
    for (std::size_t n = 1; n <= 27; ++n) {
      INFO("variant " << variant << ", " << n << " entries");
      std::vector<int> remap(n);
      for (int& r : remap) r = pick(rng);
      std::vector<Motor> ib;
      for (std::size_t k = 0; k < n; ++k) ib.push_back(random_motor(variant == 2 && k == n / 2 ? 0.6f : 1.0f));
      std::vector<Motor> m = model;
      if (variant == 1) m[remap[n - 1]] = random_motor(1.4f);
      std::vector<Motor> palette(n);
      SkinningPaletteJob pal;
      pal.joint_remap = remap, pal.inverse_bind = ib, pal.model = m, pal.output = palette;
      REQUIRE(pal.Run());
      for (std::size_t k = 0; k < n; ++k) {
        const Motor want = motor_mul(m[remap[k]], ib[k]);
        for (int c = 0; c < 12; ++c) REQUIRE(palette[k].c[c] == Approx(want.c[c]).margin(1e-5));
        if (motor_is_rigid(m[remap[k]]) && motor_is_rigid(ib[k])) REQUIRE(motor_is_rigid(palette[k]));
      }
    }
  }
}
