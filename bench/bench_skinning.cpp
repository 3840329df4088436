// Skinning throughput (vertices/s) of the runtime's SkinningJob per method, positions only and with
// normals: on a deterministic random mesh (1 M vertices, 64 bones, 4 influences; also at 64 K vertices, which
// stay in cache, and at 1 M in one 48-byte interleaved stride as engines store vertices) and on the real character
// BCN_Epileptic in a pose of its clip. Two plain GLM loops (no blocking, no hand SIMD: what a straightforward
// engine loop does) are measured beside them as references: what a plain loop gets.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <fmt/format.h>
#include <glm/gtx/dual_quaternion.hpp>

#include "bench_common.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/baselines/pose_jobs.hpp"
#include "cga/io/loader.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/simd_targets.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "summary.hpp"

namespace cga::bench {

namespace {

constexpr std::size_t kRandomVertices = 1u << 20;  // "1 M vertices"
constexpr std::size_t kCacheVertices = 1u << 16;   // "64 K vertices"
constexpr int kRandomBones = 64;
constexpr std::uint32_t kMeshSeed = 20240601;
constexpr std::uint32_t kPoseSeed = 7;

// A mesh with its palettes in every method's representation (rigid bones: dual quaternions hold no scale).
struct SkinScene {
  std::vector<SkinnedMesh> meshes;
  std::vector<MatrixPalette> matrices;
  std::vector<DualQuatPalette> dual_quats;
  std::vector<MotorPalette> motors;  // empty when this build has no generated kernels
  std::size_t vertices = 0;
};

void add_palettes(SkinScene& scene, std::size_t palette_size, std::uint32_t seed) {
  const auto pose = make_random_transforms(static_cast<int>(palette_size), seed, 1.0f, 0.0f);
  MatrixPalette m;
  DualQuatPalette d;
  MotorPalette mo;
  for (const Transform& x : pose) {
    m.push_back(to_skinning_matrix(x));
    d.push_back(to_dual_quat(x));
    mo.push_back(motor_from_transform(x));
  }
  scene.matrices.push_back(std::move(m));
  scene.dual_quats.push_back(std::move(d));
  scene.motors.push_back(std::move(mo));
}

SkinScene make_random_scene(std::size_t vertices) {
  SkinScene s;
  s.meshes.push_back(make_random_skinned_mesh(vertices, kRandomBones, kMeshSeed));
  s.vertices = vertices;
  add_palettes(s, kRandomBones, kPoseSeed);
  return s;
}

const SkinScene& random_scene() {
  static const SkinScene scene = make_random_scene(kRandomVertices);
  return scene;
}

// The same random mesh at 64 K vertices: inputs and outputs (2.6-4.5 MB) stay in this host's caches.
const SkinScene& random64k_scene() {
  static const SkinScene scene = make_random_scene(kCacheVertices);
  return scene;
}

// random1M's mesh as one interleaved buffer of EngineVertex; outputs x y z nx ny nz interleaved (24 bytes).
struct InterleavedScene {
  std::vector<EngineVertex> in;
  std::vector<float> out;
};

const InterleavedScene& interleaved_scene() {
  static const InterleavedScene scene = [] {
    InterleavedScene s;
    s.in = make_engine_vertices(random_scene().meshes.front());
    s.out.assign(6 * s.in.size(), 0.0f);
    return s;
  }();
  return scene;
}

void bm_skinning_interleaved(benchmark::State& state, SkinningMethod method, bool normals) {
  const SkinScene& scene = random_scene();
  InterleavedScene& il = const_cast<InterleavedScene&>(interleaved_scene());  // outputs only are written
  const std::size_t n = getenv("IL_N") ? std::size_t(atoi(getenv("IL_N"))) : il.in.size();
  SkinningJob job = make_engine_vertex_job(method, std::span<const EngineVertex>(il.in).first(n), il.out, normals);
  job.matrices = scene.matrices.front();
  job.dual_quats = scene.dual_quats.front();
  job.motors = scene.motors.front();
  if (const std::string error = job.ValidationError(); !error.empty()) {
    state.SkipWithError(error.c_str());
    return;
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(job.Run());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(n));
  state.SetLabel(std::to_string(n) + " vertices, 48-byte interleaved input");
}

// The palettes of every skinned mesh of `ch` in its first clip's pose at `time`, computed by the runtime's
// jobs (paper motors, GLM matrices, rigid dual quaternions). False when a job refuses its input.
bool add_pose_palettes(const Character& ch, float time, SkinScene& scene) {
  const Clip& clip = ch.clips.front();
  const std::size_t n = static_cast<std::size_t>(ch.skeleton.joint_count());
  scene.matrices.assign(scene.meshes.size(), {});
  scene.dual_quats.assign(scene.meshes.size(), {});
  scene.motors.assign(scene.meshes.size(), {});
  using baseline::PoseMode;
  for (PoseMode mode : {PoseMode::paper, PoseMode::glm_matrix, PoseMode::glm_dualquat}) {
    baseline::PoseBuffer local(n), model(n);
    if (!baseline::sample(mode, clip, time, local) || !baseline::local_to_model(mode, ch.skeleton, local, model))
      return false;
    for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
      const SkinnedMesh& mesh = scene.meshes[m];
      baseline::PaletteBuffer pal(mesh.joint_remap.size());
      if (!baseline::palette(mode, mesh.joint_remap, baseline::make_inverse_bind(mesh), model, pal)) return false;
      if (mode == PoseMode::paper) scene.motors[m] = pal.motors;
      if (mode == PoseMode::glm_matrix) scene.matrices[m] = pal.matrices;
      if (mode == PoseMode::glm_dualquat) scene.dual_quats[m] = pal.dual_quats;
    }
  }
  return true;
}

// The character's skinned meshes, posed at a third of its first clip by the runtime's jobs; a random rigid
// palette when the file has no clip or this build has no motor kernels (said in the benchmark's label).
struct CharacterScene {
  SkinScene scene;
  std::string palette;  // how the palette was made
};

const CharacterScene& character_scene_data() {
  static const std::unique_ptr<CharacterScene> data = [] {
    auto d = std::make_unique<CharacterScene>();
    const Character ch = load_character(models_dir() + "/" + kCharacter);
    for (const SkinnedMesh& mesh : ch.meshes) {
      if (mesh.joint_remap.empty()) continue;
      d->scene.meshes.push_back(mesh);
      d->scene.vertices += mesh.vertex_count();
    }
    if (d->scene.meshes.empty()) throw std::runtime_error(std::string(kCharacter) + " has no skinned mesh");
    const float time = ch.clips.empty() ? 0.0f : ch.clips.front().duration / 3.0f;
    if (!ch.clips.empty() && add_pose_palettes(ch, time, d->scene)) {
      d->palette = fmt::format("clip '{}' at t = {:.2f} s", ch.clips.front().name, time);
    } else {
      d->scene.matrices.clear();
      d->scene.dual_quats.clear();
      d->scene.motors.clear();
      std::uint32_t seed = kPoseSeed;
      for (const SkinnedMesh& mesh : d->scene.meshes) add_palettes(d->scene, mesh.joint_remap.size(), seed++);
      d->palette = "random rigid palette";
    }
    return d;
  }();
  return *data;
}

const SkinScene& character_scene() { return character_scene_data().scene; }

// One SkinningJob per mesh, outputs owned here.
struct Jobs {
  std::vector<SkinnedOutput> outputs;
  std::vector<SkinningJob> jobs;
};

Jobs make_jobs(const SkinScene& scene, SkinningMethod method, bool normals) {
  Jobs j;
  j.outputs.resize(scene.meshes.size());
  for (std::size_t m = 0; m < scene.meshes.size(); ++m) {
    SkinningJob job = make_skinning_job(method, scene.meshes[m], j.outputs[m]);
    if (!normals) {
      job.in_nx = job.in_ny = job.in_nz = {};
      job.out_nx = job.out_ny = job.out_nz = {};
    }
    job.matrices = scene.matrices[m];
    job.dual_quats = scene.dual_quats[m];
    job.motors = scene.motors[m];
    j.jobs.push_back(job);
  }
  return j;
}

// What SkinningJob runs: its default (the generated batch kernels, the CPU's best instruction set) or the
// generated scalar loop.
enum class Path { best, scalar };

// target: the batch path pinned to that instruction set (ScopedSimdTarget), else the CPU's best.
void bm_skinning(benchmark::State& state, const SkinScene& (*scene_fn)(), SkinningMethod method, bool normals,
                 Path path, std::optional<SimdTarget> target) {
  const SkinScene* scene = nullptr;
  try {
    scene = &scene_fn();
  } catch (const std::exception& e) {
    state.SkipWithError(e.what());
    return;
  }
  if (normals && !scene->meshes.front().has_normals()) {
    state.SkipWithError("the mesh has no normals");
    return;
  }
  Jobs jobs = make_jobs(*scene, method, normals);
  for (SkinningJob& job : jobs.jobs) {
    job.use_simd = path != Path::scalar;
  }
  for (const SkinningJob& job : jobs.jobs)
    if (const std::string error = job.ValidationError(); !error.empty()) {
      state.SkipWithError(error.c_str());
      return;
    }
  std::optional<ScopedSimdTarget> pin;
  if (target) pin.emplace(*target);
  for (auto _ : state) {
    bool ok = true;
    for (const SkinningJob& job : jobs.jobs) ok &= job.Run();
    benchmark::DoNotOptimize(ok);
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(scene->vertices));
  std::string label = std::to_string(scene->vertices) + " vertices";
  if (scene_fn == character_scene) label += ", " + character_scene_data().palette;
  state.SetLabel(label);
}

// The plain GLM loops: per vertex, blend and apply with GLM types, array-of-structs palette, no blocking.
void plain_glm_lbs(const SkinnedMesh& mesh, const MatrixPalette& pal, bool normals, SkinnedOutput& out) {
  const std::size_t n = mesh.vertex_count();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& j = mesh.joints[i];
    const auto& w = mesh.weights[i];
    const glm::mat3x4 m = pal[j[0]] * w[0] + pal[j[1]] * w[1] + pal[j[2]] * w[2] + pal[j[3]] * w[3];
    const glm::vec4 p(mesh.px[i], mesh.py[i], mesh.pz[i], 1.0f);
    out.px[i] = glm::dot(m[0], p);
    out.py[i] = glm::dot(m[1], p);
    out.pz[i] = glm::dot(m[2], p);
    if (normals) {
      const glm::vec3 nv(mesh.nx[i], mesh.ny[i], mesh.nz[i]);
      const glm::vec3 r = glm::normalize(
          glm::vec3(glm::dot(glm::vec3(m[0]), nv), glm::dot(glm::vec3(m[1]), nv), glm::dot(glm::vec3(m[2]), nv)));
      out.nx[i] = r.x;
      out.ny[i] = r.y;
      out.nz[i] = r.z;
    }
  }
}

