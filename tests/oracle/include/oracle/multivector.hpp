// The naive CGA oracle: a dense 32-coefficient multivector of R(4,1) over the ORTHONORMAL basis
// e1, e2, e3, ep (ep^2 = +1), em (em^2 = -1), templated on the scalar type.
//
// It exists so that everything the generator produces can be checked against an implementation that
// shares no code and no tables with it: every blade product is worked out at run time from bitmaps,
// a reordering sign and the metric. Coefficient index = bitmap (bit0 e1, bit1 e2, bit2 e3, bit3 ep,
// bit4 em). The generator's null basis (e1 e2 e3 einf e0, Gaalop order) is reached only through
// null_blade()/to_null_basis(), which build those blades here by outer products of einf = em + ep and
// e0 = (em - ep)/2.
//
// Speed is not a goal; clarity is. Products skip zero coefficients so sparse versors stay cheap.
#pragma once

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <ostream>
#include <random>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <utility>
#include <vector>

namespace oracle {

inline constexpr unsigned kDim = 5;          // basis vectors e1 e2 e3 ep em
inline constexpr unsigned kBlades = 32;      // 2^5
inline constexpr unsigned kPseudo = 0b11111; // e1 e2 e3 ep em

// ---------------------------------------------------------------------------------------------
// Blade arithmetic on bitmaps

inline int grade_of(unsigned bitmap) { return std::popcount(bitmap); }

// Square of basis vector i (0..4): +1 for e1 e2 e3 ep, -1 for em.
inline int metric(unsigned i) { return i == 4 ? -1 : 1; }

// Sign of moving the vectors of blade b (written in increasing index order) leftwards past those
// of blade a until the concatenation a b is in increasing order: every vector of a that has a
// higher index than a vector of b costs one swap.
inline int reorder_sign(unsigned a, unsigned b) {
  unsigned swaps = 0;
  for (unsigned x = a >> 1; x != 0; x >>= 1) swaps += static_cast<unsigned>(std::popcount(x & b));
  return (swaps & 1u) ? -1 : 1;
}

// Geometric product of two unit basis blades: result blade a XOR b, times this sign (the reordering,
// and the metric of every vector that a and b share and that therefore squares away).
inline int blade_product_sign(unsigned a, unsigned b) {
  int s = reorder_sign(a, b);
  const unsigned common = a & b;
  for (unsigned i = 0; i < kDim; ++i)
    if (common & (1u << i)) s *= metric(i);
  return s;
}

// ---------------------------------------------------------------------------------------------
// The multivector

template <class T>
struct MV {
  std::array<T, kBlades> c{};  // c[bitmap]

  static MV scalar(T s) {
    MV m;
    m.c[0] = s;
    return m;
  }
  static MV blade(unsigned bitmap, T coeff = T(1)) {
    if (bitmap >= kBlades) throw std::out_of_range("oracle::MV::blade: bitmap " + std::to_string(bitmap) + " > 31");
    MV m;
    m.c[bitmap] = coeff;
    return m;
  }
  T operator[](unsigned bitmap) const { return c.at(bitmap); }
  T& operator[](unsigned bitmap) { return c.at(bitmap); }
};

// Linear structure
template <class T>
MV<T> operator+(const MV<T>& a, const MV<T>& b) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) r.c[i] = a.c[i] + b.c[i];
  return r;
}
template <class T>
MV<T> operator-(const MV<T>& a, const MV<T>& b) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) r.c[i] = a.c[i] - b.c[i];
  return r;
}
template <class T>
MV<T> operator-(const MV<T>& a) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) r.c[i] = -a.c[i];
  return r;
}
template <class T>
MV<T> operator+(const MV<T>& a) {
  return a;
}
// The scalar is not deduced (type_identity), so 2 * A or 0.5f * A work for MV<double>.
template <class T>
MV<T> operator*(std::type_identity_t<T> s, const MV<T>& a) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) r.c[i] = s * a.c[i];
  return r;
}
template <class T>
MV<T> operator*(const MV<T>& a, std::type_identity_t<T> s) {
  return s * a;
}
template <class T>
MV<T> operator/(const MV<T>& a, std::type_identity_t<T> s) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) r.c[i] = a.c[i] / s;
  return r;
}
template <class T>
MV<T>& operator+=(MV<T>& a, const MV<T>& b) {
  return a = a + b;
}
template <class T>
MV<T>& operator-=(MV<T>& a, const MV<T>& b) {
  return a = a - b;
}

