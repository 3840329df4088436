// Every generated kernel against the naive oracle (tests/oracle) evaluating the same math on random inputs:
// the runtime kernels (generated/) in four forms, the C++ header's double and float overloads and the CUDA
// header's (generated/*.cuh, compiled here as plain C++ with its qualifiers defined away) double and float
// overloads, and the test scripts' kernels (tests/gen/scripts) in double; and `cgagen --eval` against the
// compiled kernels. Every output blade must equal the oracle's coefficient (relative error <= 1e-12 in
// double, 1e-5 in float), and every blade a kernel does not output must be zero in the oracle, unless the
// script drops it on purpose (the einf part of a moved point, say), which the test then names.
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <random>
#include <sstream>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <oracle/multivector.hpp>

#include "circle3.hpp"
#include "motor_from_trs.hpp"
#include "motor_lerp_paper.hpp"
#include "motor_mul.hpp"
#include "motor_mul_rigid.hpp"
#include "motor_reverse.hpp"
#include "motor_split_mul.hpp"
#include "motor_split_to_matrix.hpp"
#include "motor_to_matrix.hpp"
#include "paper_a1.hpp"
#include "paper_motor.hpp"
#include "plane_distance.hpp"
#include "rotor_n3.hpp"
#include "transform_point.hpp"
#include "transform_point_split.hpp"
#include "transform_point_staged.hpp"
#include "translator_inverse.hpp"

// The CUDA kernels as host C++: the same functions in namespace cuh::cga::kernels (their standard headers
// are already included above, so the includes inside the namespace add nothing).
namespace cuh {
#define __host__
#define __device__
#define __forceinline__ inline
#include "motor_from_trs.cuh"
#include "motor_lerp_paper.cuh"
#include "motor_mul.cuh"
#include "motor_mul_rigid.cuh"
#include "motor_reverse.cuh"
#include "motor_to_matrix.cuh"
#include "transform_point.cuh"
#include "transform_point_staged.cuh"
#undef __host__
#undef __device__
#undef __forceinline__
}  // namespace cuh

// The staged forms (built by tests/kernels/CMakeLists.txt): NAME_prepare and NAME, named as the
// unstaged kernels, so in their own namespace (the headers' standard includes are already done above).
namespace staged {
#include STAGED_TRANSFORM_POINT
#include STAGED_PAPER_A1
}  // namespace staged

using MV = oracle::MV<double>;
namespace k = cga::kernels;

