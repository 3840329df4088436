// Every skinning method against the naive dense oracle (tests/oracle): the bone motors as oracle
// multivectors, points moved by the sandwich M X ~M and brought down by their weight. Also checks, on the
// oracle, the algebra docs/skinning.md states for a blended motor M = P + Q E + U einf (E = einf^e0):
// the Euclidean part of M X ~M over its weight is ((A x ~B)_1 - 2 (A ~U)_1) / |A|^2 with A = P + Q, B = P - Q,
// a similarity when every blended bone has the same scale.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>

#include <oracle/multivector.hpp>

#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "cga/testing/nan_max.hpp"

using namespace cga;
using MV = oracle::MV<double>;

namespace {

// The names of Motor's 12 blades, in types.hpp's order.
const std::array<const char*, 12> kMotorBlades = {
    "1",         "e1^e2",     "e1^e3",     "e1^einf",           "e2^e3",           "e2^einf",
    "e3^einf",   "einf^e0",   "e1^e2^e3^einf", "e1^e2^einf^e0", "e1^e3^einf^e0", "e2^e3^einf^e0"};

MV nb(const char* name) { return oracle::null_blade<double>(name); }

MV to_mv(const Motor& m) {
  MV r;
  for (int k = 0; k < 12; ++k) r += static_cast<double>(m.c[k]) * nb(kMotorBlades[k]);
  return r;
}

// T R D built by products on the oracle: T = 1 - 1/2 t einf, R = cos(phi/2) - sin(phi/2) (n1 e23 + n2 e31 + n3 e12)
// (the rotor of GLM's angleAxis(phi, n), notes/cga-facts.md), D = 1 + (1-s)/(1+s) einf^e0.
MV oracle_motor(const Transform& x) {
  const glm::quat q = glm::normalize(x.rotation);
  const double half = std::acos(std::clamp(static_cast<double>(q.w), -1.0, 1.0));
  const double sin_half = std::sin(half);
  glm::dvec3 n(0, 0, 1);
  if (sin_half > 1e-12) n = glm::dvec3(q.x, q.y, q.z) / sin_half;
  const MV plane = n.x * nb("e2^e3") - n.y * nb("e1^e3") + n.z * nb("e1^e2");
  const MV R = MV::scalar(std::cos(half)) - sin_half * plane;
  const MV t = static_cast<double>(x.translation.x) * oracle::e1<double>() +
               static_cast<double>(x.translation.y) * oracle::e2<double>() +
               static_cast<double>(x.translation.z) * oracle::e3<double>();
  const MV T = MV::scalar(1.0) - 0.5 * (t * oracle::einf<double>());
  const double s = x.scale;
  const MV D = MV::scalar(1.0) + ((1 - s) / (1 + s)) * nb("einf^e0");
  return T * R * D;
}

std::array<double, 3> sandwich_down(const MV& M, const glm::vec3& p) {
  return oracle::down(M * oracle::up<double>(p.x, p.y, p.z) * oracle::reverse(M));
}

double distance(const std::array<double, 3>& a, const glm::vec3& b) {
  return std::sqrt((a[0] - b.x) * (a[0] - b.x) + (a[1] - b.y) * (a[1] - b.y) + (a[2] - b.z) * (a[2] - b.z));
}

// Test-local motor of a Transform from its oracle product: coefficients read off by projecting on the
// 12 blades (the product has no other blades, checked).
Motor motor_from_oracle(const Transform& x) {
  const std::array<double, 32> c = oracle::to_null_basis(oracle_motor(x));
  const auto& names = oracle::null_blade_names();
  Motor m;
  double outside = 0.0;
  for (unsigned k = 0; k < 32; ++k) {
    int slot = -1;
    for (int b = 0; b < 12; ++b)
      if (names[k] == kMotorBlades[b]) slot = b;
    if (slot >= 0)
      m.c[slot] = static_cast<float>(c[k]);
    else
      outside = testing::nan_max(outside, std::abs(c[k]));
  }
  REQUIRE(outside < 1e-12);
  return m;
}

double rotor_dot(const Motor& a, const Motor& b) {
  return a.c[blade::s] * b.c[blade::s] + a.c[blade::e12] * b.c[blade::e12] + a.c[blade::e13] * b.c[blade::e13] +
         a.c[blade::e23] * b.c[blade::e23];
}

}  // namespace