namespace detail {
// Sum over all pairs of nonzero blades of a and b of keep(ga, gb, gr) ? sign * a_i * b_j on blade i^j.
// Every bilinear product below is the geometric product with some blade pairs dropped by grade.
template <class T, class Keep>
MV<T> product(const MV<T>& a, const MV<T>& b, Keep keep) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) {
    if (a.c[i] == T(0)) continue;
    for (unsigned j = 0; j < kBlades; ++j) {
      if (b.c[j] == T(0)) continue;
      const unsigned k = i ^ j;
      if (!keep(grade_of(i), grade_of(j), grade_of(k))) continue;
      const T term = a.c[i] * b.c[j];
      if (blade_product_sign(i, j) > 0)
        r.c[k] += term;
      else
        r.c[k] -= term;
    }
  }
  return r;
}
}  // namespace detail

// Geometric product
template <class T>
MV<T> operator*(const MV<T>& a, const MV<T>& b) {
  return detail::product(a, b, [](int, int, int) { return true; });
}
template <class T>
MV<T>& operator*=(MV<T>& a, const MV<T>& b) {
  return a = a * b;
}

// Outer product: the grade k+l part of the product of a k-blade and an l-blade.
template <class T>
MV<T> operator^(const MV<T>& a, const MV<T>& b) {
  return detail::product(a, b, [](int k, int l, int g) { return g == k + l; });
}

// Left contraction: the grade l-k part for k <= l, else 0.
template <class T>
MV<T> lc(const MV<T>& a, const MV<T>& b) {
  return detail::product(a, b, [](int k, int l, int g) { return k <= l && g == l - k; });
}

// Right contraction: the grade k-l part for k >= l, else 0.
template <class T>
MV<T> rc(const MV<T>& a, const MV<T>& b) {
  return detail::product(a, b, [](int k, int l, int g) { return k >= l && g == k - l; });
}

// Gaalop's '.': zero if either factor is a scalar, else the grade |k-l| part.
template <class T>
MV<T> inner(const MV<T>& a, const MV<T>& b) {
  return detail::product(a, b, [](int k, int l, int g) { return k != 0 && l != 0 && g == std::abs(k - l); });
}

// Unary sign-per-grade operations
namespace detail {
template <class T, class SignOfGrade>
MV<T> by_grade(const MV<T>& a, SignOfGrade sign) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i) r.c[i] = sign(grade_of(i)) > 0 ? a.c[i] : -a.c[i];
  return r;
}
}  // namespace detail

template <class T>
MV<T> reverse(const MV<T>& a) {  // (-1)^(k(k-1)/2)
  return detail::by_grade(a, [](int k) { return ((k * (k - 1) / 2) % 2) ? -1 : 1; });
}
template <class T>
MV<T> involute(const MV<T>& a) {  // (-1)^k
  return detail::by_grade(a, [](int k) { return (k % 2) ? -1 : 1; });
}
template <class T>
MV<T> conjugate(const MV<T>& a) {  // reverse of the involution: (-1)^(k(k+1)/2)
  return detail::by_grade(a, [](int k) { return ((k * (k + 1) / 2) % 2) ? -1 : 1; });
}

template <class T>
MV<T> grade(const MV<T>& a, int k) {
  MV<T> r;
  for (unsigned i = 0; i < kBlades; ++i)
    if (grade_of(i) == k) r.c[i] = a.c[i];
  return r;
}

template <class T>
T scalar_part(const MV<T>& a) {
  return a.c[0];
}

// Basis and null vectors
template <class T>
MV<T> e1() {
  return MV<T>::blade(0b00001);
}
template <class T>
MV<T> e2() {
  return MV<T>::blade(0b00010);
}
template <class T>
MV<T> e3() {
  return MV<T>::blade(0b00100);
}
template <class T>
MV<T> ep() {
  return MV<T>::blade(0b01000);
}
template <class T>
MV<T> em() {
  return MV<T>::blade(0b10000);
}
template <class T>
MV<T> einf() {
  return em<T>() + ep<T>();
}
template <class T>
MV<T> e0() {
  return (em<T>() - ep<T>()) / T(2);
}

// e1 e2 e3 ep em, which equals e1^e2^e3^einf^e0 (einf^e0 = ep^em).
template <class T>
MV<T> pseudoscalar() {
  return e1<T>() * e2<T>() * e3<T>() * ep<T>() * em<T>();
}