namespace {

const std::vector<std::string> kMotorBlades = {"1", "e1^e2", "e1^e3", "e1^einf", "e2^e3", "e2^einf", "e3^einf",
                                               "einf^e0", "e1^e2^e3^einf", "e1^e2^einf^e0", "e1^e3^einf^e0",
                                               "e2^e3^einf^e0"};
const std::vector<std::string> kLerpBlades = {"1", "e1^e2", "e1^e3", "e1^einf", "e2^e3", "e2^einf", "e3^einf",
                                              "e1^e2^e3^einf"};

template <class T>
MV from_coeffs(const T* c, const std::vector<std::string>& blades) {
  MV m;
  for (size_t i = 0; i < blades.size(); ++i) m += static_cast<double>(c[i]) * oracle::null_blade<double>(blades[i]);
  return m;
}

// The kernel's outputs `got` over `blades` against the oracle's `want`: each listed blade within
// tol * max(1, largest coefficient of want), and every other blade of want zero within the same bound,
// except the blades in `dropped` (what the script leaves out on purpose).
// got (the staged kernel) against want (the unstaged one): each value within tol * max(1, largest |want|).
template <class T, size_t N>
void check_same(const T (&got)[N], const T (&want)[N], double tol) {
  double scale = 1;
  for (T v : want) scale = std::max(scale, std::abs(static_cast<double>(v)));
  for (size_t i = 0; i < N; ++i) {
    INFO("value " << i << ": staged " << got[i] << ", unstaged " << want[i]);
    REQUIRE(std::abs(static_cast<double>(got[i]) - static_cast<double>(want[i])) <= tol * scale);
  }
}

template <class T, size_t N>
void check_against(const T* got, const std::array<std::string_view, N>& blades, const MV& want, double tol = 1e-12,
                   const std::vector<std::string_view>& dropped = {}) {
  auto c = oracle::to_null_basis(want);
  double scale = 1;
  for (double v : c) scale = std::max(scale, std::abs(v));
  const auto& names = oracle::null_blade_names();
  std::vector<bool> listed(names.size(), false);
  for (size_t i = 0; i < N; ++i) {
    size_t j = 0;
    while (j < names.size() && names[j] != blades[i]) ++j;
    REQUIRE(j < names.size());
    listed[j] = true;
    INFO("blade " << blades[i] << ": kernel " << got[i] << ", oracle " << c[j]);
    REQUIRE(std::abs(static_cast<double>(got[i]) - c[j]) <= tol * scale);
  }
  for (size_t j = 0; j < names.size(); ++j) {
    if (listed[j] || std::find(dropped.begin(), dropped.end(), names[j]) != dropped.end()) continue;
    INFO("blade " << names[j] << " is not among the kernel's outputs, but the oracle has " << c[j]);
    REQUIRE(std::abs(c[j]) <= tol * scale);
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
  // N inputs in the kernel's precision (the oracle then works on exactly these values).
  template <class T, size_t N>
  std::array<T, N> array_of(double lo = -2, double hi = 2) {
    std::array<T, N> a;
    for (auto& v : a) v = static_cast<T>((*this)(lo, hi));
    return a;
  }
};

const MV einf = oracle::einf<double>(), e0 = oracle::e0<double>();
constexpr int kTrials = 1000;

// The runtime kernels in one form: the C++ header's (cga::kernels) or the CUDA header's (cuh::cga::kernels).
#define CGA_KERNEL_SET(Set, ns, label)                                                                  \
  struct Set {                                                                                            \
    static constexpr const char* name = label;                                                            \
    template <class... A> static void transform_point(A... a) { ns::transform_point(a...); }             \
    template <class... A> static void motor_mul(A... a) { ns::motor_mul(a...); }                         \
    template <class... A> static void motor_mul_rigid(A... a) { ns::motor_mul_rigid(a...); }             \
    template <class... A> static void motor_reverse(A... a) { ns::motor_reverse(a...); }                 \
    template <class... A> static void motor_from_trs(A... a) { ns::motor_from_trs(a...); }               \
    template <class... A> static void motor_lerp_paper(A... a) { ns::motor_lerp_paper(a...); }           \
    template <class... A> static void motor_to_matrix(A... a) { ns::motor_to_matrix(a...); }             \
  };
CGA_KERNEL_SET(CppKernels, cga::kernels, ".hpp")
CGA_KERNEL_SET(CudaKernels, cuh::cga::kernels, ".cuh")
#undef CGA_KERNEL_SET

template <class S, class T>
struct Form {
  using Kernels = S;
  using Real = T;
  // Relative tolerance: double rounding of a few hundred operations, or float's.
  static constexpr double tol = std::is_same_v<T, double> ? 1e-12 : 1e-5;
};
using CppDouble = Form<CppKernels, double>;
using CppFloat = Form<CppKernels, float>;
using CudaDouble = Form<CudaKernels, double>;
using CudaFloat = Form<CudaKernels, float>;

// An exact motor T R D (rotor not normalized) from random parameters, as 12 coefficients in precision T.
template <class T>
std::array<T, 12> random_exact_motor(Rng& rng) {
  MV t = rng() * oracle::e1<double>() + rng() * oracle::e2<double>() + rng() * oracle::e3<double>();
  MV T_ = MV::scalar(1.0) - 0.5 * (t * einf);
  MV R = rng() * MV::scalar(1.0) + rng() * oracle::null_blade<double>("e1^e2") +
         rng() * oracle::null_blade<double>("e1^e3") + rng() * oracle::null_blade<double>("e2^e3");
  const double s = rng(0.1, 3);
  MV D = MV::scalar(1.0) + ((1 - s) / (1 + s)) * (einf ^ e0);
  const auto c = oracle::to_null_basis(T_ * R * D);
  const auto& names = oracle::null_blade_names();
  std::array<T, 12> m;
  for (size_t i = 0; i < 12; ++i)
    m[i] = static_cast<T>(c[std::find(names.begin(), names.end(), kMotorBlades[i]) - names.begin()]);
  return m;
}

}  // namespace

#define KERNEL_FORMS CppDouble, CppFloat, CudaDouble, CudaFloat

TEST_CASE("the CUDA header lists the C++ header's blades", "[kernels][cuda]") {
  CHECK(cuh::cga::kernels::transform_point_P_blades == k::transform_point_P_blades);
  CHECK(cuh::cga::kernels::motor_mul_C_blades == k::motor_mul_C_blades);
  CHECK(cuh::cga::kernels::motor_mul_rigid_C_blades == k::motor_mul_rigid_C_blades);
  CHECK(cuh::cga::kernels::motor_reverse_C_blades == k::motor_reverse_C_blades);
  CHECK(cuh::cga::kernels::motor_from_trs_M_blades == k::motor_from_trs_M_blades);
  CHECK(cuh::cga::kernels::motor_lerp_paper_M_blades == k::motor_lerp_paper_M_blades);
  CHECK(cuh::cga::kernels::motor_to_matrix_c1_blades == k::motor_to_matrix_c1_blades);
  CHECK(cuh::cga::kernels::motor_to_matrix_t_blades == k::motor_to_matrix_t_blades);
}

TEMPLATE_TEST_CASE("transform_point = M X ~M", "[kernels]", KERNEL_FORMS) {
  using T = typename TestType::Real;
  using K = typename TestType::Kernels;
  INFO(K::name);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    // Any 12 coefficients: the point blades, but also a pseudoscalar part the kernel leaves out; an exact
    // motor: a point, of which the kernel leaves out only the einf part (1/2 |x|^2 times the weight).
    const bool exact = n % 2;
    auto m = exact ? random_exact_motor<T>(rng) : rng.template array_of<T, 12>();
    auto p = rng.template array_of<T, 3>();
    T P[4];
    K::transform_point(m.data(), p[0], p[1], p[2], P);
    MV M = from_coeffs(m.data(), kMotorBlades);
    const MV X = oracle::up(double(p[0]), double(p[1]), double(p[2]));
    INFO((exact ? "exact motor" : "any 12 coefficients"));
    if (exact)
      check_against(P, k::transform_point_P_blades, M * X * oracle::reverse(M), TestType::tol, {"einf"});
    else
      check_against(P, k::transform_point_P_blades, M * X * oracle::reverse(M), TestType::tol,
                    {"einf", "e1^e2^e3^einf^e0"});
  }
}

