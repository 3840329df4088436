// The naive oracle for ANY geometric algebra: signature (p, q, r) over a diagonal basis, plus a basis change
// to the user's vectors (null vectors such as CGA's einf, e0). Like multivector.hpp (the CGA oracle, whose
// API this file leaves alone) it shares no code and no tables with the generator: every product is worked
// out here from bitmaps, a reordering sign and the metric, in doubles; the inverse basis change is found by
// Gauss-Jordan elimination of the user-to-diagonal matrix (an n x n matrix, n <= 16, never 2^n x 2^n).
//
// Multivectors are sparse maps, so ccga's 65,536 blades cost only the blades a value has. A value is held
// over the DIAGONAL basis (bitmap over the diagonal vectors); to_user()/from_user() convert to and from
// coefficients on the user blades named "e1^einf" (user vectors in the user's order, joined by '^').
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace oracle::ga {

using Bits = std::uint32_t;
using MV = std::map<Bits, double>;  // diagonal blade bitmap -> coefficient

struct Algebra {
  std::vector<std::string> names;             // user vector names, in order
  std::vector<int> metric;                    // diagonal vector squares: +1, -1, 0
  std::vector<std::vector<double>> user_in_diag;  // row k: user vector k over the diagonal vectors
  std::vector<std::vector<double>> diag_in_user;  // the inverse (computed)

  int dim() const { return static_cast<int>(names.size()); }

  // Signature (p, q, r): diagonal vectors p of square +1, then q of -1, then r of 0; the user vectors are the
  // diagonal ones unless set_vector() changes them.
  static Algebra signature(int p, int q, int r, std::vector<std::string> names) {
    Algebra a;
    for (int i = 0; i < p; ++i) a.metric.push_back(1);
    for (int i = 0; i < q; ++i) a.metric.push_back(-1);
    for (int i = 0; i < r; ++i) a.metric.push_back(0);
    if (names.size() != a.metric.size()) throw std::invalid_argument("oracle::ga: names and signature differ");
    a.names = std::move(names);
    const int n = a.dim();
    a.user_in_diag.assign(n, std::vector<double>(n, 0.0));
    for (int k = 0; k < n; ++k) a.user_in_diag[k][k] = 1.0;
    a.invert();
    return a;
  }
  // Diagonal metric in any order (PGA's e0 first): metric[k] is the square of diagonal vector k.
  static Algebra diagonal(std::vector<int> metric, std::vector<std::string> names) {
    Algebra a = signature(0, 0, 0, {});
    a.metric = std::move(metric);
    a.names = std::move(names);
    const int n = a.dim();
    a.user_in_diag.assign(n, std::vector<double>(n, 0.0));
    for (int k = 0; k < n; ++k) a.user_in_diag[k][k] = 1.0;
    a.invert();
    return a;
  }
  // The basis change: user vector k = sum_d coeffs[d] * diagonal vector d.
  void set_vector(int k, std::vector<double> coeffs) {
    user_in_diag.at(k) = std::move(coeffs);
    invert();
  }
  // A null pair: user o = (em - ep)/2, user i = ep + em, for diagonal ep (+1) and em (-1).
  void null_pair(int o, int i, int ep, int em) {
    std::vector<double> vo(dim(), 0.0), vi(dim(), 0.0);
    vo[ep] = -0.5, vo[em] = 0.5, vi[ep] = 1.0, vi[em] = 1.0;
    user_in_diag.at(o) = vo;
    user_in_diag.at(i) = vi;
    invert();
  }

  void invert() {
    const int n = dim();
    std::vector<std::vector<double>> m(n, std::vector<double>(2 * n, 0.0));
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c < n; ++c) m[r][c] = user_in_diag[r][c];
      m[r][n + r] = 1.0;
    }
    for (int c = 0; c < n; ++c) {
      int piv = c;
      for (int r = c + 1; r < n; ++r)
        if (std::abs(m[r][c]) > std::abs(m[piv][c])) piv = r;
      if (std::abs(m[piv][c]) < 1e-12) throw std::invalid_argument("oracle::ga: the user vectors are not a basis");
      std::swap(m[piv], m[c]);
      const double p = m[c][c];
      for (double& x : m[c]) x /= p;
      for (int r = 0; r < n; ++r) {
        if (r == c || m[r][c] == 0.0) continue;
        const double f = m[r][c];
        for (int k = 0; k < 2 * n; ++k) m[r][k] -= f * m[c][k];
      }
    }
    // Rows of M^-1: M^-1[d][k] is diagonal vector d's coefficient... with M rows = user vectors over the
    // diagonal ones (u = M e), e = M^-1 u, so diagonal vector d over the user ones is row d of M^-1.
    diag_in_user.assign(n, std::vector<double>(n, 0.0));
    for (int d = 0; d < n; ++d)
      for (int k = 0; k < n; ++k) diag_in_user[d][k] = m[d][n + k];
  }
};

