// Two-bone and aim IK per solve, in ns: TwoBoneIKJob / AimIKJob (generated CGA kernels: spheres, circle,
// pole plane and point pair; shortest-arc rotor) against the plain vector/quaternion solver of
// cga/testing/ik_reference.hpp (law of cosines, glm::rotation) on the same 1024 random chains, cycled.
// Both produce the local rotation corrections of the start and mid joints from model-space input.
// ChainIKJob (ik_chain_joint.clu's Jacobian columns, damped least squares) per solve, in µs, on 5-, 10- and
// 20-hinge chains with reachable random targets (cga/testing/chain_ik_cases.hpp: every hinge turned by up to
// pi; 64 per length, cycled), with the success rate (the job's reached flag: within 1e-4 of the chain
// length) and the mean trials per solve as counters. ChainIKBatchJob (the SIMD batch kernel fills every
// chain's columns) on a crowd of 256 chains of one 10-hinge rig, in ns per chain, against ChainIKJob run
// chain by chain on the same crowd.
#include <map>
#include <random>
#include <vector>

#include <benchmark/benchmark.h>

#include "bench_common.hpp"
#include "cga/runtime/ik.hpp"
#include "cga/runtime/ik_chain.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/testing/chain_ik_cases.hpp"
#include "cga/testing/ik_reference.hpp"
#include "summary.hpp"

