// One full pose of the 54-joint character BCN_Epileptic per interpolation mode, in µs: sample two clips,
// cross-fade them, local-to-model down the hierarchy, and the skinning palette (model x inverse bind) of
// every skinned mesh. The file has a single clip, so the two "clips" are two time ranges of it (t and
// t + duration/2), which costs the same. Time advances by 1/60 s per iteration, so the key search sees
// every part of the clip. The baseline is the GLM matrix mode (quaternion slerp + TRS matrices).
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>

#include "bench_common.hpp"
#include "cga/runtime/additive.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/baselines/pose_jobs.hpp"
#include "cga/io/loader.hpp"
#include "summary.hpp"

namespace cga::bench {

namespace {

constexpr float kCrossFade = 0.35f;  // weight of the second layer
constexpr float kFrame = 1.0f / 60.0f;

struct PoseScene {
  Character character;
  std::vector<baseline::InverseBind> inverse_binds;  // per skinned mesh
  std::size_t palette_entries = 0;
};

const PoseScene& pose_scene() {
  static const std::unique_ptr<PoseScene> scene = [] {
    auto s = std::make_unique<PoseScene>();
    s->character = load_character(models_dir() + "/" + kCharacter);
    if (s->character.clips.empty()) throw std::runtime_error(std::string(kCharacter) + " has no clip");
    for (const SkinnedMesh& mesh : s->character.meshes) {
      s->inverse_binds.push_back(baseline::make_inverse_bind(mesh));
      s->palette_entries += mesh.joint_remap.size();
    }
    return s;
  }();
  return *scene;
}

struct PaletteBuffers {
  std::vector<Motor> motors;
  std::vector<glm::mat3x4> matrices;
  std::vector<glm::dualquat> dual_quats;
  explicit PaletteBuffers(std::size_t n) : motors(n), matrices(n), dual_quats(n) {}
};

void bm_pose(benchmark::State& state, baseline::PoseMode mode, bool partial) {
  const PoseScene* scene = nullptr;
  try {
    scene = &pose_scene();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  const Character& ch = scene->character;
  const Clip& clip_a = ch.clips[0];
  const Clip& clip_b = ch.clips.size() > 1 ? ch.clips[1] : ch.clips[0];
  const std::size_t joints = static_cast<std::size_t>(ch.skeleton.joint_count());
  baseline::PoseBuffer a(joints), b(joints), blended(joints), model(joints);
  std::vector<PaletteBuffers> palettes;
  for (const SkinnedMesh& mesh : ch.meshes) palettes.emplace_back(mesh.joint_remap.size());

  // One representation's jobs per mode: the runtime's motor jobs, or the GLM baselines'.
  using namespace baseline;
  // The motor jobs run in motor modes only; for a GLM mode they are made (with any motor mode) but not run.
  const Interpolation motor_mode = uses_motors(mode) ? to_interpolation(mode) : Interpolation::paper;
  SamplingJob motor_a{&clip_a, 0.0f, motor_mode, a.motors}, motor_b{&clip_b, 0.0f, motor_mode, b.motors};
  // Partial blending: the second layer weighs 1 on the second half of the joints, 0.3 on the first.
  std::vector<float> mask(joints, 1.0f);
  for (std::size_t j = 0; j < joints / 2; ++j) mask[j] = 0.3f;
  const BlendLayer motor_layers[2] = {{1.0f - kCrossFade, a.motors},
                                      {kCrossFade, b.motors, partial ? std::span<const float>(mask) : std::span<const float>()}};
  const BlendingJob motor_blend{motor_mode, motor_layers, blended.motors};
  const LocalToModelJob motor_model{&ch.skeleton, blended.motors, model.motors};
  std::vector<SkinningPaletteJob> motor_palettes;
  TransformSamplingJob trs_a{&clip_a, 0.0f, a.transforms}, trs_b{&clip_b, 0.0f, b.transforms};
  const TransformLayer trs_layers[2] = {{1.0f - kCrossFade, a.transforms}, {kCrossFade, b.transforms}};
  const TransformBlendingJob trs_blend{trs_layers, blended.transforms};
  const MatrixLocalToModelJob matrix_model{&ch.skeleton, blended.transforms, model.matrices};
  std::vector<MatrixPaletteJob> matrix_palettes;
  DualQuatSamplingJob dq_a{&clip_a, 0.0f, a.dual_quats, a.scales}, dq_b{&clip_b, 0.0f, b.dual_quats, b.scales};
  const DualQuatLayer dq_layers[2] = {{1.0f - kCrossFade, a.dual_quats, a.scales},
                                      {kCrossFade, b.dual_quats, b.scales}};
  const DualQuatBlendingJob dq_blend{dq_layers, blended.dual_quats, blended.scales};
  const DualQuatLocalToModelJob dq_model{&ch.skeleton, blended.dual_quats, blended.scales, model.dual_quats,
                                         model.scales};
  std::vector<DualQuatPaletteJob> dq_palettes;
  for (std::size_t m = 0; m < ch.meshes.size(); ++m) {
    const baseline::InverseBind& ib = scene->inverse_binds[m];
    motor_palettes.push_back({ch.meshes[m].joint_remap, ib.motors, model.motors, palettes[m].motors});
    matrix_palettes.push_back({ch.meshes[m].joint_remap, ib.matrices, model.matrices, palettes[m].matrices});
    dq_palettes.push_back({ch.meshes[m].joint_remap, ib.dual_quats, model.dual_quats, model.scales,
                           palettes[m].dual_quats});
  }
  const auto run_pose = [&](float ta, float tb) {
    bool ok = true;
    if (mode == PoseMode::glm_matrix) {
      trs_a.time = ta, trs_b.time = tb;
      ok = trs_a.Run() && trs_b.Run() && trs_blend.Run() && matrix_model.Run();
      for (const MatrixPaletteJob& job : matrix_palettes) ok &= job.Run();
    } else if (mode == PoseMode::glm_dualquat) {
      dq_a.time = ta, dq_b.time = tb;
      ok = dq_a.Run() && dq_b.Run() && dq_blend.Run() && dq_model.Run();
      for (const DualQuatPaletteJob& job : dq_palettes) ok &= job.Run();
    } else {
      motor_a.time = ta, motor_b.time = tb;
      ok = motor_a.Run() && motor_b.Run() && motor_blend.Run() && motor_model.Run();
      for (const SkinningPaletteJob& job : motor_palettes) ok &= job.Run();
    }
    return ok;
  };

  const float duration_a = clip_a.duration > 0 ? clip_a.duration : 1.0f;
  const float duration_b = clip_b.duration > 0 ? clip_b.duration : 1.0f;
  float t = 0.0f;
  bool ok = true;
  for (auto _ : state) {
    ok &= run_pose(std::fmod(t, duration_a), std::fmod(t + 0.5f * duration_b, duration_b));
    benchmark::DoNotOptimize(palettes.front().motors.data());
    benchmark::DoNotOptimize(palettes.front().matrices.data());
    benchmark::ClobberMemory();
    t += kFrame;
    if (t > 1e4f) t = 0.0f;  // keep the float time precise over long runs
  }
  if (!ok) {
    state.SkipWithError("a pose job refused its input (Run() returned false)");
    return;
  }
  state.SetLabel(fmt::format("{} joints, {} palette entries", joints, scene->palette_entries));
  state.counters["joints"] = static_cast<double>(joints);
}

// An additive layer (weight 0.6) on a 54-joint base pose, both random rigid motors: the screw weighting
// (motor log/exp per joint) against the normalized lerp toward the identity.
void bm_additive(benchmark::State& state, Interpolation mode) {
  constexpr std::size_t kJoints = 54;
  std::vector<Motor> base(kJoints), delta(kJoints), out(kJoints);
  for (std::size_t j = 0; j < kJoints; ++j) {
    const float a = 0.1f * static_cast<float>(j);
    Transform x, y;
    x.rotation = glm::angleAxis(a, glm::normalize(glm::vec3(1.0f, a, 2.0f)));
    x.translation = glm::vec3(a, 1.0f, -a);
    y.rotation = glm::angleAxis(0.5f + a, glm::normalize(glm::vec3(a, 1.0f, 0.5f)));
    y.translation = glm::vec3(0.2f, -a, 0.3f);
    base[j] = motor_from_transform(x), delta[j] = motor_from_transform(y);
  }
  const AdditiveLayer layers[1] = {{0.6f, delta}};
  const AdditiveBlendingJob job{mode, base, layers, out};
  bool ok = true;
  for (auto _ : state) {
    ok &= job.Run();
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  if (!ok) state.SkipWithError("AdditiveBlendingJob::Run returned false");
}

}  // namespace

void register_pose_benchmarks() {
  const std::string section = "Pose of BCN_Epileptic (54 joints): sample 2 clips + cross-fade + hierarchy + palette";
  const std::string baseline = "pose/glm-matrix";
  for (baseline::PoseMode mode : baseline::kAllPoseModes) {
    const std::string name = "pose/" + std::string(to_string(mode));
    benchmark::RegisterBenchmark(name.c_str(), bm_pose, mode, false)->Unit(benchmark::kMicrosecond);
    const bool ours = baseline::uses_motors(mode);
    add_figure({name, section, std::string(to_string(mode)) + (ours ? "" : " (baseline)"), Metric::us_per_iter,
                baseline, "glm-matrix", ours ? std::optional<Target>(Target{1.0, "<= 1.0 µs"}) : std::nullopt,
                {}});
  }
  // Additive layer weighting, screw (exp(w log Δ)) vs nlerp toward the identity.
  const std::string additive = "Additive layer on 54 joints (weight 0.6)";
  for (Interpolation mode : {Interpolation::screw, Interpolation::nlerp}) {
    const std::string name = "pose/additive-" + std::string(to_string(mode));
    benchmark::RegisterBenchmark(name.c_str(), bm_additive, mode)->Unit(benchmark::kMicrosecond);
    add_figure({name, additive, std::string(to_string(mode)) + " weighting", Metric::us_per_iter,
                mode == Interpolation::nlerp ? "" : "pose/additive-nlerp", "nlerp", std::nullopt, {}});
  }
  // Partial blending (per-joint weights on the second layer): the per-joint path of BlendingJob.
  for (Interpolation mode : {Interpolation::paper, Interpolation::nlerp}) {
    const std::string name = "pose/" + std::string(to_string(mode)) + "-partial";
    benchmark::RegisterBenchmark(name.c_str(), bm_pose, baseline::to_pose_mode(mode), true)->Unit(benchmark::kMicrosecond);
    add_figure({name, section, std::string(to_string(mode)) + ", per-joint weights", Metric::us_per_iter, baseline,
                "glm-matrix", std::nullopt, {}});
  }
}

}  // namespace cga::bench