inline int reorder_sign(Bits a, Bits b) {
  unsigned swaps = 0;
  for (Bits x = a >> 1; x != 0; x >>= 1) swaps += static_cast<unsigned>(std::popcount(x & b));
  return (swaps & 1u) ? -1 : 1;
}

inline void add(MV& r, Bits b, double c) {
  if (c == 0.0) return;
  r[b] += c;
}

inline MV clean(MV m, double eps = 0.0) {
  for (auto it = m.begin(); it != m.end();) it = std::abs(it->second) <= eps ? m.erase(it) : std::next(it);
  return m;
}

enum class Op { Geometric, Outer, Inner };

// a (op) b over the diagonal basis. Inner: Gaalop's, the grade-|k-l| part of a blade pair's geometric
// product, 0 when either is a scalar.
inline MV product(const Algebra& alg, const MV& a, const MV& b, Op op) {
  MV r;
  for (const auto& [x, cx] : a)
    for (const auto& [y, cy] : b) {
      if (op == Op::Outer && (x & y)) continue;
      const int gx = std::popcount(x), gy = std::popcount(y);
      if (op == Op::Inner && (gx == 0 || gy == 0)) continue;
      double s = reorder_sign(x, y);
      for (int k = 0; k < alg.dim(); ++k)
        if ((x & y) & (1u << k)) s *= alg.metric[k];
      if (s == 0.0) continue;
      const Bits z = x ^ y;
      if (op == Op::Inner && std::popcount(z) != (gx > gy ? gx - gy : gy - gx)) continue;
      add(r, z, s * cx * cy);
    }
  return clean(r);
}

inline MV reverse(const MV& a) {
  MV r;
  for (const auto& [x, c] : a) {
    const int k = std::popcount(x);
    r[x] = ((k * (k - 1) / 2) % 2) ? -c : c;
  }
  return r;
}

// The outer product of vectors given as rows over another basis: blade `bits` of that expansion.
inline MV expand_blade(Bits bits, const std::vector<std::vector<double>>& rows) {
  MV r{{0u, 1.0}};
  for (int k = 0; k < static_cast<int>(rows.size()); ++k) {
    if (!(bits & (1u << k))) continue;
    MV v;
    for (int d = 0; d < static_cast<int>(rows[k].size()); ++d)
      if (rows[k][d] != 0.0) v[1u << d] = rows[k][d];
    MV n;
    for (const auto& [x, cx] : r)
      for (const auto& [y, cy] : v)
        if (!(x & y)) add(n, x | y, reorder_sign(x, y) * cx * cy);
    r = clean(n);
  }
  return r;
}

// User blade name ("1", "e1^einf", any order of the vectors) -> diagonal multivector.
inline MV user_blade(const Algebra& alg, const std::string& name) {
  if (name == "1") return MV{{0u, 1.0}};
  MV r{{0u, 1.0}};
  size_t pos = 0;
  while (pos <= name.size()) {
    size_t end = name.find('^', pos);
    if (end == std::string::npos) end = name.size();
    const std::string v = name.substr(pos, end - pos);
    int k = -1;
    for (int i = 0; i < alg.dim(); ++i)
      if (alg.names[i] == v) k = i;
    if (k < 0) throw std::invalid_argument("oracle::ga: no vector " + v);
    r = product(alg, r, expand_blade(1u << k, alg.user_in_diag), Op::Outer);
    pos = end + 1;
  }
  return r;
}

// User-blade name of a user bitmap.
inline std::string user_name(const Algebra& alg, Bits b) {
  std::string s;
  for (int k = 0; k < alg.dim(); ++k)
    if (b & (1u << k)) s += (s.empty() ? "" : "^") + alg.names[k];
  return s.empty() ? "1" : s;
}

// A diagonal multivector over the user blades (bitmap over the user vectors).
inline MV to_user(const Algebra& alg, const MV& a) {
  MV r;
  for (const auto& [x, c] : a)
    for (const auto& [u, cu] : expand_blade(x, alg.diag_in_user)) add(r, u, c * cu);
  return clean(r, 1e-12);
}
inline MV from_user(const Algebra& alg, const MV& user) {
  MV r;
  for (const auto& [u, c] : user)
    for (const auto& [x, cx] : expand_blade(u, alg.user_in_diag)) add(r, x, c * cx);
  return clean(r);
}

