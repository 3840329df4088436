// SkinningJob: names, validation, the per-run palette preparation, strided streams and the dispatch: every
// method to its blend's generated SIMD batch kernels (batch.cpp, the CPU's best instruction set), or with
// use_simd = false to the generated scalar loop (generated.hpp, portable.cpp). No method is named here.
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/packed_palette.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>


#include <fmt/format.h>


#include "batch.hpp"
#include "generated.hpp"

namespace cga {

static_assert(sizeof(glm::mat3x4) == 12 * sizeof(float), "matrix palette entries are read as 12 floats");
static_assert(sizeof(Motor) == 12 * sizeof(float), "motor palette entries are read as 12 floats");

std::string_view to_string(SkinningMethod method) {
  if (static_cast<std::size_t>(method) >= kSkinningMethodCount)
    throw std::invalid_argument(fmt::format("to_string: unknown SkinningMethod {}", static_cast<int>(method)));
  return skinning_method_info(method).name;
}

SkinningMethod parse_skinning_method(std::string_view text) {
  std::string canonical(text);
  for (char& c : canonical)
    if (c == '_') c = '-';
  std::string choices;
  for (const SkinningMethodInfo& m : kSkinningMethods) {
    if (m.name == canonical) return m.method;
    choices += (choices.empty() ? "" : ", ") + std::string(m.name);
  }
  throw std::invalid_argument(fmt::format("unknown skinning method '{}' (choose {})", text, choices));
}

void SkinnedOutput::resize_for(const SkinnedMesh& mesh) {
  const std::size_t n = mesh.vertex_count();
  px.assign(n, 0.0f);
  py.assign(n, 0.0f);
  pz.assign(n, 0.0f);
  const std::size_t nn = mesh.has_normals() ? n : 0;
  nx.assign(nn, 0.0f);
  ny.assign(nn, 0.0f);
  nz.assign(nn, 0.0f);
}

SkinningJob make_skinning_job(SkinningMethod method, const SkinnedMesh& mesh, SkinnedOutput& out) {
  out.resize_for(mesh);
  SkinningJob job;
  job.method = method;
  job.in_px = mesh.px;
  job.in_py = mesh.py;
  job.in_pz = mesh.pz;
  job.in_nx = mesh.nx;
  job.in_ny = mesh.ny;
  job.in_nz = mesh.nz;
  job.joints = mesh.joints;
  job.weights = mesh.weights;
  job.out_px = out.px;
  job.out_py = out.py;
  job.out_pz = out.pz;
  job.out_nx = out.nx;
  job.out_ny = out.ny;
  job.out_nz = out.nz;
  return job;
}

namespace {

using namespace skinning_detail;

std::size_t palette_size(const SkinningJob& job) {
  switch (skinning_method_info(job.method).palette) {
    case PaletteKind::matrices: return job.matrices.size();
    case PaletteKind::dual_quats: return job.dual_quats.size();
    case PaletteKind::motors: return job.motors.size();
  }
  return 0;
}

// A stream of n vertices with the given stride (floats between consecutive vertices) needs this many floats.
std::size_t stream_extent(std::size_t n, std::size_t stride) { return n == 0 ? 0 : (n - 1) * stride + 1; }

// The O(1) checks of a strided stream triple: every span covers n vertices at its stride.
bool strided_fits(std::size_t n, std::size_t stride, std::span<const float> x, std::span<const float> y,
                  std::span<const float> z) {
  const std::size_t need = stream_extent(n, stride);
  return x.size() >= need && y.size() >= need && z.size() >= need;
}

// The O(1) checks: sizes, strides, normals, palette limits.
std::string shape_error(const SkinningJob& job) {
  if (job.in_positions_stride == 0 || job.in_normals_stride == 0 || job.out_positions_stride == 0 ||
      job.out_normals_stride == 0 || job.joints_stride == 0 || job.weights_stride == 0)
    return "a stream stride is 0 (1 is packed; an interleaved buffer's stride is its vertex size in the span's "
           "elements)";
  const std::size_t n = job.vertex_count();
  if (job.is_packed()) {
    if (job.in_py.size() != n || job.in_pz.size() != n)
      return fmt::format("input positions differ in size (x {}, y {}, z {})", n, job.in_py.size(), job.in_pz.size());
    if (job.out_px.size() != n || job.out_py.size() != n || job.out_pz.size() != n)
      return fmt::format("output positions must hold {} vertices (x {}, y {}, z {})", n, job.out_px.size(),
                         job.out_py.size(), job.out_pz.size());
  } else {
    if (!strided_fits(n, job.in_positions_stride, job.in_px, job.in_py, job.in_pz))
      return fmt::format("input positions must cover {} vertices at stride {} ({} floats; x {}, y {}, z {})", n,
                         job.in_positions_stride, stream_extent(n, job.in_positions_stride), job.in_px.size(),
                         job.in_py.size(), job.in_pz.size());
    if (!strided_fits(n, job.out_positions_stride, job.out_px, job.out_py, job.out_pz))
      return fmt::format("output positions must cover {} vertices at stride {} ({} floats; x {}, y {}, z {})", n,
                         job.out_positions_stride, stream_extent(n, job.out_positions_stride), job.out_px.size(),
                         job.out_py.size(), job.out_pz.size());
  }
  if (job.joints_stride == 1 ? job.joints.size() != n : job.joints.size() < stream_extent(n, job.joints_stride))
    return fmt::format("{} joint quadruples for {} vertices at stride {}", job.joints.size(), n, job.joints_stride);
  if (job.weights_stride == 1 ? job.weights.size() != n : job.weights.size() < stream_extent(n, job.weights_stride))
    return fmt::format("{} weight quadruples for {} vertices at stride {}", job.weights.size(), n,
                       job.weights_stride);
  const bool any_in_normals = !job.in_nx.empty() || !job.in_ny.empty() || !job.in_nz.empty();
  const bool any_out_normals = !job.out_nx.empty() || !job.out_ny.empty() || !job.out_nz.empty();
  if (any_in_normals) {
    if (job.is_packed()) {
      if (job.in_nx.size() != n || job.in_ny.size() != n || job.in_nz.size() != n)
        return fmt::format("input normals must be empty or hold {} vertices (x {}, y {}, z {})", n,
                           job.in_nx.size(), job.in_ny.size(), job.in_nz.size());
      if (job.out_nx.size() != n || job.out_ny.size() != n || job.out_nz.size() != n)
        return fmt::format("output normals must hold {} vertices (x {}, y {}, z {})", n, job.out_nx.size(),
                           job.out_ny.size(), job.out_nz.size());
    } else {
      if (!strided_fits(n, job.in_normals_stride, job.in_nx, job.in_ny, job.in_nz))
        return fmt::format("input normals must be empty or cover {} vertices at stride {} (x {}, y {}, z {})", n,
                           job.in_normals_stride, job.in_nx.size(), job.in_ny.size(), job.in_nz.size());
      if (!strided_fits(n, job.out_normals_stride, job.out_nx, job.out_ny, job.out_nz))
        return fmt::format("output normals must cover {} vertices at stride {} (x {}, y {}, z {})", n,
                           job.out_normals_stride, job.out_nx.size(), job.out_ny.size(), job.out_nz.size());
    }
  } else if (any_out_normals) {
    return "output normals given without input normals";
  }
  const std::size_t palette = palette_size(job);
  if (palette > kMaxConvertedPalette)
    return fmt::format("{} converts at most {} palette entries per run, the palette has {}",
                       to_string(job.method), kMaxConvertedPalette, palette);
  return {};
}

std::string data_error(const SkinningJob& job) {
  const std::size_t palette = palette_size(job);
  for (std::size_t i = 0; i < job.vertex_count(); ++i)
    for (int k = 0; k < 4; ++k) {
      const std::uint16_t joint = job.joints[i * job.joints_stride][k];
      const float weight = job.weights[i * job.weights_stride][k];
      if (joint >= palette)
        return fmt::format("vertex {} influence {}: joint {} is outside the {} palette of {} entries", i, k, joint,
                           to_string(job.method), palette);
      if (!std::isfinite(weight)) return fmt::format("vertex {} influence {}: weight {} is not finite", i, k, weight);
      if (weight < 0.0f) return fmt::format("vertex {} influence {}: weight {} is negative", i, k, weight);
    }
  // lbs and cga-points scale a vertex by its weight sum: an unnormalized vertex would be silently misplaced.
  for (std::size_t i = 0; i < job.vertex_count(); ++i) {
    const auto& w = job.weights[i * job.weights_stride];
    const float sum = w[0] + w[1] + w[2] + w[3];
    if (!(std::abs(sum - 1.0f) <= kWeightSumTolerance))
      return fmt::format("vertex {}: weights sum to {}, not 1 (renormalize them)", i, sum);
  }
  return {};
}

// Strided streams run through one block of packed vertices on the stack (stage_in, the packed block
// function, stage_out). The mesh is never copied; the staging costs two passes over 256
// vertices that are in L1 anyway.
bool run_strided(const Streams& s, std::size_t n, bool normals, BlockFn block, const float* pal,
                 std::size_t palette) {
  Staged t;
  for (std::size_t begin = 0; begin < n; begin += kBlock) {
    const std::size_t count = std::min(kBlock, n - begin);
    if (!block(pal, stage_in(s, begin, count, normals, t), 0, count, palette)) return false;
    stage_out(t, s, begin, count, normals);
  }
  return true;
}

}  // namespace

std::string SkinningJob::ValidationError() const {
  std::string error = shape_error(*this);
  if (error.empty()) error = data_error(*this);
  return error;
}

bool SkinningJob::Run() const {
  if (!shape_error(*this).empty()) return false;
  const std::size_t n = vertex_count();
  const bool normals = has_normals();
  // Per-run palette preparation, on the stack (Run() never allocates): every entry by the method's bone
  // kernel, one kEntry-float line each. Outputs are written with plain stores: non-temporal stores gained 10 %
  // on one host and halved the throughput on another (docs/bench.md), and ozz-animation uses plain stores too.
  alignas(64) float converted[kMaxConvertedPalette * kEntry];
  static_assert([] {
    for (const SkinningMethodInfo& m : kSkinningMethods)
      if (4 * m.entry_vec4s > kEntry) return false;
    return true;
  }(), "a prepared entry must fit the converted palette's entry size");
  const std::size_t palette = palette_size(*this);
  prepare_palette_strided(method, matrices, dual_quats, motors,
                          std::span<float>(converted, sizeof converted / sizeof(float)), kEntry);
  const BlockFn block = (use_simd ? batch_blocks() : generated_blocks())[static_cast<std::size_t>(method)][normals];
  const Streams s{in_px.data(),  in_py.data(),  in_pz.data(),  in_nx.data(),  in_ny.data(),
                  in_nz.data(),  joints.data(), weights.data(), out_px.data(), out_py.data(),
                  out_pz.data(), out_nx.data(), out_ny.data(), out_nz.data(), in_positions_stride,
                  in_normals_stride, out_positions_stride, out_normals_stride, joints_stride, weights_stride};
  if (!is_packed()) return run_strided(s, n, normals, block, converted, palette);
  bool ok = true;
  for (std::size_t begin = 0; begin < n && ok; begin += kBlock)
    ok = block(converted, s, begin, std::min(n, begin + kBlock), palette);
  return ok;
}

}  // namespace cga
