// Every generated kernel against the naive oracle (tests/oracle) evaluating the same math on random inputs,
// in double precision (relative error <= 1e-12), and `cgagen --eval` against the compiled kernels.
#include <catch2/catch.hpp>

#include <array>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <oracle/multivector.hpp>

#include "motor_from_trs.hpp"
#include "motor_lerp_paper.hpp"
#include "motor_mul.hpp"
#include "motor_reverse.hpp"
#include "motor_to_matrix.hpp"
#include "plane_distance.hpp"
#include "transform_point.hpp"
#include "translator_inverse.hpp"

using MV = oracle::MV<double>;
namespace k = cga::kernels;

namespace {

const std::vector<std::string> kMotorBlades = {"1", "e1^e2", "e1^e3", "e1^einf", "e2^e3", "e2^einf", "e3^einf",
                                               "einf^e0", "e1^e2^e3^einf", "e1^e2^einf^e0", "e1^e3^einf^e0",
                                               "e2^e3^einf^e0"};
const std::vector<std::string> kLerpBlades = {"1", "e1^e2", "e1^e3", "e1^einf", "e2^e3", "e2^einf", "e3^einf",
                                              "e1^e2^e3^einf"};

MV from_coeffs(const double* c, const std::vector<std::string>& blades) {
  MV m;
  for (size_t i = 0; i < blades.size(); ++i) m += c[i] * oracle::null_blade<double>(blades[i]);
  return m;
}

template <size_t N>
void check_against(const double* got, const std::array<std::string_view, N>& blades, const MV& want) {
  auto c = oracle::to_null_basis(want);
  double scale = 1;
  for (double v : c) scale = std::max(scale, std::abs(v));
  const auto& names = oracle::null_blade_names();
  for (size_t i = 0; i < N; ++i) {
    size_t j = 0;
    while (names[j] != blades[i]) ++j;
    INFO("blade " << blades[i] << ": kernel " << got[i] << ", oracle " << c[j]);
    REQUIRE(std::abs(got[i] - c[j]) <= 1e-12 * scale);
  }
}

struct Rng {
  std::mt19937_64 gen{12345};
  double operator()(double lo = -2, double hi = 2) { return std::uniform_real_distribution<double>(lo, hi)(gen); }
  template <size_t N>
  std::array<double, N> array() {
    std::array<double, N> a;
    for (auto& v : a) v = (*this)();
    return a;
  }
};

const MV einf = oracle::einf<double>(), e0 = oracle::e0<double>();
constexpr int kTrials = 1000;

}  // namespace

TEST_CASE("transform_point = M X ~M", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto m = rng.array<12>();
    double x = rng(), y = rng(), z = rng(), P[4];
    k::transform_point(m.data(), x, y, z, P);
    MV M = from_coeffs(m.data(), kMotorBlades);
    check_against(P, k::transform_point_P_blades, M * oracle::up(x, y, z) * oracle::reverse(M));
  }
}

TEST_CASE("motor_mul = A B, motor_reverse = ~A", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto a = rng.array<12>(), b = rng.array<12>();
    double C[12], R[12];
    k::motor_mul(a.data(), b.data(), C);
    k::motor_reverse(a.data(), R);
    MV A = from_coeffs(a.data(), kMotorBlades), B = from_coeffs(b.data(), kMotorBlades);
    check_against(C, k::motor_mul_C_blades, A * B);
    check_against(R, k::motor_reverse_C_blades, oracle::reverse(A));
  }
}

TEST_CASE("motor_from_trs = T R D", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    double tx = rng(), ty = rng(), tz = rng(), rs = rng(), r12 = rng(), r13 = rng(), r23 = rng(), s = rng(0.1, 3);
    double M[12];
    k::motor_from_trs(tx, ty, tz, rs, r12, r13, r23, s, M);
    MV t = tx * oracle::e1<double>() + ty * oracle::e2<double>() + tz * oracle::e3<double>();
    MV T = MV::scalar(1.0) - 0.5 * (t * einf);
    MV R = rs * MV::scalar(1.0) + r12 * oracle::null_blade<double>("e1^e2") + r13 * oracle::null_blade<double>("e1^e3") +
           r23 * oracle::null_blade<double>("e2^e3");
    MV D = MV::scalar(1.0) + ((1 - s) / (1 + s)) * (einf ^ e0);
    check_against(M, k::motor_from_trs_M_blades, T * R * D);
  }
}