TEMPLATE_TEST_CASE("motor_mul = A B, motor_reverse = ~A", "[kernels]", KERNEL_FORMS) {
  using T = typename TestType::Real;
  using K = typename TestType::Kernels;
  INFO(K::name);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto a = rng.template array_of<T, 12>(), b = rng.template array_of<T, 12>();
    T C[12], R[12];
    K::motor_mul(a.data(), b.data(), C);
    K::motor_reverse(a.data(), R);
    MV A = from_coeffs(a.data(), kMotorBlades), B = from_coeffs(b.data(), kMotorBlades);
    check_against(C, k::motor_mul_C_blades, A * B, TestType::tol);
    check_against(R, k::motor_reverse_C_blades, oracle::reverse(A), TestType::tol);
  }
}

TEMPLATE_TEST_CASE("motor_mul_rigid = A B on the 8 rigid blades", "[kernels]", KERNEL_FORMS) {
  using T = typename TestType::Real;
  using K = typename TestType::Kernels;
  INFO(K::name);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto a = rng.template array_of<T, 8>(), b = rng.template array_of<T, 8>();
    T C[8];
    K::motor_mul_rigid(a.data(), b.data(), C);
    check_against(C, k::motor_mul_rigid_C_blades, from_coeffs(a.data(), kLerpBlades) * from_coeffs(b.data(), kLerpBlades),
                  TestType::tol);
  }
}

TEMPLATE_TEST_CASE("motor_from_trs = T R D", "[kernels]", KERNEL_FORMS) {
  using T = typename TestType::Real;
  using K = typename TestType::Kernels;
  INFO(K::name);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    const auto in = rng.template array_of<T, 7>();
    const T s = static_cast<T>(rng(0.1, 3));
    T M[12];
    K::motor_from_trs(in[0], in[1], in[2], in[3], in[4], in[5], in[6], s, M);
    const double tx = in[0], ty = in[1], tz = in[2], rs = in[3], r12 = in[4], r13 = in[5], r23 = in[6], sd = s;
    MV t = tx * oracle::e1<double>() + ty * oracle::e2<double>() + tz * oracle::e3<double>();
    MV T_ = MV::scalar(1.0) - 0.5 * (t * einf);
    MV R = rs * MV::scalar(1.0) + r12 * oracle::null_blade<double>("e1^e2") + r13 * oracle::null_blade<double>("e1^e3") +
           r23 * oracle::null_blade<double>("e2^e3");
    MV D = MV::scalar(1.0) + ((1 - sd) / (1 + sd)) * (einf ^ e0);
    check_against(M, k::motor_from_trs_M_blades, T_ * R * D, TestType::tol);
  }
}

TEMPLATE_TEST_CASE("motor_lerp_paper = ((1-a)A + aB)(D1 + (D2-D1)a)", "[kernels]", KERNEL_FORMS) {
  using T = typename TestType::Real;
  using K = typename TestType::Kernels;
  INFO(K::name);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto a = rng.template array_of<T, 8>(), b = rng.template array_of<T, 8>();
    const T d1 = static_cast<T>(rng(0.1, 3)), d2 = static_cast<T>(rng(0.1, 3)), alpha = static_cast<T>(rng(0, 1));
    T M[12];
    K::motor_lerp_paper(a.data(), b.data(), d1, d2, alpha, M);
    MV A = from_coeffs(a.data(), kLerpBlades), B = from_coeffs(b.data(), kLerpBlades);
    const double d1d = d1, d2d = d2, al = alpha;
    MV D1 = MV::scalar(1.0) + ((1 - d1d) / (1 + d1d)) * (einf ^ e0),
       D2 = MV::scalar(1.0) + ((1 - d2d) / (1 + d2d)) * (einf ^ e0);
    check_against(M, k::motor_lerp_paper_M_blades, (A * (1 - al) + B * al) * (D1 + (D2 - D1) * al), TestType::tol);
  }
}