namespace cga::bench {

namespace {

struct IkCase {
  Motor start, mid, end;  // model space
  glm::vec3 s, m, e;
  glm::quat qs, qm;
  glm::vec3 target, pole;
};

const std::vector<IkCase>& ik_cases() {
  static const std::vector<IkCase> cases = [] {
    std::mt19937 gen(31337u);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    const auto dir = [&] { return glm::normalize(glm::vec3(u(gen), u(gen), u(gen)) + glm::vec3(1e-3f)); };
    const auto rot = [&] { return glm::normalize(glm::quat(u(gen), u(gen), u(gen), u(gen)) + glm::quat(1e-3f, 0, 0, 0)); };
    std::vector<IkCase> out(1024);
    for (IkCase& c : out) {
      Transform root, mid, end;
      root.translation = 2.0f * glm::vec3(u(gen), u(gen), u(gen)), root.rotation = rot();
      mid.translation = (1.2f + 0.5f * u(gen)) * dir(), mid.rotation = rot();
      end.translation = (1.0f + 0.5f * u(gen)) * dir(), end.rotation = rot();
      c.start = motor_from_transform(root);
      c.mid = motor_mul(c.start, motor_from_transform(mid));
      c.end = motor_mul(c.mid, motor_from_transform(end));
      c.s = motor_transform_point(c.start, glm::vec3(0.0f));
      c.m = motor_transform_point(c.mid, glm::vec3(0.0f));
      c.e = motor_transform_point(c.end, glm::vec3(0.0f));
      c.qs = root.rotation, c.qm = root.rotation * mid.rotation;
      c.target = c.s + 2.0f * (0.5f + 0.5f * u(gen)) * dir();
      c.pole = dir();
    }
    return out;
  }();
  return cases;
}

// kPositions: the solves with the positions handed in (TwoBoneIKJob::positions), as the reference gets them;
// otherwise the job derives them from the joint motors.
template <bool kPositions>
void bm_two_bone_cga(benchmark::State& state) {
  const std::vector<IkCase>& cases = ik_cases();
  Motor c1, c2;
  bool reached = false;
  TwoBoneIKJob job;
  job.start_joint_correction = &c1, job.mid_joint_correction = &c2, job.reached = &reached;
  std::size_t i = 0, ok = 0;
  for (auto _ : state) {
    const IkCase& c = cases[i++ & 1023];
    const glm::vec3 positions[3] = {c.s, c.m, c.e};
    job.start_joint = &c.start, job.mid_joint = &c.mid, job.end_joint = &c.end;
    if constexpr (kPositions) job.positions = positions;
    job.target = c.target, job.pole_vector = c.pole;
    ok += job.Run();
    benchmark::DoNotOptimize(c1);
    benchmark::DoNotOptimize(c2);
  }
  if (ok != i) state.SkipWithError("TwoBoneIKJob::Run returned false");
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void bm_two_bone_reference(benchmark::State& state) {
  const std::vector<IkCase>& cases = ik_cases();
  std::size_t i = 0;
  for (auto _ : state) {
    const IkCase& c = cases[i++ & 1023];
    testing::TwoBoneReference r = testing::two_bone_reference(c.s, c.m, c.e, c.qs, c.qm, c.target, c.pole);
    benchmark::DoNotOptimize(r);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void bm_aim_cga(benchmark::State& state) {
  const std::vector<IkCase>& cases = ik_cases();
  Motor c1;
  AimIKJob job;
  job.joint_correction = &c1;
  std::size_t i = 0, ok = 0;
  for (auto _ : state) {
    const IkCase& c = cases[i++ & 1023];
    job.joint = &c.start, job.target = c.target, job.pole_vector = c.pole;
    ok += job.Run();
    benchmark::DoNotOptimize(c1);
  }
  if (ok != i) state.SkipWithError("AimIKJob::Run returned false");
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

void bm_aim_reference(benchmark::State& state) {
  const std::vector<IkCase>& cases = ik_cases();
  std::size_t i = 0;
  for (auto _ : state) {
    const IkCase& c = cases[i++ & 1023];
    glm::quat q = testing::aim_reference(c.s, c.qs, c.target, glm::vec3(1, 0, 0), glm::vec3(0, 1, 0), c.pole);
    benchmark::DoNotOptimize(q);
  }
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations()));
}

const std::vector<testing::ChainCase>& chain_cases(int joints) {
  static std::map<int, std::vector<testing::ChainCase>> cases;
  auto it = cases.find(joints);
  if (it != cases.end()) return it->second;
  testing::SeededRandom rng(2026u + static_cast<std::uint32_t>(joints));
  std::vector<testing::ChainCase> out;
  for (int i = 0; i < 64; ++i) out.push_back(testing::random_chain_case(rng, joints, false, 3.14159265f));
  return cases.emplace(joints, std::move(out)).first->second;
}

void bm_chain(benchmark::State& state, int joints) {
  const std::vector<testing::ChainCase>& cases = chain_cases(joints);
  std::vector<Motor> corrections(cases[0].local.size());
  bool reached = false;
  int trials = 0;
  ChainIKJob job;
  job.corrections = corrections, job.reached = &reached, job.iterations = &trials;
  std::size_t i = 0, ok = 0, hit = 0, total_trials = 0;
  for (auto _ : state) {
    const testing::ChainCase& c = cases[i++ & 63];
    job.joints = c.model, job.axes = c.axes, job.effector_offset = c.offset, job.target = c.target;
    ok += job.Run();
    hit += reached;
    total_trials += static_cast<std::size_t>(trials);
    benchmark::DoNotOptimize(corrections.data());
  }
  if (ok != i) state.SkipWithError("ChainIKJob::Run returned false");
  state.counters["success"] = i ? double(hit) / double(i) : 0.0;
  state.counters["trials"] = i ? double(total_trials) / double(i) : 0.0;
}

const testing::ChainCrowd& chain_crowd() {
  static const testing::ChainCrowd crowd = [] {
    testing::SeededRandom rng(77u);
    return testing::random_crowd(rng, 256, 10);
  }();
  return crowd;
}

// kBatch: one ChainIKBatchJob over the crowd; else ChainIKJob per chain. Items: chains.
template <bool kBatch>
void bm_chain_crowd(benchmark::State& state) {
  const testing::ChainCrowd& crowd = chain_crowd();
  const std::size_t chains = crowd.targets.size(), n = static_cast<std::size_t>(crowd.chain_joints);
  std::vector<Motor> out(crowd.joints.size());
  std::vector<std::uint8_t> reached(chains);
  std::vector<int> trials(chains);
  std::size_t ok = 0, runs = 0;
  for (auto _ : state) {
    if constexpr (kBatch) {
      ChainIKBatchJob job;
      job.chain_joints = crowd.chain_joints, job.joints = crowd.joints, job.axes = crowd.axes;
      job.effector_offset = crowd.offset, job.targets = crowd.targets, job.corrections = out;
      job.reached = reached, job.iterations = trials;
      ok += job.Run(), ++runs;
    } else {
      for (std::size_t c = 0; c < chains; ++c) {
        bool r = false;
        ChainIKJob job;
        job.joints = std::span<const Motor>(crowd.joints).subspan(c * n, n);
        job.axes = crowd.axes, job.effector_offset = crowd.offset, job.target = crowd.targets[c];
        job.corrections = std::span<Motor>(out).subspan(c * n, n), job.reached = &r, job.iterations = &trials[c];
        ok += job.Run(), ++runs;
        reached[c] = r;
      }
    }
    benchmark::DoNotOptimize(out.data());
  }
  if (ok != runs) state.SkipWithError("Run returned false");
  std::size_t hit = 0, total = 0;
  for (std::size_t c = 0; c < chains; ++c) hit += reached[c], total += static_cast<std::size_t>(trials[c]);
  state.counters["success"] = double(hit) / double(chains);
  state.counters["trials"] = double(total) / double(chains);
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * chains));
}

}  // namespace

void register_ik_benchmarks() {
  const std::string section = "IK, one solve (1024 random chains, cycled)";
  benchmark::RegisterBenchmark("ik/two_bone/cga", bm_two_bone_cga<false>);
  benchmark::RegisterBenchmark("ik/two_bone/cga_positions", bm_two_bone_cga<true>);
  benchmark::RegisterBenchmark("ik/two_bone/quaternion_reference", bm_two_bone_reference);
  benchmark::RegisterBenchmark("ik/aim/cga", bm_aim_cga);
  benchmark::RegisterBenchmark("ik/aim/quaternion_reference", bm_aim_reference);
  add_figure({"ik/two_bone/quaternion_reference", section, "two-bone, vector/quaternion reference",
              Metric::ns_per_item, "", "", std::nullopt, {}});
  add_figure({"ik/two_bone/cga", section, "two-bone, TwoBoneIKJob (ik_two_bone.clu)", Metric::ns_per_item,
              "ik/two_bone/quaternion_reference", "reference", Target{50.0, "<= 50 ns"}, {}});
  add_figure({"ik/two_bone/cga_positions", section, "two-bone, TwoBoneIKJob with positions given",
              Metric::ns_per_item, "ik/two_bone/quaternion_reference", "reference", Target{50.0, "<= 50 ns"}, {}});
  add_figure({"ik/aim/quaternion_reference", section, "aim, vector/quaternion reference", Metric::ns_per_item, "",
              "", std::nullopt, {}});
  add_figure({"ik/aim/cga", section, "aim, AimIKJob (ik_aim.clu)", Metric::ns_per_item, "ik/aim/quaternion_reference",
              "reference", std::nullopt, {}});
  const std::string chain_section = "Chain IK, one solve (ChainIKJob, 64 random reachable targets per length, cycled)";
  for (int joints : {5, 10, 20}) {
    const std::string name = "ik/chain/" + std::to_string(joints);
    benchmark::RegisterBenchmark(name.c_str(), bm_chain, joints)->Unit(benchmark::kMicrosecond);
    add_figure({name, chain_section,
                std::to_string(joints) + " hinges, ChainIKJob (ik_chain_joint.clu)", Metric::us_per_iter, "", "",
                std::nullopt, {"success", "trials"}});
  }
  const std::string crowd_section = "Chain IK, a crowd (256 chains of one 10-hinge rig), per chain";
  benchmark::RegisterBenchmark("ik/chain_crowd/single", bm_chain_crowd<false>)->Unit(benchmark::kMicrosecond);
  benchmark::RegisterBenchmark("ik/chain_crowd/batch", bm_chain_crowd<true>)->Unit(benchmark::kMicrosecond);
  add_figure({"ik/chain_crowd/single", crowd_section, "ChainIKJob per chain", Metric::ns_per_item, "", "",
              std::nullopt, {"success", "trials"}});
  add_figure({"ik/chain_crowd/batch", crowd_section, "ChainIKBatchJob (ik_chain_joint.simd.hpp)", Metric::ns_per_item,
              "ik/chain_crowd/single", "ChainIKJob per chain", std::nullopt, {"success", "trials"}});
}

}  // namespace cga::bench
