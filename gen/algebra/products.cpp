// Builds the null-basis product tables (see products.hpp) by going through the orthonormal basis.
#include "algebra/products.hpp"

#include <array>
#include <bit>
#include <numeric>
#include <stdexcept>

namespace cgagen::algebra {

Rational::Rational(std::int64_t n, std::int64_t d) {
  if (d == 0) throw std::invalid_argument("Rational: zero denominator");
  if (d < 0) n = -n, d = -d;
  std::int64_t g = std::gcd(n < 0 ? -n : n, d);
  if (g == 0) g = 1;
  num = n / g;
  den = d / g;
}

std::string Rational::str() const {
  return den == 1 ? std::to_string(num) : std::to_string(num) + "/" + std::to_string(den);
}

Rational operator+(Rational a, Rational b) { return Rational(a.num * b.den + b.num * a.den, a.den * b.den); }
Rational operator*(Rational a, Rational b) { return Rational(a.num * b.num, a.den * b.den); }
Rational operator/(Rational a, Rational b) {
  if (b.is_zero()) throw std::invalid_argument("Rational: division by zero");
  return Rational(a.num * b.den, a.den * b.num);
}

namespace {

// A multivector over the orthonormal basis {e1, e2, e3, e+, e-}, indexed by bitmap (bit 3 e+, bit 4 e-).
using Ortho = std::array<Rational, kBladeCount>;
constexpr std::array<int, 5> kOrthoMetric = {1, 1, 1, 1, -1};

// Sign of moving the vectors of b past those of a into increasing order (one minus per swap).
int reorder_sign(unsigned a, unsigned b) {
  a >>= 1;
  int swaps = 0;
  while (a) {
    swaps += std::popcount(a & b);
    a >>= 1;
  }
  return (swaps & 1) ? -1 : 1;
}

// Product of two orthonormal basis blades: (sign, bitmap). The outer product of orthogonal blades is their
// geometric product when they share no vector, and 0 otherwise.
Ortho ortho_product(const Ortho& x, const Ortho& y, bool outer) {
  Ortho r{};
  for (unsigned a = 0; a < kBladeCount; ++a) {
    if (x[a].is_zero()) continue;
    for (unsigned b = 0; b < kBladeCount; ++b) {
      if (y[b].is_zero()) continue;
      if (outer && (a & b)) continue;
      int sign = reorder_sign(a, b);
      for (int k = 0; k < 5; ++k)
        if ((a & b) & (1u << k)) sign *= kOrthoMetric[k];
      r[a ^ b] = r[a ^ b] + Rational(sign) * x[a] * y[b];
    }
  }
  return r;
}

// The null basis vector k (0..4: e1 e2 e3 einf e0) over the orthonormal basis.
Ortho null_vector(int k) {
  Ortho v{};
  if (k < 3) {
    v[1u << k] = Rational(1);
  } else if (k == 3) {  // einf = e- + e+
    v[1u << 3] = Rational(1);
    v[1u << 4] = Rational(1);
  } else {  // e0 = (e- - e+)/2
    v[1u << 3] = Rational(-1, 2);
    v[1u << 4] = Rational(1, 2);
  }
  return v;
}

struct Tables {
  // null_in_ortho[i]: null blade i (Gaalop index) over the orthonormal basis.
  std::array<Ortho, kBladeCount> null_in_ortho;
  // to_null[o][i]: coefficient of null blade i in orthonormal blade o (the inverse change of basis).
  std::array<std::array<Rational, kBladeCount>, kBladeCount> to_null;
  std::array<std::vector<ProductTerm>, kBladeCount * kBladeCount> geo, outer, inner;