void plain_glm_dqs(const SkinnedMesh& mesh, const DualQuatPalette& pal, bool normals, SkinnedOutput& out) {
  const std::size_t n = mesh.vertex_count();
  for (std::size_t i = 0; i < n; ++i) {
    const auto& j = mesh.joints[i];
    const auto& w = mesh.weights[i];
    const glm::dualquat& q0 = pal[j[0]];
    glm::quat real = q0.real * w[0];
    glm::quat dual = q0.dual * w[0];
    for (int k = 1; k < 4; ++k) {
      const glm::dualquat& q = pal[j[k]];
      const float wk = glm::dot(q0.real, q.real) < 0.0f ? -w[k] : w[k];
      real = real + q.real * wk;
      dual = dual + q.dual * wk;
    }
    const glm::dualquat b = glm::normalize(glm::dualquat(real, dual));
    const glm::vec3 p = b * glm::vec3(mesh.px[i], mesh.py[i], mesh.pz[i]);
    out.px[i] = p.x;
    out.py[i] = p.y;
    out.pz[i] = p.z;
    if (normals) {
      const glm::vec3 r = b.real * glm::vec3(mesh.nx[i], mesh.ny[i], mesh.nz[i]);
      out.nx[i] = r.x;
      out.ny[i] = r.y;
      out.nz[i] = r.z;
    }
  }
}