TEST_CASE("oracle motors move points like GLM's TRS matrices and have exactly the 12 motor blades",
          "[skinning][oracle]") {
  for (const Transform& x : make_random_transforms(20, 5, 2.0f, 0.7f)) {
    const MV M = oracle_motor(x);
    const Motor m = motor_from_oracle(x);  // REQUIREs the other 20 blades vanish
    CHECK(oracle::max_abs_diff(to_mv(m), M) < 1e-6);
    const glm::vec3 p(0.3f, -0.7f, 0.5f);
    CHECK(distance(sandwich_down(M, p), transform_point(to_skinning_matrix(x), p)) < 1e-5);
  }
}

TEST_CASE("every skinning method agrees with the oracle's M X ~M", "[skinning][oracle]") {
  const bool rigid = GENERATE(true, false);
  const int bones = 8;
  const std::vector<Transform> xs = make_random_transforms(bones, rigid ? 31 : 32, 2.0f, rigid ? 0.0f : 0.7f);
  const SkinnedMesh mesh = make_random_skinned_mesh(64, bones, 33);
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
  MotorPalette motors;
  std::vector<MV> mvs;
  for (const Transform& x : xs) {
    matrices.push_back(to_skinning_matrix(x));
    if (rigid) dual_quats.push_back(to_dual_quat(x));
    motors.push_back(motor_from_oracle(x));
    mvs.push_back(oracle_motor(x));
  }
  std::vector<SkinningMethod> methods{SkinningMethod::lbs, SkinningMethod::cga_points, SkinningMethod::cga_motors};
  if (rigid) methods.push_back(SkinningMethod::dqs);
  for (SkinningMethod method : methods) {
    SkinnedOutput out;
    SkinningJob job = make_skinning_job(method, mesh, out);
    job.matrices = matrices;
    job.dual_quats = dual_quats;
    job.motors = motors;
    REQUIRE(job.Run());
    for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
      const glm::vec3 p(mesh.px[i], mesh.py[i], mesh.pz[i]);
      const auto& j = mesh.joints[i];
      const auto& w = mesh.weights[i];
      std::array<double, 3> expected{0, 0, 0};
      if (method == SkinningMethod::lbs || method == SkinningMethod::cga_points) {
        // Each bone's point normalized by its weight, then averaged.
        for (int k = 0; k < 4; ++k) {
          const auto q = sandwich_down(mvs[j[k]], p);
          for (int a = 0; a < 3; ++a) expected[a] += w[k] * q[a];
        }
      } else {
        // One sandwich with the blended motor (sign fix against the first influence).
        MV blend = static_cast<double>(w[0]) * mvs[j[0]];
        for (int k = 1; k < 4; ++k)
          blend += (rotor_dot(motors[j[0]], motors[j[k]]) < 0 ? -1.0 : 1.0) * w[k] * mvs[j[k]];
        expected = sandwich_down(blend, p);
      }
      INFO(to_string(method) << (rigid ? " rigid" : " scaled") << ", vertex " << i);
      REQUIRE(distance(expected, glm::vec3(out.px[i], out.py[i], out.pz[i])) < 1e-5 * 6.0);
    }
  }
}

