// Palette entries of each skinning method from a Transform (TRS with uniform scale), and the bridge from the
// skinning loops to the generated motor kernels (cga::kernels, built from runtime/scripts/*.clu).
// These conversions are for tests, examples and single transforms; whole poses come from the runtime's
// local-to-model job.
#pragma once

#include <span>
#include <stdexcept>
#include <string_view>

#include "cga/runtime/rotor_sign.hpp"
#include "cga/runtime/types.hpp"

// A hard dependency: the CGA methods run on this generated kernel (cga::kernels, generated/CMakeLists.txt), so
// a build without it fails here rather than at run time.
#include <transform_point_split.hpp>

namespace cga {

// The row-major 3x4 matrix of p -> s R p + t (see MatrixPalette).
inline glm::mat3x4 to_skinning_matrix(const Transform& x) {
  const glm::mat3 linear = glm::mat3_cast(x.rotation) * x.scale;  // column-major: linear[c][r]
  glm::mat3x4 m;
  for (int r = 0; r < 3; ++r) m[r] = glm::vec4(linear[0][r], linear[1][r], linear[2][r], x.translation[r]);
  return m;
}

// The unit dual quaternion of the rigid part (rotation, translation); a dual quaternion cannot hold the
// scale, so a Transform with scale != 1 is rejected rather than silently dropped.
inline glm::dualquat to_dual_quat(const Transform& x) {
  if (x.scale != 1.0f)
    throw std::invalid_argument("to_dual_quat: dual quaternions cannot represent a scale != 1");
  return glm::dualquat(glm::normalize(x.rotation), x.translation);
}

// Applies a row-major 3x4 matrix to a point.
inline glm::vec3 transform_point(const glm::mat3x4& m, const glm::vec3& p) {
  return {glm::dot(m[0], glm::vec4(p, 1.0f)), glm::dot(m[1], glm::vec4(p, 1.0f)), glm::dot(m[2], glm::vec4(p, 1.0f))};
}

// Dual quaternions as 8 floats (real x y z w, dual x y z w), the layout the dqs loop reads.
inline void pack_dual_quats(std::span<const glm::dualquat> in, std::span<float> out) {
  if (out.size() < 8 * in.size()) throw std::invalid_argument("pack_dual_quats: output too small");
  for (std::size_t k = 0; k < in.size(); ++k) {
    const glm::dualquat& q = in[k];
    const float v[8] = {q.real.x, q.real.y, q.real.z, q.real.w, q.dual.x, q.dual.y, q.dual.z, q.dual.w};
    for (int e = 0; e < 8; ++e) out[8 * k + e] = v[e];
  }
}

namespace detail {

// A motor in split form (runtime/scripts/transform_point_split.clu): G = a + b and H = a - b (blades 1 e12
// e13 e23 of a and of the E-times group b), U the einf blades (e1inf e2inf e3inf e123inf). Linear in the
// coefficients, so blending split motors is the split form of the blend.
inline void motor_split(const float m[12], float g[4], float h[4], float u[4]) { rotor_sign::split(m, g, h, u); }

// The layout of transform_point_split's prepared values that motor_split_matrix reads, checked against the
// slot names the generator emits: row r of the normalized 3x4 as (translation, x, y, z).
constexpr bool prepared_split_layout() {
  const auto& got = cga::kernels::transform_point_split_prepare_prepared_blades;
  if (got.size() != 12) return false;
  const char* col[4] = {"[1]", "[x]", "[y]", "[z]"};
  for (std::size_t k = 0; k < 12; ++k) {
    const std::string_view want_row[3] = {"p.e1", "p.e2", "p.e3"};
    const std::string_view s = got[k];
    if (s.substr(0, 4) != want_row[k / 4] || s.substr(4) != col[k % 4]) return false;
  }
  return true;
}
static_assert(prepared_split_layout(), "transform_point_split's prepared values are no longer the 3x4 rows");

// The weight-normalized point transform of a (possibly blended, unnormalized) motor in split form as a
// row-major 3x4 matrix (x, y, z, translation per row): the generated prepare of the staged
// transform_point_split, its rows rotated from (translation, x, y, z).
inline void motor_split_matrix(const float g[4], const float h[4], const float u[4], float out[12]) {
  float prepared[12];
  cga::kernels::transform_point_split_prepare(g, h, u, prepared);
  for (int r = 0; r < 3; ++r) {
    out[4 * r + 0] = prepared[4 * r + 1];
    out[4 * r + 1] = prepared[4 * r + 2];
    out[4 * r + 2] = prepared[4 * r + 3];
    out[4 * r + 3] = prepared[4 * r + 0];
  }
}

// The same from the 12 blade coefficients (the split form first: the blade form's weight a^2 + b^2 + 2ab
// cancels for scaled motors, see the script).
inline void motor_matrix(const float motor[12], float out[12]) {
  float g[4], h[4], u[4];
  motor_split(motor, g, h, u);
  motor_split_matrix(g, h, u, out);
}

}  // namespace detail
}  // namespace cga