// The dual: A * I^-1 for the user pseudoscalar I when the metric is nondegenerate; with a null vector (PGA)
// Gaalop's complement map over the user blades: the coefficient of blade B goes to the blade of the user
// vectors B lacks, with sign +1.
inline MV dual(const Algebra& alg, const MV& a) {
  const Bits all = alg.dim() >= 32 ? ~0u : ((1u << alg.dim()) - 1u);
  bool degenerate = false;
  for (int m : alg.metric) degenerate = degenerate || m == 0;
  if (degenerate) {
    MV u;
    for (const auto& [x, c] : to_user(alg, a)) u[all ^ x] = c;
    return from_user(alg, u);
  }
  MV I = expand_blade(all, alg.user_in_diag);
  MV sq = product(alg, I, I, Op::Geometric);
  const double s = sq.count(0u) ? sq.at(0u) : 0.0;
  if (s == 0.0) throw std::logic_error("oracle::ga: pseudoscalar squares to 0");
  for (auto& [x, c] : I) c /= s;
  return product(alg, a, I, Op::Geometric);
}

// ---- the operator set of GATL / ga-benchmark, from the definitions (each over the diagonal basis, where a
// blade's grade is its bit count) ----

inline MV scaled(const MV& a, double f) {
  MV r;
  for (const auto& [x, c] : a) add(r, x, f * c);
  return clean(r);
}
inline MV sum(const MV& a, const MV& b, double fb = 1.0) {
  MV r = a;
  for (const auto& [x, c] : b) r[x] += fb * c;
  return clean(r);
}
// <A>_k.
inline MV grade(const MV& a, int k) {
  MV r;
  for (const auto& [x, c] : a)
    if (std::popcount(x) == k) r[x] = c;
  return r;
}
// (-1)^k on grade k.
inline MV involute(const MV& a) {
  MV r;
  for (const auto& [x, c] : a) r[x] = (std::popcount(x) % 2) ? -c : c;
  return r;
}
// Clifford conjugation: (-1)^(k(k+1)/2) on grade k.
inline MV conjugate(const MV& a) {
  MV r;
  for (const auto& [x, c] : a) {
    const int k = std::popcount(x);
    r[x] = ((k * (k + 1) / 2) % 2) ? -c : c;
  }
  return r;
}

// Left contraction (grade s - r of A_r B_s, none when r > s), right contraction (r - s, none when r < s),
// scalar product (grade 0), dot product (|r - s|, scalars included).
enum class Graded { Left, Right, Scalar, Dot };
inline MV graded(const Algebra& alg, const MV& a, const MV& b, Graded kind) {
  MV r;
  for (const auto& [x, cx] : a)
    for (const auto& [y, cy] : b) {
      const int gx = std::popcount(x), gy = std::popcount(y);
      const int want = kind == Graded::Left     ? gy - gx
                       : kind == Graded::Right  ? gx - gy
                       : kind == Graded::Scalar ? 0
                                                : (gx > gy ? gx - gy : gy - gx);
      if (want < 0) continue;
      MV p = product(alg, MV{{x, cx}}, MV{{y, cy}}, Op::Geometric);
      for (const auto& [z, cz] : grade(p, want)) add(r, z, cz);
    }
  return clean(r);
}

// The undual: A * I when dual is A * I^-1; the complement map (its own inverse) when the metric is degenerate.
inline MV undual(const Algebra& alg, const MV& a) {
  bool degenerate = false;
  for (int m : alg.metric) degenerate = degenerate || m == 0;
  if (degenerate) return dual(alg, a);
  const Bits all = alg.dim() >= 32 ? ~0u : ((1u << alg.dim()) - 1u);
  return product(alg, a, expand_blade(all, alg.user_in_diag), Op::Geometric);
}
// Commutator product (AB - BA)/2 and regressive product undual(dual(A) ^ dual(B)).
inline MV commutator(const Algebra& alg, const MV& a, const MV& b) {
  return scaled(sum(product(alg, a, b, Op::Geometric), product(alg, b, a, Op::Geometric), -1.0), 0.5);
}
inline MV regressive(const Algebra& alg, const MV& a, const MV& b) {
  return undual(alg, product(alg, dual(alg, a), dual(alg, b), Op::Outer));
}
// <A ~A>_0.
inline double reverse_norm_squared(const Algebra& alg, const MV& a) {
  const MV s = graded(alg, a, reverse(a), Graded::Scalar);
  return s.count(0u) ? s.at(0u) : 0.0;
}

}  // namespace oracle::ga