enum class PlainLoop { lbs, dqs };

void bm_plain_glm(benchmark::State& state, PlainLoop loop, bool normals) {
  const SkinScene& scene = random_scene();
  const SkinnedMesh& mesh = scene.meshes.front();
  SkinnedOutput out;
  out.resize_for(mesh);
  for (auto _ : state) {
    if (loop == PlainLoop::lbs)
      plain_glm_lbs(mesh, scene.matrices.front(), normals, out);
    else
      plain_glm_dqs(mesh, scene.dual_quats.front(), normals, out);
    benchmark::DoNotOptimize(out.px.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(mesh.vertex_count()));
}

// Performance targets (positions / with normals) per method.
std::optional<Target> target_for(SkinningMethod m, bool normals) {
  if (m == SkinningMethod::cga_points)
    return normals ? Target{235, ">= 235 M/s"} : Target{300, ">= 300 M/s"};
  if (m == SkinningMethod::cga_motors)
    return normals ? Target{120, ">= 120 M/s"} : Target{150, ">= 150 M/s"};
  return std::nullopt;
}

}  // namespace

void register_skinning_benchmarks() {
  struct Scene {
    const char* key;
    const SkinScene& (*fn)();
    const char* title;
  };
  const Scene scenes[] = {
      {"random1M", random_scene, "1 M random vertices, 64 bones, 4 influences"},
      {"random64K", random64k_scene, "64 K random vertices (cache-resident), 64 bones, 4 influences"},
      {"BCN_Epileptic", character_scene, "BCN_Epileptic.X meshes, posed by the runtime's jobs"},
  };
  for (const Scene& sc : scenes)
    for (bool normals : {false, true}) {
      const std::string kind = normals ? "positions+normals" : "positions";
      const std::string section = "Skinning, " + kind + ": " + sc.title;
      const std::string prefix = std::string("skinning/") + sc.key + "/" + kind + "/";
      const std::string baseline = prefix + "lbs";
      for (SkinningMethod m : kAllSkinningMethods) {
        const std::string name = prefix + std::string(to_string(m));
        benchmark::RegisterBenchmark(name.c_str(), bm_skinning, sc.fn, m, normals, Path::best, std::nullopt)
            ->Unit(benchmark::kMillisecond);
        add_figure({name, section, std::string(to_string(m)), Metric::mega_items_per_s, baseline, "lbs",
                    sc.fn == random_scene ? target_for(m, normals) : std::nullopt, {}});
      }
      // The A/B of the paths, 1 M vertices: every method on the batch path pinned to each instruction set of
      // the machine but the best (NAME@TARGET), and on the generated scalar loop (use_simd = false).
      if (sc.fn == random_scene)
        for (SkinningMethod m : kAllSkinningMethods) {
          const std::vector<SimdTarget> targets = simd_targets();
          for (std::size_t t = 1; t < targets.size(); ++t) {
            const std::string name = prefix + std::string(to_string(m)) + "@" + targets[t].name;
            benchmark::RegisterBenchmark(name.c_str(), bm_skinning, sc.fn, m, normals, Path::best, targets[t])
                ->Unit(benchmark::kMillisecond);
            add_figure({name, section, std::string(to_string(m)) + ", batch path on " + targets[t].name,
                        Metric::mega_items_per_s, prefix + std::string(to_string(m)), std::string(to_string(m)),
                        std::nullopt, {}});
          }
          const std::string name = prefix + std::string(to_string(m)) + "-generated";
          benchmark::RegisterBenchmark(name.c_str(), bm_skinning, sc.fn, m, normals, Path::scalar, std::nullopt)
              ->Unit(benchmark::kMillisecond);
          add_figure({name, section, std::string(to_string(m)) + ", generated scalar loop", Metric::mega_items_per_s,
                      prefix + std::string(to_string(m)), std::string(to_string(m)), std::nullopt, {}});
        }
      if (sc.fn != random_scene) continue;
      for (SkinningMethod m : kAllSkinningMethods) {
        const std::string name = std::string("skinning/interleaved1M/") + kind + "/" + std::string(to_string(m));
        benchmark::RegisterBenchmark(name.c_str(), bm_skinning_interleaved, m, normals)->Unit(benchmark::kMillisecond);
        add_figure({name, "Skinning, " + kind + ": 1 M random vertices in one 48-byte interleaved stride",
                    std::string(to_string(m)), Metric::mega_items_per_s, "skinning/interleaved1M/" + kind + "/lbs",
                    "lbs", std::nullopt, {}});
      }
      for (PlainLoop loop : {PlainLoop::lbs, PlainLoop::dqs}) {
        const std::string label = loop == PlainLoop::lbs ? "plain GLM lbs loop" : "plain GLM dqs loop";
        const std::string name = prefix + (loop == PlainLoop::lbs ? "plain_glm_lbs" : "plain_glm_dqs");
        benchmark::RegisterBenchmark(name.c_str(), bm_plain_glm, loop, normals)
            ->Unit(benchmark::kMillisecond);
        add_figure({name, section, label, Metric::mega_items_per_s, baseline, "lbs", std::nullopt, {}});
      }
    }
}

}  // namespace cga::bench