// Gaalop's dual: A * (-(e1^e2^e3^einf^e0)).
template <class T>
MV<T> dual(const MV<T>& a) {
  return a * (-pseudoscalar<T>());
}

// Sum of |coefficient|: submultiplicative here (|AB|_1 <= |A|_1 |B|_1) because every blade product
// is a single blade with coefficient +-1. Used for tolerances and the exp stopping rule.
template <class T>
T norm1(const MV<T>& a) {
  T s = T(0);
  for (const T& x : a.c) s += std::abs(x);
  return s;
}

template <class T>
T max_abs(const MV<T>& a) {
  T m = T(0);
  for (const T& x : a.c) m = std::max(m, T(std::abs(x)));
  return m;
}

template <class T>
T max_abs_diff(const MV<T>& a, const MV<T>& b) {
  T m = T(0);
  for (unsigned i = 0; i < kBlades; ++i) m = std::max(m, T(std::abs(a.c[i] - b.c[i])));
  return m;
}

// ~V / <V ~V>. Throws std::domain_error when V ~V is not a scalar (V is no versor) or is zero (null
// versor); "not a scalar" allows the rounding a product of |V|_1^2 magnitude can carry.
template <class T>
MV<T> versor_inverse(const MV<T>& v) {
  const MV<T> rev = reverse(v);
  const MV<T> vv = v * rev;
  const T n = norm1(v);
  const T tol = T(1000) * std::numeric_limits<T>::epsilon() * std::max(T(1), n * n);
  for (unsigned i = 1; i < kBlades; ++i)
    if (std::abs(vv.c[i]) > tol)
      throw std::domain_error("oracle::versor_inverse: V~V has a non-scalar part (blade bitmap " + std::to_string(i) +
                              "), so V is not a versor");
  if (std::abs(vv.c[0]) <= tol) throw std::domain_error("oracle::versor_inverse: V~V is zero (null versor)");
  return rev / vv.c[0];
}

// exp(B) = sum_k B^k / k!, summed until a term is negligible next to the sum and the terms can only
// shrink from there on (k beyond |B|_1, so |B^k/k!|_1 decreases geometrically). Works for any
// multivector; plain series, so precision degrades for |B|_1 much larger than ~10.
template <class T>
MV<T> exp(const MV<T>& b) {
  const T n = norm1(b);
  const T eps = std::numeric_limits<T>::epsilon();
  MV<T> sum = MV<T>::scalar(T(1));
  MV<T> term = MV<T>::scalar(T(1));
  constexpr int kMaxTerms = 10000;
  for (int k = 1; k < kMaxTerms; ++k) {
    term = (term * b) / T(k);
    sum += term;
    const T tn = norm1(term);
    if (T(k) > n && tn <= eps * norm1(sum) / T(4)) return sum;
  }
  throw std::domain_error("oracle::exp: series did not converge (|B|_1 = " + std::to_string(double(n)) + ")");
}

// Conformal points
template <class T>
MV<T> up(T x, T y, T z) {
  return x * e1<T>() + y * e2<T>() + z * e3<T>() + (T(0.5) * (x * x + y * y + z * z)) * einf<T>() + e0<T>();
}

template <class T>
MV<T> up(const std::array<T, 3>& p) {
  return up(p[0], p[1], p[2]);
}

// Euclidean part of X divided by its weight -X.einf. Throws std::domain_error for weight 0.
template <class T>
std::array<T, 3> down(const MV<T>& X) {
  const T w = -scalar_part(inner(X, einf<T>()));
  if (w == T(0)) throw std::domain_error("oracle::down: weight -X.einf is zero (not a finite point)");
  return {X.c[0b001] / w, X.c[0b010] / w, X.c[0b100] / w};
}

// ---------------------------------------------------------------------------------------------
// The generator's null basis {e1, e2, e3, einf, e0}, rebuilt here from the orthonormal one.

// The five null-basis vector names, in the order Gaalop sorts by.
inline constexpr std::array<std::string_view, 5> kNullVectorNames = {"e1", "e2", "e3", "einf", "e0"};

template <class T>
MV<T> null_vector(unsigned i) {
  switch (i) {
    case 0: return e1<T>();
    case 1: return e2<T>();
    case 2: return e3<T>();
    case 3: return einf<T>();
    case 4: return e0<T>();
  }
  throw std::out_of_range("oracle::null_vector: index " + std::to_string(i) + " > 4");
}