TEMPLATE_TEST_CASE("motor_to_matrix columns = E(M e_i ~M)/w", "[kernels]", KERNEL_FORMS) {
  using T = typename TestType::Real;
  using K = typename TestType::Kernels;
  INFO(K::name);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    // As for transform_point: any 12 coefficients (weight kept away from 0) or an exact motor.
    const bool exact = n % 2;
    std::array<T, 12> m;
    if (exact) {
      do m = random_exact_motor<T>(rng);
      while (std::abs(static_cast<double>(m[0])) < 0.3);  // the weight grows with the rotor's norm
    } else {
      m = rng.template array_of<T, 12>();
      m[0] += 3;  // keep the weight away from 0
    }
    T c1[3], c2[3], c3[3], t[3];
    K::motor_to_matrix(m.data(), c1, c2, c3, t);
    MV M = from_coeffs(m.data(), kMotorBlades), Mr = oracle::reverse(M);
    MV P0 = M * e0 * Mr;
    double w = oracle::scalar_part(oracle::inner(einf ^ P0, einf ^ e0));
    INFO((exact ? "exact motor" : "any 12 coefficients"));
    // The columns drop their einf part (it never reaches x, y, z), t its e0 part (the weight, 1 here);
    // any 12 coefficients also give a pseudoscalar part, which the script's (einf^P0).(einf^e0) removes.
    const std::vector<std::string_view> column_drop =
        exact ? std::vector<std::string_view>{"einf"} : std::vector<std::string_view>{"einf", "e1^e2^e3^einf^e0"};
    const std::vector<std::string_view> t_drop = exact ? std::vector<std::string_view>{"einf", "e0"}
                                                       : std::vector<std::string_view>{"einf", "e0", "e1^e2^e3^einf^e0"};
    check_against(c1, k::motor_to_matrix_c1_blades, (M * oracle::e1<double>() * Mr) / w, TestType::tol, column_drop);
    check_against(c2, k::motor_to_matrix_c2_blades, (M * oracle::e2<double>() * Mr) / w, TestType::tol, column_drop);
    check_against(c3, k::motor_to_matrix_c3_blades, (M * oracle::e3<double>() * Mr) / w, TestType::tol, column_drop);
    check_against(t, k::motor_to_matrix_t_blades, P0 / w, TestType::tol, t_drop);
  }
}

// Split form (tests/kernels/scripts/motor_split_to_matrix.clu, runtime/scripts/transform_point_split.clu): G = a + b, H = a - b of the blades 1 e12 e13 e23 and
// their einf^e0 multiples, U the einf blades e1inf e2inf e3inf e123inf.
namespace {
void split(const double* m, double* g, double* h, double* u) {
  const int a[4] = {0, 1, 2, 4}, b[4] = {7, 9, 10, 11}, e[4] = {3, 5, 6, 8};
  for (int i = 0; i < 4; ++i) g[i] = m[a[i]] + m[b[i]], h[i] = m[a[i]] - m[b[i]], u[i] = m[e[i]];
}
}  // namespace

TEST_CASE("motor_split_to_matrix on the split form = motor_to_matrix's E(M e_i ~M)/w", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto m = rng.array<12>();
    m[0] += 3;  // keep the weight away from 0
    double g[4], h[4], u[4], c1[3], c2[3], c3[3], t[3];
    split(m.data(), g, h, u);
    k::motor_split_to_matrix(g, h, u, c1, c2, c3, t);
    MV M = from_coeffs(m.data(), kMotorBlades), Mr = oracle::reverse(M);
    MV P0 = M * e0 * Mr;
    double w = oracle::scalar_part(oracle::inner(einf ^ P0, einf ^ e0));
    // As motor_to_matrix on any 12 coefficients: the columns drop einf and the pseudoscalar, t also e0.
    const std::vector<std::string_view> column_drop = {"einf", "e1^e2^e3^einf^e0"};
    const std::vector<std::string_view> t_drop = {"einf", "e0", "e1^e2^e3^einf^e0"};
    check_against(c1, k::motor_split_to_matrix_c1_blades, (M * oracle::e1<double>() * Mr) / w, 1e-12, column_drop);
    check_against(c2, k::motor_split_to_matrix_c2_blades, (M * oracle::e2<double>() * Mr) / w, 1e-12, column_drop);
    check_against(c3, k::motor_split_to_matrix_c3_blades, (M * oracle::e3<double>() * Mr) / w, 1e-12, column_drop);
    check_against(t, k::motor_split_to_matrix_t_blades, P0 / w, 1e-12, t_drop);
  }
}

