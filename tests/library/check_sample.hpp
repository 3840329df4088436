// What rust_check and python_check share: a fixed-seed sample of a generated library's functions (from its C++
// registry, LIBRARY::functions[]), seeded operands for each, the C++ library's values on them (tests/library
// checks the C++ against the oracle), and the comparison of another target's values with those. The operands
// are drawn as glsl_check draws them: random coefficients in [-1, 1] (the same numbers go to both sides, so
// any operand does), inverse and normalize away from a zero norm, log near the identity.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace library_check {

// One sampled function: its registry names, operand and result sizes, and `rows` operand rows (the a then the
// b coefficients) with the C++ values.
struct Case {
  std::string name, a, b, result;
  int arity = 1;
  size_t na = 0, nb = 0, nr = 0;
  std::vector<float> x, want;  // rows * (na + nb), rows * nr
};

// "ideal_line" -> "IdealLine": the generator's {{Type}} for a name no target reserves (the shipped specs').
inline std::string camel(const std::string& name) {
  std::string out;
  bool up = true;
  for (char c : name) {
    if (c == '_') {
      up = true;
      continue;
    }
    out += up ? static_cast<char>(std::toupper(static_cast<unsigned char>(c))) : c;
    up = false;
  }
  return out;
}

// COUNT functions (0: all) drawn with a fixed seed, in registry order, each with `rows` operand rows. Empty and
// a message on stderr when some function has no operand with a finite C++ value in 100 draws.
template <class TypeInfo, class FunctionInfo, size_t NT, size_t NF>
std::vector<Case> sample(const std::string& tool, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF],
                         size_t count, size_t rows) {
  std::map<std::string, size_t> size;
  std::map<std::string, std::vector<std::string>> blades;
  for (const auto& t : types) {
    size[std::string(t.name)] = t.size;
    for (size_t k = 0; k < t.size; ++k) blades[std::string(t.name)].emplace_back(t.blades[k]);
  }
  std::vector<size_t> picked(NF);
  for (size_t i = 0; i < NF; ++i) picked[i] = i;
  std::mt19937 rng(20261128u);
  std::shuffle(picked.begin(), picked.end(), rng);
  if (count && count < NF) picked.resize(count);
  std::sort(picked.begin(), picked.end());
  std::uniform_int_distribution<int> d(-256, 256);
  std::vector<Case> cases;
  for (size_t i : picked) {
    const auto& f = fns[i];
    Case c;
    c.name = f.name, c.a = f.a, c.b = f.b, c.result = f.result, c.arity = f.arity;
    c.na = size[c.a], c.nb = c.arity == 2 ? size[c.b] : 0, c.nr = size[c.result];
    c.x.resize(rows * (c.na + c.nb));
    c.want.resize(rows * c.nr);
    for (size_t row = 0; row < rows; ++row) {
      float* x = &c.x[row * (c.na + c.nb)];
      float* y = &c.want[row * c.nr];
      bool finite = false;
      for (int tries = 0; tries < 100 && !finite; ++tries) {
        for (size_t k = 0; k < c.na + c.nb; ++k) x[k] = static_cast<float>(d(rng) / (c.name == "log" ? 1024.0 : 256.0));
        if (c.name == "log")  // near the identity: log's domain is rotors and motors
          for (size_t k = 0; k < c.na; ++k)
            if (blades[c.a][k] == "1") x[k] += 1.0f;
        if (c.name == "inverse" || c.name == "normalize") {
          float n = 0.0f;
          for (const auto& g : fns)  // the operand's norm_sqr, through the library itself
            if (std::string(g.name) == "norm_sqr" && std::string(g.a) == c.a) g.unary(x, &n);
          if (std::abs(n) <= 0.25f) continue;
        }
        if (c.arity == 2) f.binary(x, x + c.na, y);
        else f.unary(x, y);
        finite = std::all_of(y, y + c.nr, [](float v) { return std::isfinite(v); });
      }
      if (!finite) {
        std::fprintf(stderr, "%s: %s(%s): no operand with a finite C++ value in 100 draws\n", tool.c_str(),
                     c.name.c_str(), c.a.c_str());
        return {};
      }
    }
    cases.push_back(std::move(c));
  }
  return cases;
}

// Every matrix of the C++ registry (LIBRARY::matrices) as a case "matrix" with `rows` rows: M(b) for M =
// matrix(a, of<B>), random a and b, M(b) from the scalar matrix kernel's columns (the kernel the other targets
// print; it is a polynomial in a, so any a will do).
template <class TypeInfo, class Matrices, size_t NT>
std::vector<Case> matrix_cases(const TypeInfo (&types)[NT], const Matrices& matrices, size_t rows) {
  std::mt19937 rng(20261203u);
  std::uniform_int_distribution<int> d(-256, 256);
  std::vector<Case> out;
  for (const auto& m : matrices) {
    Case c;
    c.name = "matrix", c.a = m.a, c.b = m.b, c.result = m.result, c.arity = 2;
    c.nb = m.cols, c.nr = m.rows;
    for (const auto& t : types)
      if (t.name == m.a) c.na = t.size;
    c.x.resize(rows * (c.na + c.nb));
    for (float& v : c.x) v = static_cast<float>(d(rng) / 256.0);
    c.want.assign(rows * c.nr, 0.0f);
    std::vector<float> cols(m.cols * m.rows);
    for (size_t row = 0; row < rows; ++row) {
      const float* x = &c.x[row * (c.na + c.nb)];
      m.scalar_columns(x, cols.data());
      for (size_t j = 0; j < m.cols; ++j)
        for (size_t k = 0; k < m.rows; ++k) c.want[row * c.nr + k] += x[c.na + j] * cols[j * m.rows + k];
    }
    out.push_back(std::move(c));
  }
  return out;
}

// Compares `got` (per case, per row: `forms` results of nr values each, every form the same function called
// another way) with the C++ values within 1e-4 (1 + |value|); prints the first mismatches, returns their count.
inline int compare(const std::string& tool, const std::string& lib, const std::vector<Case>& cases,
                   const std::vector<std::vector<double>>& got, const std::vector<std::vector<std::string>>& forms,
                   size_t rows) {
  int bad = 0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const Case& c = cases[i];
    if (got[i].size() != rows * forms[i].size() * c.nr) {
      std::fprintf(stderr, "%s: %s %s(%s%s%s): %zu values back, %zu expected\n", tool.c_str(), lib.c_str(),
                   c.name.c_str(), c.a.c_str(), c.arity == 2 ? ", " : "", c.b.c_str(), got[i].size(),
                   rows * forms[i].size() * c.nr);
      ++bad;
      continue;
    }
    for (size_t row = 0; row < rows; ++row)
      for (size_t form = 0; form < forms[i].size(); ++form)
        for (size_t k = 0; k < c.nr; ++k) {
          const double w = c.want[row * c.nr + k], g = got[i][(row * forms[i].size() + form) * c.nr + k];
          if (std::abs(g - w) <= 1e-4 * (1 + std::abs(w))) continue;
          if (bad++ < 20)
            std::fprintf(stderr, "%s: %s %s(%s%s%s) row %zu as %s, coefficient %zu: %.9g, C++ %.9g\n", tool.c_str(),
                         lib.c_str(), c.name.c_str(), c.a.c_str(), c.arity == 2 ? ", " : "", c.b.c_str(), row,
                         forms[i][form].c_str(), k, g, w);
        }
  }
  return bad;
}

}  // namespace library_check
