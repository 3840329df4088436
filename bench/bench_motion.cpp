// Motion extraction per root key, in ns: MotionExtractionJob (generated motor_from_trs, transform_point,
// motor_mul and motor_reverse) against the same extraction on TRS keys with quaternions (translation
// components, swing-twist yaw, remaining = yaw⁻¹ · (t − sel t), yaw⁻¹ · q), on 1024 random root keys.
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "cga/runtime/motion.hpp"
#include "cga/runtime/motor.hpp"
#include "summary.hpp"

namespace cga::bench {

namespace {

constexpr std::size_t kKeys = 1024;

const std::vector<Transform>& motion_keys() {
  static const std::vector<Transform> keys = [] {
    std::mt19937 gen(4242u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::vector<Transform> out(kKeys);
    for (Transform& x : out) {
      x.translation = 3.0f * glm::vec3(u(gen), u(gen), u(gen));
      x.rotation = glm::normalize(glm::quat(u(gen), u(gen), u(gen), u(gen)) + glm::quat(1e-3f, 0, 0, 0));
    }
    return out;
  }();
  return keys;
}

void bm_motion_cga(benchmark::State& state) {
  std::vector<Motor> root, track(kKeys), remaining(kKeys);
  for (const Transform& x : motion_keys()) root.push_back(motor_from_transform(x));
  MotionExtractionJob job;
  job.root = root, job.track = track, job.remaining = remaining;
  bool ok = true;
  for (auto _ : state) {
    ok &= job.Run();
    benchmark::DoNotOptimize(track.data());
    benchmark::DoNotOptimize(remaining.data());
    benchmark::ClobberMemory();
  }
  if (!ok) state.SkipWithError("MotionExtractionJob::Run returned false");
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kKeys));
}

void bm_motion_quaternion(benchmark::State& state) {
  const std::vector<Transform>& keys = motion_keys();
  std::vector<Transform> track(kKeys), remaining(kKeys);
  for (auto _ : state) {
    const glm::vec3 t0 = keys[0].translation;
    const glm::quat y0 = glm::normalize(glm::quat(keys[0].rotation.w, 0.0f, keys[0].rotation.y, 0.0f));
    for (std::size_t k = 0; k < kKeys; ++k) {
      const Transform& x = keys[k];
      const glm::vec3 d = x.translation - t0;
      const glm::vec3 sel(d.x, 0.0f, d.z);
      const glm::quat yaw = glm::normalize(glm::quat(x.rotation.w, 0.0f, x.rotation.y, 0.0f)) * glm::conjugate(y0);
      const glm::quat inv = glm::conjugate(yaw);
      track[k] = {sel, yaw, 1.0f};
      remaining[k] = {inv * (x.translation - sel), inv * x.rotation, x.scale};
    }
    benchmark::DoNotOptimize(track.data());
    benchmark::DoNotOptimize(remaining.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kKeys));
}

}  // namespace

void register_motion_benchmarks() {
  const std::string section = "Motion extraction, per root key (1024 random keys; x, z and yaw, first-frame reference)";
  benchmark::RegisterBenchmark("motion/extract/quaternion_reference", bm_motion_quaternion);
  benchmark::RegisterBenchmark("motion/extract/cga", bm_motion_cga);
  add_figure({"motion/extract/quaternion_reference", section, "TRS keys, quaternion twist (baseline)",
              Metric::ns_per_item, "", "", std::nullopt, {}});
  add_figure({"motion/extract/cga", section, "MotionExtractionJob (motors)", Metric::ns_per_item,
              "motion/extract/quaternion_reference", "quaternion", std::nullopt, {}});
}

}  // namespace cga::bench
