// SkinningPaletteJob and make_inverse_bind_motors (see jobs.hpp): a mesh's motor palette, model motor times
// inverse bind motor per palette entry, by the 8-blade product (vectorized across entries) where every factor
// is rigid and the split form otherwise. Run() never allocates.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "common.hpp"

namespace cga {

namespace {

// palette[k] = model[remap[k]] * inverse_bind[k], by the 8-blade product where both factors are rigid.
// The rigidity of every entry is checked first (OR of the b groups' bits), so that an all-rigid palette runs a
// loop of nothing but rigid products: with the test and the 12-blade product in the same loop body, GCC
// hoists parts of the 12-blade product above the branch and the loop costs twice as much.
__attribute__((noinline)) void palette_general(const Motor& m, const Motor& ib, Motor& out) {
  float x[12], y[12], z[12];
  to_split(m, x), to_split(ib, y);
  split_mul(x, y, z);
  from_split(z, out);
}
// The check reads every model motor (contiguous, vectorized), not only the remapped ones: a dilated joint
// that no entry uses sends the palette to the per-entry loop, which is slower but equal.
CGA_JOBS_CLONES void palette(std::size_t n, const int* __restrict remap, const Motor* __restrict model,
                             std::size_t joints, const Motor* __restrict ib, Motor* __restrict out) {
  if (all_rigid(model, joints) && all_rigid(ib, n)) {
    std::size_t k = 0;
#if defined(__GNUC__)
    // Blocks of 8 entries as structure of arrays: the generated 8-blade product vectorized across entries.
    constexpr int kRigidBlade[kR] = {0, 1, 2, 3, 4, 5, 6, 8};
    for (; k + kB <= n; k += kB) {
      v8f x[kM], y[kM];
      gather_rows([&](int l) -> const Motor& { return model[remap[k + l]]; }, x);
      gather_rows([&](int l) -> const Motor& { return ib[k + l]; }, y);
      float xs[kR][kB], ys[kR][kB], zs[kR][kB];
      for (std::size_t c = 0; c < kR; ++c) store8(xs[c], x[kRigidBlade[c]]), store8(ys[c], y[kRigidBlade[c]]);
      for (std::size_t l = 0; l < kB; ++l) {
        float a[kR], b[kR], z[kR];
        for (std::size_t c = 0; c < kR; ++c) a[c] = xs[c][l], b[c] = ys[c][l];
        kernels::motor_mul_rigid(a, b, z);
        for (std::size_t c = 0; c < kR; ++c) zs[c][l] = z[c];
      }
      v8f z[kM];
      z[7] = z[9] = z[10] = z[11] = v8f{};
      for (std::size_t c = 0; c < kR; ++c) z[kRigidBlade[c]] = load8(zs[c]);
      scatter_rows(z, out + k);
    }
#endif
    for (; k < n; ++k) motor_mul_rigid(model[remap[k]], ib[k], out[k]);
    return;
  }
  for (std::size_t k = 0; k < n; ++k) {
    const Motor& m = model[remap[k]];
    if (motor_is_rigid(m) && motor_is_rigid(ib[k]))
      motor_mul_rigid(m, ib[k], out[k]);
    else
      palette_general(m, ib[k], out[k]);
  }
}

constexpr float kRigidScaleTolerance = 8.0f * 1.1920929e-7f;  // 8 float ulps at 1

}  // namespace

std::vector<Motor> make_inverse_bind_motors(const SkinnedMesh& mesh) {
  const std::size_t n = mesh.joint_remap.size();
  std::vector<Motor> motors(n);
  for (std::size_t k = 0; k < n && k < mesh.inverse_bind.size(); ++k) {
    // A scale within float rounding of 1 (what decomposing a rigid offset matrix leaves) is taken as 1,
    // so that rigid characters get exactly rigid inverse binds and the palette its 8-blade product.
    Transform x = mesh.inverse_bind[k];
    if (std::abs(x.scale - 1.0f) <= kRigidScaleTolerance) x.scale = 1.0f;
    motors[k] = motor_from_transform(x);
  }
  return motors;
}

bool SkinningPaletteJob::Validate() const {
  const std::size_t n = joint_remap.size();
  if (!fits(output, n) || !fits(inverse_bind, n)) return false;
  for (int j : joint_remap)
    if (j < 0 || static_cast<std::size_t>(j) >= model.size()) return false;
  return true;
}

bool SkinningPaletteJob::Run() const {
  if (!Validate()) return false;
  palette(joint_remap.size(), joint_remap.data(), model.data(), model.size(), inverse_bind.data(), output.data());
  return true;
}

}  // namespace cga