TEST_CASE("a blended motor's point transform: the closed form, and a similarity when scales agree",
          "[skinning][oracle]") {
  std::mt19937 rng(77);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const MV E = nb("einf^e0");
  for (int trial = 0; trial < 20; ++trial) {
    const bool same_scale = trial % 2 == 0;
    std::vector<Transform> xs = make_random_transforms(3, 900 + trial, 2.0f, 0.6f);
    if (same_scale)
      for (Transform& x : xs) x.scale = xs[0].scale;
    MV M;
    double wsum = 0;
    for (const Transform& x : xs) {
      const double w = 0.2 + u(rng);
      wsum += w;
      MV m = oracle_motor(x);
      if (oracle::scalar_part(m * oracle::reverse(oracle_motor(xs[0]))) < 0) m = -m;
      M += w * m;
    }
    M = M / wsum;
    // Split M = P + Q E + U einf on its blades.
    const std::array<double, 32> c = oracle::to_null_basis(M);
    const auto& names = oracle::null_blade_names();
    auto coef = [&](const char* name) {
      for (unsigned k = 0; k < 32; ++k)
        if (names[k] == name) return c[k];
      throw std::logic_error(name);
    };
    const MV P = coef("1") * nb("1") + coef("e1^e2") * nb("e1^e2") + coef("e1^e3") * nb("e1^e3") +
                 coef("e2^e3") * nb("e2^e3");
    const MV Q = coef("einf^e0") * nb("1") + coef("e1^e2^einf^e0") * nb("e1^e2") +
                 coef("e1^e3^einf^e0") * nb("e1^e3") + coef("e2^e3^einf^e0") * nb("e2^e3");
    const MV U = coef("e1^einf") * nb("e1") + coef("e2^einf") * nb("e2") + coef("e3^einf") * nb("e3") +
                 coef("e1^e2^e3^einf") * nb("e1^e2^e3");
    REQUIRE(oracle::max_abs_diff(P + Q * E + U * oracle::einf<double>(), M) < 1e-9);
    const MV A = P + Q, B = P - Q;
    const double norm = oracle::scalar_part(A * oracle::reverse(A));
    const MV shift = oracle::grade(A * oracle::reverse(U), 1);
    // The linear map's columns L e_a and the translation, from the closed form.
    std::array<std::array<double, 3>, 3> L{};
    for (int a = 0; a < 3; ++a) {
      const MV x = a == 0 ? oracle::e1<double>() : a == 1 ? oracle::e2<double>() : oracle::e3<double>();
      const MV col = oracle::grade(A * x * oracle::reverse(B), 1) / norm;
      L[a] = {col[0b001], col[0b010], col[0b100]};
    }
    for (const glm::vec3 p : {glm::vec3(0, 0, 0), glm::vec3(0.4f, -1.2f, 0.9f), glm::vec3(-2, 1, 3)}) {
      const auto direct = sandwich_down(M, p);
      for (int r = 0; r < 3; ++r) {
        const double closed = L[0][r] * p.x + L[1][r] * p.y + L[2][r] * p.z - 2 * shift[1u << r] / norm;
        CHECK(closed == Approx(direct[r]).margin(1e-9));
      }
    }
    // L^T L = s^2 I exactly when the scales agree; with different scales (and rotations) it is not a multiple
    // of I: the blend is then only close to a similarity (docs/skinning.md).
    std::array<std::array<double, 3>, 3> g{};
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) g[a][b] = L[a][0] * L[b][0] + L[a][1] * L[b][1] + L[a][2] * L[b][2];
    const double off = std::max({std::abs(g[0][1]), std::abs(g[0][2]), std::abs(g[1][2])});
    const double spread = std::max({std::abs(g[0][0] - g[1][1]), std::abs(g[0][0] - g[2][2]), std::abs(g[1][1] - g[2][2])});
    if (same_scale) {
      CHECK(off < 1e-6);
      CHECK(spread < 1e-6);
      CHECK(g[0][0] == Approx(static_cast<double>(xs[0].scale) * xs[0].scale).epsilon(1e-6));
    } else {
      CHECK(std::max(off, spread) > 1e-4);
    }
  }
}
