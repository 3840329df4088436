// Host side of the CUDA crowd skinning (C++ compiler): argument checks, byte counts, the launch.
#include "cga/cuda/crowd_skinning.hpp"

#include <algorithm>
#include <array>

#include "kernels.hpp"

namespace cga::cuda {

PaletteLayout palette_layout(SkinningMethod method, std::size_t bones) {
  const unsigned units = detail::palette_units(static_cast<int>(method));
  const unsigned shift = detail::copy_shift_for(bones, units);
  return {1u << shift, std::size_t{detail::palette_slots(static_cast<unsigned>(bones * units), shift)} * 16u};
}

double modelled_palette_wavefronts(const PaletteLayout& layout, SkinningMethod method,
                                   std::span<const std::array<std::uint16_t, 4>> joints) {
  unsigned shift = 0;
  while ((1u << shift) < layout.copies) ++shift;
  const unsigned units = detail::palette_units(static_cast<int>(method));
  double sum = 0.0;
  std::size_t loads = 0;
  for (std::size_t warp = 0; warp < joints.size(); warp += 32) {
    const std::size_t lanes = std::min<std::size_t>(32, joints.size() - warp);
    for (int k = 0; k < 4; ++k)
      for (unsigned u = 0; u < units; ++u) {
        unsigned wavefronts = 0;
        for (std::size_t quarter = 0; quarter < lanes; quarter += 8) {
          std::array<std::array<unsigned, 8>, detail::kBankGroups> slots{};  // distinct slots per group
          std::array<unsigned, detail::kBankGroups> count{};
          for (std::size_t l = quarter; l < std::min(lanes, quarter + 8); ++l) {
            const unsigned s = detail::palette_slot(joints[warp + l][k] * units + u,
                                                    static_cast<unsigned>(l) & (layout.copies - 1u), shift);
            const unsigned g = s % detail::kBankGroups;
            if (std::find(slots[g].begin(), slots[g].begin() + count[g], s) == slots[g].begin() + count[g])
              slots[g][count[g]++] = s;
          }
          wavefronts += *std::max_element(count.begin(), count.end());
        }
        sum += wavefronts;
        ++loads;
      }
  }
  return loads ? sum / static_cast<double>(loads) : 0.0;
}

std::size_t bytes_per_vertex(const CrowdArgs& a) {
  const std::size_t joints = a.joint_format == JointFormat::u16x4 ? 8 : 4;
  const std::size_t weights = a.weight_format == WeightFormat::f32x4 ? 16 : 8;
  const std::size_t normals = a.normals ? 24 : 0;
  return 12 + joints + weights + 12 + normals;
}

void launch_crowd_skinning(const CrowdArgs& a, void* stream) {
  auto fail = [](const std::string& why) { throw CudaError("cga::cuda::launch_crowd_skinning: " + why); };
  if (a.vertex_count == 0 || a.instances == 0) return;
  if (a.bones == 0 || a.bones > kMaxBones)
    fail(std::to_string(a.bones) + " bones per instance (1.." + std::to_string(kMaxBones) + ")");
  if (a.vertex_count > 0xffffffffu) fail("more than 2^32 - 1 vertices per instance");
  if (!a.positions || !a.joints || !a.weights || !a.palettes || !a.out_positions)
    fail("a required device pointer is null");
  if (a.normals && !a.out_normals) fail("input normals without output normals");
  detail::LaunchArgs d;
  d.method = static_cast<int>(a.method);
  d.vertex_count = a.vertex_count, d.instances = a.instances, d.bones = a.bones;
  d.per_instance_inputs = a.per_instance_inputs;
  d.positions = a.positions, d.normals = a.normals;
  d.joints = a.joints, d.joints_u8 = a.joint_format == JointFormat::u8x4;
  d.weights = a.weights, d.weights_unorm16 = a.weight_format == WeightFormat::unorm16x4;
  d.palettes = a.palettes, d.out_positions = a.out_positions, d.out_normals = a.out_normals;
  const std::string error = detail::launch(d, stream);
  if (!error.empty()) fail(std::string(to_string(a.method)) + ": " + error);
}

}  // namespace cga::cuda
