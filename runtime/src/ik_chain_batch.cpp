// ChainIKBatchJob (see ik_chain.hpp): many chains of one rig solved in lockstep by ChainIKJob's solver
// (detail/ik_chain_solver.hpp). Per iteration one call of ik_chain_joint's SIMD batch kernel
// (ik_chain_joint.simd.hpp, the simd target; Highway picks the instruction set at run time; without
// orientation targets ik_chain_joint_position's, the effector's derivative alone) computes the
// Jacobian columns of every chain still iterating: element i is one column, its joint's posed motor
// gathered through an index stream, its axis and the chain's effector and frame axes likewise.
#define CGAGEN_SIMD_DISPATCH
// Before Highway's first header: the generated kernels take arrays of vectors, which sizeless vectors (SVE,
// RVV) cannot be elements of.
#define HWY_DISABLED_TARGETS (HWY_SVE | HWY_SVE2 | HWY_SVE_256 | HWY_SVE2_128 | HWY_RVV)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "ik_chain_batch_kernels.hpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep

#include <ik_chain_batch_kernels.hpp>

#include "cga/runtime/ik_chain.hpp"
#include "detail/ik_chain_solver.hpp"

namespace cga {

namespace {

// The job of chain c (spans into the batch's arrays); reached and iterations are written by Run().
ChainIKJob chain_job(const ChainIKBatchJob& b, std::size_t c) {
  const std::size_t n = static_cast<std::size_t>(b.chain_joints);
  ChainIKJob job;
  job.joints = b.joints.subspan(c * n, n);
  job.axes = b.axes, job.min_angles = b.min_angles, job.max_angles = b.max_angles;
  job.effector_offset = b.effector_offset;
  job.target = b.targets[c];
  job.target_orientation = b.target_orientations.empty() ? nullptr : &b.target_orientations[c];
  job.orientation_weight = b.orientation_weight, job.weight = b.weight, job.max_iterations = b.max_iterations;
  job.tolerance = b.tolerance, job.orientation_tolerance = b.orientation_tolerance, job.damping = b.damping;
  job.corrections = b.corrections.subspan(c * n, n);
  return job;
}

// Clears the upper halves of the vector registers after the batch kernel, before the solve's scalar SSE
// code: left dirty by the AVX2 / AVX-512 kernel, they made the rest of the solve (forward kinematics, the
// normal equations) about 1.4x slower here (a 256-chain crowd, AMD EPYC VM: 8.3 against 6.1 us per chain).
inline void clear_upper_state() {
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx) __asm__ volatile("vzeroupper" ::: "memory");
#endif
}

}  // namespace

bool ChainIKBatchJob::Validate() const {
  if (chain_joints < 1 || joints.empty() || joints.size() % static_cast<std::size_t>(chain_joints) != 0) return false;
  const std::size_t chains = joints.size() / static_cast<std::size_t>(chain_joints);
  if (targets.size() != chains || corrections.size() != joints.size()) return false;
  if (!target_orientations.empty() && target_orientations.size() != chains) return false;
  if ((!reached.empty() && reached.size() != chains) || (!iterations.empty() && iterations.size() != chains))
    return false;
  for (std::size_t c = 0; c < chains; ++c)
    if (!chain_job(*this, c).Validate()) return false;
  return true;
}