  Tables() {
    for (BladeIndex i = 0; i < kBladeCount; ++i) {
      Ortho blade{};
      blade[0] = Rational(1);
      BladeBits bits = blade_bits(i);
      for (int k = 0; k < 5; ++k)
        if (bits & (1 << k)) blade = ortho_product(blade, null_vector(k), true);
      null_in_ortho[i] = blade;
    }
    invert_change_of_basis();
    for (BladeIndex a = 0; a < kBladeCount; ++a) {
      for (BladeIndex b = 0; b < kBladeCount; ++b) {
        auto g = to_null_terms(ortho_product(null_in_ortho[a], null_in_ortho[b], false));
        outer[a * kBladeCount + b] = to_null_terms(ortho_product(null_in_ortho[a], null_in_ortho[b], true));
        int ga = blade_grade(a), gb = blade_grade(b);
        if (ga > 0 && gb > 0) {
          int want = ga > gb ? ga - gb : gb - ga;
          for (const auto& t : g)
            if (blade_grade(t.blade) == want) inner[a * kBladeCount + b].push_back(t);
        }
        geo[a * kBladeCount + b] = std::move(g);
      }
    }
  }

  // Gauss-Jordan on the 32x32 matrix whose column i is null blade i over the orthonormal blades.
  void invert_change_of_basis() {
    std::array<std::array<Rational, 2 * kBladeCount>, kBladeCount> m{};
    for (int o = 0; o < kBladeCount; ++o) {
      for (int i = 0; i < kBladeCount; ++i) m[o][i] = null_in_ortho[i][o];
      m[o][kBladeCount + o] = Rational(1);
    }
    for (int col = 0; col < kBladeCount; ++col) {
      int pivot = col;
      while (pivot < kBladeCount && m[pivot][col].is_zero()) ++pivot;
      if (pivot == kBladeCount) throw std::logic_error("null blades are not a basis");
      std::swap(m[pivot], m[col]);
      Rational p = m[col][col];
      for (auto& x : m[col]) x = x / p;
      for (int r = 0; r < kBladeCount; ++r) {
        if (r == col || m[r][col].is_zero()) continue;
        Rational f = m[r][col];
        for (int c = 0; c < 2 * kBladeCount; ++c) m[r][c] = m[r][c] - f * m[col][c];
      }
    }
    // Now m[i][32 + o] = coefficient of null blade i in orthonormal blade o.
    for (int o = 0; o < kBladeCount; ++o)
      for (int i = 0; i < kBladeCount; ++i) to_null[o][i] = m[i][kBladeCount + o];
  }

  std::vector<ProductTerm> to_null_terms(const Ortho& v) const {
    std::array<Rational, kBladeCount> acc{};
    for (int o = 0; o < kBladeCount; ++o) {
      if (v[o].is_zero()) continue;
      for (int i = 0; i < kBladeCount; ++i)
        if (!to_null[o][i].is_zero()) acc[i] = acc[i] + v[o] * to_null[o][i];
    }
    std::vector<ProductTerm> out;
    for (int i = 0; i < kBladeCount; ++i)
      if (!acc[i].is_zero()) out.push_back({i, acc[i]});
    return out;
  }
};

const Tables& tables() {
  static const Tables t;
  return t;
}

void check_index(BladeIndex i) {
  if (i < 0 || i >= kBladeCount) throw std::out_of_range("blade index " + std::to_string(i) + " out of range");
}

}  // namespace

const std::vector<ProductTerm>& product(ProductKind kind, BladeIndex a, BladeIndex b) {
  check_index(a);
  check_index(b);
  const auto& t = tables();
  switch (kind) {
    case ProductKind::Geometric: return t.geo[a * kBladeCount + b];
    case ProductKind::Outer: return t.outer[a * kBladeCount + b];
    case ProductKind::Inner: return t.inner[a * kBladeCount + b];
  }
  throw std::logic_error("unknown product kind");
}

int reverse_sign(BladeIndex i) {
  int k = blade_grade(i);
  return ((k * (k - 1) / 2) & 1) ? -1 : 1;
}

int involution_sign(BladeIndex i) { return (blade_grade(i) & 1) ? -1 : 1; }

}  // namespace cgagen::algebra