TEMPLATE_TEST_CASE("staged transform_point_split: prepare(G, H, U) = the hand motor_split_to_matrix, body = the "
                   "matrix on the point and the normal = the oracle", "[kernels][stage]", double, float) {
  // Skinning's motor -> 3x4 (CPU, GL, CUDA, web) is this prepare; motor_split_to_matrix.clu is the hand split
  // it replaced (tests/kernels/scripts).
  using T = TestType;
  const double tol = std::is_same_v<T, double> ? 1e-12 : 2e-5;
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto md = rng.array<12>();
    md[0] += 3;  // keep the weight away from 0
    double gd[4], hd[4], ud[4];
    split(md.data(), gd, hd, ud);
    T g[4], h[4], u[4];
    for (int i = 0; i < 4; ++i) g[i] = T(gd[i]), h[i] = T(hd[i]), u[i] = T(ud[i]);
    T prepared[k::transform_point_split_prepare_prepared_blades.size()], c[4][3];
    static_assert(sizeof prepared / sizeof prepared[0] == 12);
    k::transform_point_split_prepare(g, h, u, prepared);
    k::motor_split_to_matrix(g, h, u, c[0], c[1], c[2], c[3]);
    INFO("trial " << n);
    // Row r of the prepared matrix: p.e<r>[1] (translation), p.e<r>[x], p.e<r>[y], p.e<r>[z].
    T got[12], want[12];
    for (int r = 0; r < 3; ++r) {
      REQUIRE(k::transform_point_split_prepare_prepared_blades[4 * r] == "p.e" + std::to_string(r + 1) + "[1]");
      for (int col = 0; col < 3; ++col) got[4 * r + col] = prepared[4 * r + 1 + col];
      got[4 * r + 3] = prepared[4 * r];
      for (int col = 0; col < 4; ++col) want[4 * r + col] = c[col][r];
    }
    check_same(got, want, tol);
    // The body: the point through the whole matrix, the normal through its linear part; against the oracle.
    auto p = rng.template array_of<T, 3>(), nv = rng.template array_of<T, 3>();
    T P[3], N[3];
    k::transform_point_split(prepared, p[0], p[1], p[2], nv[0], nv[1], nv[2], P, N);
    MV M = from_coeffs(md.data(), kMotorBlades), Mr = oracle::reverse(M);
    double w = oracle::scalar_part(oracle::inner(einf ^ (M * e0 * Mr), einf ^ e0));
    const MV X = oracle::up(double(p[0]), double(p[1]), double(p[2]));
    const MV V = double(nv[0]) * oracle::e1<double>() + double(nv[1]) * oracle::e2<double>() +
                 double(nv[2]) * oracle::e3<double>();
    check_against(P, k::transform_point_split_p_blades, (M * X * Mr) / w, 8 * tol,
                  {"einf", "e0", "e1^e2^e3^einf^e0"});
    check_against(N, k::transform_point_split_n_blades, (M * V * Mr) / w, 8 * tol, {"einf", "e1^e2^e3^einf^e0"});
  }
}