bool ChainIKBatchJob::Run() const {
  if (!Validate()) return false;
  namespace ks = ::cga::kernels::simd;
  using ik_chain_detail::Solver;
  const std::size_t chains = targets.size(), n = static_cast<std::size_t>(chain_joints);
  // Blocks of kBlock chains in lockstep: a block's solver states stay in cache between iterations, and its
  // kBlock * columns elements still fill many vectors.
  constexpr std::size_t kBlock = 16;
  std::vector<ChainIKJob> jobs;
  std::vector<Solver> solvers;
  jobs.reserve(kBlock), solvers.reserve(kBlock);
  // Scratch of one iteration: per active chain its posed motors and its effector and frame axes (gathered by
  // chain), per element (column) its axis and its rows' indices, and the kernel's outputs.
  std::vector<std::size_t> active;
  std::vector<float> posed, chain_vecs, ax, ay, az, out_p, out_uw, out_dp, out_du, out_dw;
  std::vector<std::int32_t> motor_row, chain_row;
  const float zero = 0.0f;
  for (std::size_t first = 0; first < chains; first += kBlock) {
    const std::size_t count = std::min(kBlock, chains - first);
    jobs.clear(), solvers.clear();
    for (std::size_t c = 0; c < count; ++c) jobs.push_back(chain_job(*this, first + c));
    for (const ChainIKJob& job : jobs) solvers.emplace_back(job);
    const int cols = solvers[0].columns();
    const bool oriented = solvers[0].oriented();  // every chain's or none
    for (;;) {
      active.clear();
      for (std::size_t c = 0; c < count; ++c)
        if (solvers[c].active()) active.push_back(c);
      if (active.empty()) break;
      const std::size_t elements = active.size() * static_cast<std::size_t>(cols);
      posed.resize(active.size() * n * 8), chain_vecs.resize(active.size() * 9);
      ax.resize(elements), ay.resize(elements), az.resize(elements);
      motor_row.resize(elements), chain_row.resize(elements);
      out_p.resize(elements * 4), out_dp.resize(elements * 4), out_uw.resize(elements * 3);
      out_du.resize(elements * 3), out_dw.resize(elements * 3);
      std::size_t e = 0;
      for (std::size_t k = 0; k < active.size(); ++k) {
        const Solver& s = solvers[active[k]];
        for (std::size_t j = 0; j < n; ++j) {
          const RigidMotor& m = s.posed(static_cast<int>(j));
          std::copy(m.begin(), m.end(), posed.begin() + static_cast<std::ptrdiff_t>((k * n + j) * 8));
        }
        const glm::vec3 v[3] = {s.effector(), s.frame_x(), s.frame_y()};
        for (int i = 0; i < 3; ++i)
          for (int x = 0; x < 3; ++x) chain_vecs[k * 9 + static_cast<std::size_t>(3 * i + x)] = v[i][x];
        for (int c = 0; c < cols; ++c, ++e) {
          const glm::vec3 a = s.axis_of(c);
          ax[e] = a.x, ay[e] = a.y, az[e] = a.z;
          motor_row[e] = static_cast<std::int32_t>(k * n + static_cast<std::size_t>(s.joint_of(c)));
          chain_row[e] = static_cast<std::int32_t>(k);
        }
      }
      // Streams: the motor as rows of 8 gathered by motor_row; the axis as three arrays; the angle 0
      // broadcast; the effector and the frame axes as rows of 9 gathered by chain_row. Outputs as rows of 4
      // and 3 (U and W, which the solve does not use, into one scratch).
      const ks::In motor{posed.data(), 8, 1, motor_row.data(), 1, nullptr};
      const ks::In sx{ax.data()}, sy{ay.data()}, sz{az.data()}, angle{&zero, 0};
      ks::In vec[9];
      for (int i = 0; i < 9; ++i) vec[i] = ks::In{chain_vecs.data() + i, 9, 1, chain_row.data(), 1, nullptr};
      const ks::Out p{out_p.data(), 4, 1}, dp{out_dp.data(), 4, 1}, uw{out_uw.data(), 3, 1};
      const ks::Out du{out_du.data(), 3, 1}, dw{out_dw.data(), 3, 1};
      if (oriented)
        ks::ik_chain_joint_batch(elements, motor, sx, sy, sz, angle, vec[0], vec[1], vec[2], vec[3], vec[4], vec[5],
                                 vec[6], vec[7], vec[8], p, uw, uw, dp, du, dw);
      else
        ks::ik_chain_joint_position_batch(elements, motor, sx, sy, sz, angle, vec[0], vec[1], vec[2], vec[3], vec[4],
                                          vec[5], vec[6], vec[7], vec[8], dp);
      clear_upper_state();
      e = 0;
      for (const std::size_t c : active) {
        Solver& s = solvers[c];
        for (int k = 0; k < cols; ++k, ++e)
          if (oriented)
            s.store_column(k, &out_p[e * 4], &out_dp[e * 4], &out_du[e * 3], &out_dw[e * 3]);
          else
            s.store_position_column(k, &out_dp[e * 4]);
        s.step();
      }
    }
    for (std::size_t c = 0; c < count; ++c) {
      bool r = false;
      int it = 0;
      jobs[c].reached = &r, jobs[c].iterations = &it;
      solvers[c].finish();
      if (!reached.empty()) reached[first + c] = r ? 1 : 0;
      if (!iterations.empty()) iterations[first + c] = it;
    }
  }
  return true;
}

}  // namespace cga