// "1", or names from kNullVectorNames joined by '^' (any order, no repeats, optional spaces), e.g.
// "e1^einf", "e0^einf" (= -einf^e0). Built as the outer product of the named vectors.
template <class T>
MV<T> null_blade(std::string_view name) {
  auto trim = [](std::string_view s) {
    while (!s.empty() && s.front() == ' ') s.remove_prefix(1);
    while (!s.empty() && s.back() == ' ') s.remove_suffix(1);
    return s;
  };
  const std::string whole(name);
  if (trim(name) == "1") return MV<T>::scalar(T(1));
  MV<T> r = MV<T>::scalar(T(1));
  unsigned used = 0;
  std::string_view rest = name;
  while (true) {
    const std::size_t cut = rest.find('^');
    const std::string_view part = trim(rest.substr(0, cut));
    unsigned idx = kNullVectorNames.size();
    for (unsigned i = 0; i < kNullVectorNames.size(); ++i)
      if (kNullVectorNames[i] == part) idx = i;
    if (idx == kNullVectorNames.size())
      throw std::invalid_argument("oracle::null_blade: '" + std::string(part) + "' in '" + whole +
                                  "' is not one of e1 e2 e3 einf e0");
    if (used & (1u << idx))
      throw std::invalid_argument("oracle::null_blade: '" + std::string(part) + "' repeats in '" + whole + "'");
    used |= 1u << idx;
    r = r ^ null_vector<T>(idx);
    if (cut == std::string_view::npos) break;
    rest = rest.substr(cut + 1);
  }
  return r;
}

// The 32 null-basis blade names in Gaalop's order: 1; the vectors; then each grade's blades in
// lexicographic order of their factors' positions in kNullVectorNames.
inline const std::array<std::string, kBlades>& null_blade_names() {
  static const std::array<std::string, kBlades> names = [] {
    std::array<std::string, kBlades> out;
    std::vector<unsigned> masks;
    for (unsigned m = 0; m < kBlades; ++m) masks.push_back(m);
    // Within a grade, lexicographic order of the factor index lists equals ascending order of the
    // bit-reversed mask (lowest index most significant).
    auto bitrev = [](unsigned m) {
      unsigned r = 0;
      for (unsigned i = 0; i < kDim; ++i)
        if (m & (1u << i)) r |= 1u << (kDim - 1 - i);
      return r;
    };
    std::stable_sort(masks.begin(), masks.end(), [&](unsigned a, unsigned b) {
      if (grade_of(a) != grade_of(b)) return grade_of(a) < grade_of(b);
      return bitrev(a) > bitrev(b);
    });
    for (unsigned k = 0; k < kBlades; ++k) {
      std::string s;
      for (unsigned i = 0; i < kDim; ++i)
        if (masks[k] & (1u << i)) s += (s.empty() ? "" : "^") + std::string(kNullVectorNames[i]);
      out[k] = s.empty() ? "1" : s;
    }
    return out;
  }();
  return names;
}

// Multivector from coefficients on the 32 null-basis blades (Gaalop order).
template <class T>
MV<T> from_null_basis(const std::array<T, kBlades>& coeffs) {
  MV<T> r;
  for (unsigned k = 0; k < kBlades; ++k)
    if (coeffs[k] != T(0)) r += coeffs[k] * null_blade<T>(null_blade_names()[k]);
  return r;
}

// Coefficients of a on the 32 null-basis blades (Gaalop order): solves the 32x32 linear system whose
// columns are the null blades, by Gaussian elimination with partial pivoting.
template <class T>
std::array<T, kBlades> to_null_basis(const MV<T>& a) {
  std::array<std::array<T, kBlades + 1>, kBlades> m{};  // augmented matrix, row = orthonormal blade
  for (unsigned k = 0; k < kBlades; ++k) {
    const MV<T> col = null_blade<T>(null_blade_names()[k]);
    for (unsigned r = 0; r < kBlades; ++r) m[r][k] = col.c[r];
  }
  for (unsigned r = 0; r < kBlades; ++r) m[r][kBlades] = a.c[r];
  for (unsigned col = 0; col < kBlades; ++col) {
    unsigned piv = col;
    for (unsigned r = col + 1; r < kBlades; ++r)
      if (std::abs(m[r][col]) > std::abs(m[piv][col])) piv = r;
    if (m[piv][col] == T(0)) throw std::logic_error("oracle::to_null_basis: null blades are not a basis");
    std::swap(m[piv], m[col]);
    for (unsigned r = 0; r < kBlades; ++r) {
      if (r == col || m[r][col] == T(0)) continue;
      const T f = m[r][col] / m[col][col];
      for (unsigned c = col; c <= kBlades; ++c) m[r][c] -= f * m[col][c];
    }
  }
  std::array<T, kBlades> out{};
  for (unsigned k = 0; k < kBlades; ++k) out[k] = m[k][kBlades] / m[k][k];
  return out;
}