TEST_CASE("motor_lerp_paper = ((1-a)A + aB)(D1 + (D2-D1)a)", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto a = rng.array<8>(), b = rng.array<8>();
    double d1 = rng(0.1, 3), d2 = rng(0.1, 3), alpha = rng(0, 1), M[12];
    k::motor_lerp_paper(a.data(), b.data(), d1, d2, alpha, M);
    MV A = from_coeffs(a.data(), kLerpBlades), B = from_coeffs(b.data(), kLerpBlades);
    MV D1 = MV::scalar(1.0) + ((1 - d1) / (1 + d1)) * (einf ^ e0), D2 = MV::scalar(1.0) + ((1 - d2) / (1 + d2)) * (einf ^ e0);
    check_against(M, k::motor_lerp_paper_M_blades, (A * (1 - alpha) + B * alpha) * (D1 + (D2 - D1) * alpha));
  }
}

TEST_CASE("motor_to_matrix columns = E(M e_i ~M)/w", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto m = rng.array<12>();
    m[0] += 3;  // keep the weight away from 0
    double c1[3], c2[3], c3[3], t[3];
    k::motor_to_matrix(m.data(), c1, c2, c3, t);
    MV M = from_coeffs(m.data(), kMotorBlades), Mr = oracle::reverse(M);
    MV P0 = M * e0 * Mr;
    double w = oracle::scalar_part(oracle::inner(einf ^ P0, einf ^ e0));
    check_against(c1, k::motor_to_matrix_c1_blades, (M * oracle::e1<double>() * Mr) / w);
    check_against(c2, k::motor_to_matrix_c2_blades, (M * oracle::e2<double>() * Mr) / w);
    check_against(c3, k::motor_to_matrix_c3_blades, (M * oracle::e3<double>() * Mr) / w);
    check_against(t, k::motor_to_matrix_t_blades, P0 / w);
  }
}

TEST_CASE("plane_distance: plane = *(P1^P2^P3^einf), d = plane . X", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto p = rng.array<12>();
    std::array<double, k::plane_distance_plane_blades.size()> plane;
    double d[1];
    k::plane_distance(p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8], p[9], p[10], p[11], plane.data(), d);
    MV pl = oracle::dual(oracle::up(p[0], p[1], p[2]) ^ oracle::up(p[3], p[4], p[5]) ^ oracle::up(p[6], p[7], p[8]) ^
                         einf);
    check_against(plane.data(), k::plane_distance_plane_blades, pl);
    check_against(d, k::plane_distance_d_blades, oracle::inner(pl, oracle::up(p[9], p[10], p[11])));
  }
}

TEST_CASE("translator_inverse: both inverses undo T", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    double tx = rng(), ty = rng(), tz = rng(), x = rng(), y = rng(), z = rng();
    std::array<double, k::translator_inverse_moved_blades.size()> moved;
    std::array<double, k::translator_inverse_back_blades.size()> back;
    std::array<double, k::translator_inverse_back2_blades.size()> back2;
    std::array<double, k::translator_inverse_one_blades.size()> one;
    std::array<double, k::translator_inverse_one2_blades.size()> one2;
    k::translator_inverse(tx, ty, tz, x, y, z, moved.data(), back.data(), back2.data(), one.data(), one2.data());
    check_against(moved.data(), k::translator_inverse_moved_blades, oracle::up(x + tx, y + ty, z + tz));
    check_against(back.data(), k::translator_inverse_back_blades, oracle::up(x, y, z));
    check_against(back2.data(), k::translator_inverse_back2_blades, oracle::up(x, y, z));
    check_against(one.data(), k::translator_inverse_one_blades, MV::scalar(1.0));
    check_against(one2.data(), k::translator_inverse_one2_blades, MV::scalar(1.0));
  }
}

TEST_CASE("cgagen --eval agrees with the compiled kernel", "[kernels][cli]") {
  Rng rng;
  for (int n = 0; n < 3; ++n) {
    auto m = rng.array<12>();
    double x = rng(), y = rng(), z = rng(), P[4];
    k::transform_point(m.data(), x, y, z, P);
    std::ostringstream cmd;
    cmd.precision(17);
    cmd << CGAGEN_EXE << " " << CGA_SOURCE_DIR << "/runtime/scripts/transform_point.clu --eval M=";
    for (size_t i = 0; i < 12; ++i) cmd << (i ? "," : "") << m[i];
    cmd << " x=" << x << " y=" << y << " z=" << z;
    FILE* pipe = popen(cmd.str().c_str(), "r");
    REQUIRE(pipe);
    std::string out;
    char buf[256];
    while (fgets(buf, sizeof buf, pipe)) out += buf;
    REQUIRE(pclose(pipe) == 0);
    std::istringstream in(out);
    for (size_t i = 0; i < 4; ++i) {
      std::string output, blade;
      double v = 0;
      REQUIRE(in >> output >> blade >> v);
      CHECK(output == "P");
      CHECK(blade == k::transform_point_P_blades[i]);
      CHECK(v == Approx(P[i]).epsilon(1e-13).margin(1e-13));
    }
  }
}