TEST_CASE("motor_split_mul = A B in split form", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    auto a = rng.array<12>(), b = rng.array<12>();
    double ga[4], ha[4], ua[4], gb[4], hb[4], ub[4], g[4], h[4], u[4];
    split(a.data(), ga, ha, ua);
    split(b.data(), gb, hb, ub);
    k::motor_split_mul(ga, ha, ua, gb, hb, ub, g, h, u);
    // Back to the 12 blades (a = (G + H)/2, b = (G - H)/2) and against the oracle's product.
    double c[12];
    const int ai[4] = {0, 1, 2, 4}, bi[4] = {7, 9, 10, 11}, ei[4] = {3, 5, 6, 8};
    for (int i = 0; i < 4; ++i) c[ai[i]] = 0.5 * (g[i] + h[i]), c[bi[i]] = 0.5 * (g[i] - h[i]), c[ei[i]] = u[i];
    std::array<std::string_view, 12> names;
    for (int i = 0; i < 12; ++i) names[i] = kMotorBlades[i];
    check_against(c, names, from_coeffs(a.data(), kMotorBlades) * from_coeffs(b.data(), kMotorBlades));
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

using Vec3 = std::array<double, 3>;
Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
Vec3 cross(const Vec3& a, const Vec3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// |got - want| <= tol * max(1, |want|), per component.
void check_close(const Vec3& got, const Vec3& want, double tol) {
  double scale = std::max({1.0, std::abs(want[0]), std::abs(want[1]), std::abs(want[2])});
  for (int i = 0; i < 3; ++i) {
    INFO("component " << i << ": got " << got[i] << ", want " << want[i]);
    REQUIRE(std::abs(got[i] - want[i]) <= tol * scale);
  }
}

TEST_CASE("circle3: m = -c einf c / ((c einf c).einf), r, circumcentre and radius of plain geometry", "[kernels]") {
  Rng rng;
  int checked = 0;
  for (int n = 0; n < kTrials; ++n) {
    Vec3 a{rng(), rng(), rng()}, b{rng(), rng(), rng()}, c{rng(), rng(), rng()};
    Vec3 u = sub(b, a), v = sub(c, a), w = cross(u, v);
    // Nearly collinear points have a far-away, ill-conditioned centre: compare well-shaped triangles only.
    if (dot(w, w) < 1e-2 * dot(u, u) * dot(v, v)) continue;
    ++checked;
    double m[5], r[1];
    k::circle3(a[0], a[1], a[2], b[0], b[1], b[2], c[0], c[1], c[2], m, r);
    MV C = oracle::dual(oracle::up(a) ^ oracle::up(b) ^ oracle::up(c));
    MV mtmp = C * einf * C;
    check_against(m, k::circle3_m_blades, -1.0 * mtmp / oracle::scalar_part(oracle::inner(mtmp, einf)));
    double ec = oracle::scalar_part(oracle::inner(einf, C));
    double rr[1] = {std::sqrt(std::abs(oracle::scalar_part(oracle::inner(C, C)) / (ec * ec)))};
    REQUIRE(std::abs(r[0] - rr[0]) <= 1e-12 * std::max(1.0, rr[0]));
    // Plain geometry: centre = a + (|u|^2 v x w + |v|^2 w x u) / (2 |w|^2), radius = |centre - a|.
    Vec3 t1 = cross(v, w), t2 = cross(w, u);
    double s = 2 * dot(w, w);
    Vec3 centre;
    for (int i = 0; i < 3; ++i) centre[i] = a[i] + (dot(u, u) * t1[i] + dot(v, v) * t2[i]) / s;
    REQUIRE(k::circle3_m_blades[4] == "e0");
    CHECK(std::abs(m[4] - 1) <= 1e-12);
    check_close({m[0], m[1], m[2]}, centre, 1e-10);
    Vec3 ac = sub(centre, a);
    CHECK(std::abs(r[0] - std::sqrt(dot(ac, ac))) <= 1e-10 * std::max(1.0, r[0]));
  }
  CHECK(checked > kTrials / 2);
}

TEST_CASE("paper_a1: the appendix's blended motor (4th-order exp) moves a point", "[kernels]") {
  Rng rng;
  auto exp4 = [](const MV& b) {  // the script's Exp_approx
    MV b2 = b * b;
    return MV::scalar(1.0) + b + b2 / 2.0 + b2 * b / 6.0 + b2 * b2 / 24.0;
  };
  for (int n = 0; n < kTrials; ++n) {
    Vec3 t1{rng(), rng(), rng()}, ax1{rng(), rng(), rng()}, t2{rng(), rng(), rng()}, ax2{rng(), rng(), rng()};
    double angle1 = rng(-3.2, 3.2), d1 = rng(0.1, 3), angle2 = rng(-3.2, 3.2), d2 = rng(0.1, 3), alpha = rng(0, 1);
    double X = rng(), Y = rng(), Z = rng(), P[4];
    k::paper_a1(t1[0], t1[1], t1[2], ax1[0], ax1[1], ax1[2], angle1, d1, t2[0], t2[1], t2[2], ax2[0], ax2[1], ax2[2],
                angle2, d2, alpha, X, Y, Z, P);
    auto motor = [&](const Vec3& t, const Vec3& ax, double angle) {
      MV tv = t[0] * oracle::e1<double>() + t[1] * oracle::e2<double>() + t[2] * oracle::e3<double>();
      MV T = MV::scalar(1.0) - 0.5 * (tv ^ einf);
      MV plane = oracle::dual(oracle::up(ax) ^ oracle::up(0.0, 0.0, 0.0) ^ einf);
      return T * exp4((-angle / 2) * plane);
    };
    auto dilation = [&](double d) { return MV::scalar(1.0) + ((1 - d) / (1 + d)) * (einf ^ e0); };
    MV TR = motor(t1, ax1, angle1) * (1 - alpha) + motor(t2, ax2, angle2) * alpha;
    MV D = dilation(d1) + (dilation(d2) - dilation(d1)) * alpha;
    MV F = TR * D;
    // The script outputs the point's e1 e2 e3 e0 (x, y, z, weight), not its einf part, nor the pseudoscalar
    // part that a blend of motors (not itself a versor) adds to F X ~F.
    check_against(P, k::paper_a1_vertexPos_blades, F * oracle::up(X, Y, Z) * oracle::reverse(F), 1e-12,
                  {"einf", "e1^e2^e3^einf^e0"});
  }
}

TEST_CASE("paper_motor: T R D with the exact exp moves points like GLM translate * rotate * scale", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    Vec3 t{rng(), rng(), rng()}, ax{rng(), rng(), rng()};
    double len = std::sqrt(dot(ax, ax));
    if (len < 0.1) continue;
    for (auto& x : ax) x /= len;  // the script's plane is n1 e23 + n2 e31 + n3 e12 only for a unit axis
    double angle = rng(-3.2, 3.2), d = rng(0.1, 3), X = rng(), Y = rng(), Z = rng(), P[4];
    k::paper_motor(t[0], t[1], t[2], ax[0], ax[1], ax[2], angle, d, X, Y, Z, P);
    MV tv = t[0] * oracle::e1<double>() + t[1] * oracle::e2<double>() + t[2] * oracle::e3<double>();
    MV T = MV::scalar(1.0) - 0.5 * (tv ^ einf);
    MV plane = oracle::dual(oracle::up(ax) ^ oracle::up(0.0, 0.0, 0.0) ^ einf);
    MV R = oracle::exp((-0.5 * angle) * plane);
    MV D = MV::scalar(1.0) + ((1 - d) / (1 + d)) * (einf ^ e0);
    MV M = T * R * D;
    check_against(P, k::paper_motor_P_blades, M * oracle::up(X, Y, Z) * oracle::reverse(M), 1e-12, {"einf"});
    // The moved point (weight = the e0 coefficient) against GLM in double precision.
    glm::dmat4 G = glm::translate(glm::dmat4(1.0), glm::dvec3(t[0], t[1], t[2])) *
                   glm::rotate(glm::dmat4(1.0), angle, glm::dvec3(ax[0], ax[1], ax[2])) *
                   glm::scale(glm::dmat4(1.0), glm::dvec3(d));
    glm::dvec4 g = G * glm::dvec4(X, Y, Z, 1.0);
    REQUIRE(k::paper_motor_P_blades[3] == "e0");
    check_close({P[0] / P[3], P[1] / P[3], P[2] / P[3]}, {g.x, g.y, g.z}, 1e-12);
  }
}

TEST_CASE("rotor_n3: T R X ~R ~T and M R, the point rotated about n (Rodrigues) and moved by t", "[kernels]") {
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    Vec3 nv{rng(), rng(), rng()};
    if (dot(nv, nv) < 1e-2) continue;
    double angle = rng(0, 6.3), tx = rng(), ty = rng(), tz = rng(), x = rng(), y = rng(), z = rng();
    auto m = rng.array<4>();
    double P[5], MR[4];
    k::rotor_n3(m.data(), nv[0], nv[1], nv[2], angle, tx, ty, tz, x, y, z, P, MR);
    double len = std::sqrt(dot(nv, nv));
    MV plane = (nv[0] / len) * oracle::null_blade<double>("e2^e3") - (nv[1] / len) * oracle::null_blade<double>("e1^e3") +
               (nv[2] / len) * oracle::null_blade<double>("e1^e2");  // e31 = -e13
    MV R = std::cos(angle / 2) * MV::scalar(1.0) - std::sin(angle / 2) * plane;
    MV tv = tx * oracle::e1<double>() + ty * oracle::e2<double>() + tz * oracle::e3<double>();
    MV T = MV::scalar(1.0) - 0.5 * (tv * einf);
    check_against(P, k::rotor_n3_P_blades, T * R * oracle::up(x, y, z) * oracle::reverse(R) * oracle::reverse(T));
    MV M = from_coeffs(m.data(), {"1", "e1^e2", "e1^e3", "e2^e3"});
    check_against(MR, k::rotor_n3_MR_blades, M * R);
    // Rodrigues: p' = p cos + (k x p) sin + k (k.p)(1 - cos), then + t.
    Vec3 kk{nv[0] / len, nv[1] / len, nv[2] / len}, p{x, y, z}, kxp = cross(kk, p);
    Vec3 want;
    for (int i = 0; i < 3; ++i)
      want[i] = p[i] * std::cos(angle) + kxp[i] * std::sin(angle) + kk[i] * dot(kk, p) * (1 - std::cos(angle));
    want = {want[0] + tx, want[1] + ty, want[2] + tz};
    REQUIRE(k::rotor_n3_P_blades[0] == "e1");
    check_close({P[0], P[1], P[2]}, want, 1e-12);
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

// ---- staged kernels: prepare once, then the per-element body ------------------------------------------


TEMPLATE_TEST_CASE("staged transform_point: prepare(M) then body = the unstaged kernel = the oracle",
                   "[kernels][stage]", double, float) {
  using T = TestType;
  const double tol = std::is_same_v<T, double> ? 1e-12 : 1e-5;
  namespace s = staged::cga::kernels;
  CHECK(s::transform_point_P_blades == k::transform_point_P_blades);
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    const bool exact = n % 2;
    auto m = exact ? random_exact_motor<T>(rng) : rng.template array_of<T, 12>();
    auto p = rng.template array_of<T, 3>();
    T prepared[s::transform_point_prepare_prepared_blades.size()], P[4], Q[4];
    s::transform_point_prepare(m.data(), prepared);
    s::transform_point(prepared, p[0], p[1], p[2], P);
    k::transform_point(m.data(), p[0], p[1], p[2], Q);
    INFO((exact ? "exact motor" : "any 12 coefficients") << ", trial " << n);
    check_same(P, Q, 2 * tol);
    const MV M = from_coeffs(m.data(), kMotorBlades);
    const MV X = oracle::up(double(p[0]), double(p[1]), double(p[2]));
    check_against(P, s::transform_point_P_blades, M * X * oracle::reverse(M), tol, {"einf", "e1^e2^e3^einf^e0"});
  }
}

TEMPLATE_TEST_CASE("the runtime's motor -> 3x4 (generated transform_point_staged's prepare, over its weight) = the "
                   "hand-derived motor_to_matrix", "[kernels][stage]", double, float) {
  // cga::motor_matrix reads these 13 prepared values (the 3x4 rows and the weight) and divides them by the
  // weight; motor_to_matrix.clu (tests/kernels/scripts) is the hand split it replaced.
  using T = TestType;
  const double tol = std::is_same_v<T, double> ? 1e-12 : 2e-5;
  REQUIRE(k::transform_point_staged_prepare_prepared_blades.size() == 13);
  CHECK(k::transform_point_staged_prepare_prepared_blades[12] == "P.e0");
  Rng rng;
  for (int n = 0; n < kTrials; ++n) {
    const bool exact = n % 2;
    std::array<T, 12> m;
    if (exact) {
      do m = random_exact_motor<T>(rng);
      while (std::abs(static_cast<double>(m[0])) < 0.3);
    } else {
      m = rng.template array_of<T, 12>();
      m[0] += 3;  // keep the weight away from 0
    }
    T prepared[13], cpu[13], c[4][3];
    k::transform_point_staged_prepare(m.data(), prepared);
    cuh::cga::kernels::transform_point_staged_prepare(m.data(), cpu);
    k::motor_to_matrix(m.data(), c[0], c[1], c[2], c[3]);
    INFO((exact ? "exact motor" : "any 12 coefficients") << ", trial " << n);
    for (int i = 0; i < 13; ++i) REQUIRE(prepared[i] == cpu[i]);  // the CUDA form is the same code
    // Row r of the prepared matrix: P.e<r>[1] (translation), P.e<r>[x], P.e<r>[y], P.e<r>[z].
    T got[12], want[12];
    for (int r = 0; r < 3; ++r) {
      for (int col = 0; col < 3; ++col) got[4 * r + col] = prepared[4 * r + 1 + col] / prepared[12];
      got[4 * r + 3] = prepared[4 * r] / prepared[12];
      for (int col = 0; col < 4; ++col) want[4 * r + col] = c[col][r];
    }
    check_same(got, want, tol);
    // And the body on the normalized values is the matrix times the point, w = 1.
    T normalized[13], P[4];
    for (int i = 0; i < 13; ++i) normalized[i] = prepared[i] / prepared[12];
    auto p = rng.template array_of<T, 3>();
    k::transform_point_staged(normalized, p[0], p[1], p[2], P);
    for (int r = 0; r < 3; ++r) {
      const double want_r = double(want[4 * r]) * p[0] + double(want[4 * r + 1]) * p[1] +
                            double(want[4 * r + 2]) * p[2] + double(want[4 * r + 3]);
      REQUIRE(std::abs(double(P[r]) - want_r) <= 8 * tol * std::max(1.0, std::abs(want_r)));
    }
    REQUIRE(std::abs(double(P[3]) - 1.0) <= tol);
  }
}

TEST_CASE("staged paper_a1: prepare(key parameters) then body(X, Y, Z) = the unstaged kernel = the oracle",
          "[kernels][stage]") {
  namespace s = staged::cga::kernels;
  Rng rng;
  auto exp4 = [](const MV& b) {
    MV b2 = b * b;
    return MV::scalar(1.0) + b + b2 / 2.0 + b2 * b / 6.0 + b2 * b2 / 24.0;
  };
  for (int n = 0; n < kTrials; ++n) {
    Vec3 t1{rng(), rng(), rng()}, ax1{rng(), rng(), rng()}, t2{rng(), rng(), rng()}, ax2{rng(), rng(), rng()};
    double angle1 = rng(-3.2, 3.2), d1 = rng(0.1, 3), angle2 = rng(-3.2, 3.2), d2 = rng(0.1, 3), alpha = rng(0, 1);
    double X = rng(), Y = rng(), Z = rng(), P[4], Q[4];
    double prepared[s::paper_a1_prepare_prepared_blades.size()];
    s::paper_a1_prepare(t1[0], t1[1], t1[2], ax1[0], ax1[1], ax1[2], angle1, d1, t2[0], t2[1], t2[2], ax2[0], ax2[1],
                        ax2[2], angle2, d2, alpha, prepared);
    s::paper_a1(prepared, X, Y, Z, P);
    k::paper_a1(t1[0], t1[1], t1[2], ax1[0], ax1[1], ax1[2], angle1, d1, t2[0], t2[1], t2[2], ax2[0], ax2[1], ax2[2],
                angle2, d2, alpha, X, Y, Z, Q);
    INFO("trial " << n);
    check_same(P, Q, 1e-12);
    auto motor = [&](const Vec3& t, const Vec3& ax, double angle) {
      MV tv = t[0] * oracle::e1<double>() + t[1] * oracle::e2<double>() + t[2] * oracle::e3<double>();
      MV T = MV::scalar(1.0) - 0.5 * (tv ^ einf);
      MV plane = oracle::dual(oracle::up(ax) ^ oracle::up(0.0, 0.0, 0.0) ^ einf);
      return T * exp4((-angle / 2) * plane);
    };
    auto dilation = [&](double d) { return MV::scalar(1.0) + ((1 - d) / (1 + d)) * (einf ^ e0); };
    MV TR = motor(t1, ax1, angle1) * (1 - alpha) + motor(t2, ax2, angle2) * alpha;
    MV D = dilation(d1) + (dilation(d2) - dilation(d1)) * alpha;
    MV F = TR * D;
    check_against(P, s::paper_a1_vertexPos_blades, F * oracle::up(X, Y, Z) * oracle::reverse(F), 1e-12,
                  {"einf", "e1^e2^e3^einf^e0"});
  }
}