// ---------------------------------------------------------------------------------------------
// Printing (for test failure messages): nonzero orthonormal coefficients.

inline std::string orthonormal_blade_name(unsigned bitmap) {
  static constexpr std::array<const char*, kDim> names = {"e1", "e2", "e3", "ep", "em"};
  if (bitmap == 0) return "1";
  std::string s;
  for (unsigned i = 0; i < kDim; ++i)
    if (bitmap & (1u << i)) s += (s.empty() ? "" : "^") + std::string(names[i]);
  return s;
}

template <class T>
std::ostream& operator<<(std::ostream& os, const MV<T>& a) {
  bool any = false;
  for (unsigned i = 0; i < kBlades; ++i) {
    if (a.c[i] == T(0)) continue;
    os << (any ? " + " : "") << a.c[i] << "*" << orthonormal_blade_name(i);
    any = true;
  }
  if (!any) os << "0";
  return os;
}

// ---------------------------------------------------------------------------------------------
// Deterministic random inputs for tests.

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 0x5eed'c9a0'0000'0001ull) : gen_(seed) {}

  double uniform(double lo = -1.0, double hi = 1.0) { return std::uniform_real_distribution<double>(lo, hi)(gen_); }

  // All 32 coefficients uniform in [lo, hi].
  template <class T = double>
  MV<T> multivector(double lo = -1.0, double hi = 1.0) {
    MV<T> m;
    for (auto& x : m.c) x = T(uniform(lo, hi));
    return m;
  }

  template <class T = double>
  std::array<T, 3> vec3(double lo = -10.0, double hi = 10.0) {
    return {T(uniform(lo, hi)), T(uniform(lo, hi)), T(uniform(lo, hi))};
  }

  // A uniformly distributed unit 3-vector (normalized Gaussian).
  template <class T = double>
  std::array<T, 3> unit3() {
    std::normal_distribution<double> n(0.0, 1.0);
    for (;;) {
      const double x = n(gen_), y = n(gen_), z = n(gen_);
      const double l = std::sqrt(x * x + y * y + z * z);
      if (l > 1e-6) return {T(x / l), T(y / l), T(z / l)};
    }
  }

  std::mt19937_64& engine() { return gen_; }

 private:
  std::mt19937_64 gen_;
};

// Common versors, written exactly as the facts file states them.

// T = 1 - 1/2 t einf: moves points by +t.
template <class T>
MV<T> translator(T tx, T ty, T tz) {
  return MV<T>::scalar(T(1)) - T(0.5) * ((tx * e1<T>() + ty * e2<T>() + tz * e3<T>()) * einf<T>());
}

// R = cos(phi/2) - sin(phi/2) (n1 e23 + n2 e31 + n3 e12): right-handed rotation by phi about unit n.
template <class T>
MV<T> rotor(T nx, T ny, T nz, T phi) {
  const MV<T> plane = nx * (e2<T>() * e3<T>()) + ny * (e3<T>() * e1<T>()) + nz * (e1<T>() * e2<T>());
  return MV<T>::scalar(std::cos(phi / T(2))) - std::sin(phi / T(2)) * plane;
}

// D = 1 + (1-s)/(1+s) einf^e0: scales points about the origin by s (not normalized).
template <class T>
MV<T> dilator(T s) {
  return MV<T>::scalar(T(1)) + ((T(1) - s) / (T(1) + s)) * (einf<T>() ^ e0<T>());
}

// M X ~M followed by down(): the point a versor M maps (x, y, z) to.
template <class T>
std::array<T, 3> apply_to_point(const MV<T>& m, const std::array<T, 3>& p) {
  return down(m * up(p[0], p[1], p[2]) * reverse(m));
}

}  // namespace oracle
