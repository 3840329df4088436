// gabench's models, random blades and oracle references (models.hpp), and the reader of GATL's printed
// results (gabench.hpp parse_gatl).
#include "models.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <random>
#include <stdexcept>

namespace gabench {

std::vector<Entry>& registry() {
  static std::vector<Entry> entries;
  return entries;
}
bool add(Entry e) {
  registry().push_back(std::move(e));
  return true;
}

namespace {

Model build(const std::string& name) {
  Model m;
  m.name = name;
  if (name == "c3ga") {
    m.id = 0x01;
    m.cg = {"e1", "e2", "e3", "einf", "e0"};
    m.gatl = {"e1", "e2", "e3", "no", "ni"};
    m.gatl_to_cg = {0, 1, 2, 4, 3};
    // einf = ep + em, e0 = (em - ep)/2 over the diagonal e1 e2 e3 ep em.
    m.alg = og::Algebra::diagonal({1, 1, 1, 1, -1}, m.cg);
    m.alg.null_pair(4, 3, 3, 4);
  } else if (name == "e3ga") {
    m.id = 0x02;
    m.cg = {"e1", "e2", "e3"};
    m.gatl = m.cg;
    m.gatl_to_cg = {0, 1, 2};
    m.alg = og::Algebra::signature(3, 0, 0, m.cg);
  } else if (name == "h3ga") {
    m.id = 0x03;
    m.cg = {"e1", "e2", "e3", "e4"};
    m.gatl = {"e1", "e2", "e3", "ep"};
    m.gatl_to_cg = {0, 1, 2, 3};
    m.alg = og::Algebra::signature(4, 0, 0, m.cg);
  } else {
    throw std::invalid_argument("gabench: unknown model '" + name + "' (c3ga e3ga h3ga)");
  }
  return m;
}

// The user blade of cgagen vectors `bits` (bit k: cgagen vector k) over the diagonal basis.
og::MV user(const Model& m, og::Bits bits, double c) {
  return og::scaled(og::from_user(m.alg, og::MV{{bits, 1.0}}), c);
}

// GATL's pseudoscalar: the outer product of the vectors in GATL's order.
og::MV gatl_pseudoscalar(const Model& m) {
  og::MV I{{0u, 1.0}};
  for (int j = 0; j < m.dim(); ++j)
    I = og::product(m.alg, I, user(m, og::Bits{1} << m.gatl_to_cg[j], 1.0), og::Op::Outer);
  return I;
}

double scalar_of(const og::MV& x) { return x.count(0u) ? x.at(0u) : 0.0; }

Named by_name(const Model& m, const og::MV& diag) {
  Named r;
  for (const auto& [u, c] : og::to_user(m.alg, diag)) r[og::user_name(m.alg, u)] = c;
  return r;
}

}  // namespace

const Model& model(const std::string& name) {
  static std::map<std::string, Model> models;
  auto it = models.find(name);
  if (it == models.end()) it = models.emplace(name, build(name)).first;
  return it->second;
}

std::vector<og::Bits> grade_blades(int n, int k) {
  std::vector<og::Bits> out;
  std::vector<int> idx(static_cast<std::size_t>(k));
  std::function<void(int, int)> rec = [&](int pos, int from) {
    if (pos == k) {
      og::Bits b = 0;
      for (int i : idx) b |= og::Bits{1} << i;
      out.push_back(b);
      return;
    }
    for (int v = from; v < n; ++v) {
      idx[static_cast<std::size_t>(pos)] = v;
      rec(pos + 1, v + 1);
    }
  };
  rec(0, 0);
  return out;
}

BladeSet make_blades(const Model& m, int grade, const std::string& role, bool invertible) {
  const int n = m.dim();
  BladeSet s;
  s.grade = grade;
  s.dim = n;
  const auto order = grade_blades(n, grade);
  s.blades = static_cast<int>(order.size());
  // A fixed seed per (model, role, grade): the same arguments on every run and for both sides.
  std::uint64_t seed = 0x9e3779b97f4a7c15ull;
  for (char ch : m.name + "/" + role + "/" + std::to_string(grade)) seed = (seed ^ static_cast<unsigned char>(ch)) * 0x100000001b3ull;
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  while (s.scalars.size() < kSamples) {
    // ga-benchmark's recipe: factor k has coordinate k equal to 1, coordinates grade..n-1 random, the others
    // 0 (over the vectors in GATL's order), so the factors are independent; times a random scalar.
    const double scalar = u(rng);
    std::vector<double> f(static_cast<std::size_t>(grade * n), 0.0);
    for (int k = 0; k < grade; ++k) {
      f[static_cast<std::size_t>(k * n + k)] = 1.0;
      for (int j = grade; j < n; ++j) f[static_cast<std::size_t>(k * n + j)] = u(rng);
    }
    og::MV b{{0u, scalar}};
    for (int k = 0; k < grade; ++k) {
      og::MV v;
      for (int j = 0; j < n; ++j) {
        const double c = f[static_cast<std::size_t>(k * n + j)];
        if (c != 0.0) v = og::sum(v, user(m, og::Bits{1} << m.gatl_to_cg[j], c));
      }
      b = og::product(m.alg, b, v, og::Op::Outer);
    }
    if (invertible && std::abs(og::reverse_norm_squared(m.alg, b)) <= 1e-8) continue;
    const og::MV coeffs = og::to_user(m.alg, b);
    s.scalars.push_back(scalar);
    s.factors.insert(s.factors.end(), f.begin(), f.end());
    for (og::Bits bits : order) s.coeffs.push_back(coeffs.count(bits) ? coeffs.at(bits) : 0.0);
  }
  return s;
}

og::MV oracle_value(const Model& m, const BladeSet& s, std::size_t i) {
  const auto order = grade_blades(m.dim(), s.grade);
  og::MV userv;
  for (std::size_t k = 0; k < order.size(); ++k)
    if (s.coeff(i)[k] != 0.0) userv[order[k]] = s.coeff(i)[k];
  return og::from_user(m.alg, userv);
}

Named reference(const Model& m, const std::string& op, const og::MV& a, const og::MV* b) {
  const og::Algebra& alg = m.alg;
  const og::MV I = gatl_pseudoscalar(m);
  const og::MV Iinv = og::scaled(I, 1.0 / scalar_of(og::product(alg, I, I, og::Op::Geometric)));
  auto dual = [&](const og::MV& x) { return og::product(alg, x, Iinv, og::Op::Geometric); };
  auto undual = [&](const og::MV& x) { return og::product(alg, x, I, og::Op::Geometric); };
  auto inverse = [&](const og::MV& x) { return og::scaled(og::reverse(x), 1.0 / og::reverse_norm_squared(alg, x)); };
  og::MV r;
  if (op == "CliffordConjugation") r = og::conjugate(a);
  else if (op == "Dualization") r = dual(a);
  else if (op == "GradeInvolution") r = og::involute(a);
  else if (op == "Inversion") r = inverse(a);
  else if (op == "Normalization") r = og::scaled(a, 1.0 / std::sqrt(std::abs(og::reverse_norm_squared(alg, a))));
  else if (op == "Reversion") r = og::reverse(a);
  else if (op == "SquaredReverseNorm") r = og::MV{{0u, og::reverse_norm_squared(alg, a)}};
  else if (op == "UnaryMinus") r = og::scaled(a, -1.0);
  else if (op == "UnaryPlus") r = a;
  else if (op == "Undualization") r = undual(a);
  else if (!b) throw std::invalid_argument("gabench: unknown unary operation " + op);
  else if (op == "Addition") r = og::sum(a, *b);
  else if (op == "Subtraction") r = og::sum(a, *b, -1.0);
  else if (op == "CommutatorProduct") r = og::commutator(alg, a, *b);
  else if (op == "DotProduct") r = og::graded(alg, a, *b, og::Graded::Dot);
  else if (op == "GeometricProduct") r = og::product(alg, a, *b, og::Op::Geometric);
  else if (op == "HestenesInnerProduct") r = og::product(alg, a, *b, og::Op::Inner);
  else if (op == "InverseGeometricProduct") r = og::product(alg, a, inverse(*b), og::Op::Geometric);
  else if (op == "LeftContraction") r = og::graded(alg, a, *b, og::Graded::Left);
  else if (op == "OuterProduct") r = og::product(alg, a, *b, og::Op::Outer);
  // The regressive product: GATL's is metric-free (a pair of blades spanning the space meets in their common
  // blade, with the sign of reordering the rest), which is the meet (B* ^ A*) I with B* = B I^-1 over GATL's
  // pseudoscalar I: undual(dual(B) ^ dual(A)), the operands' duals in the reverse order.
  else if (op == "RegressiveProduct") r = undual(og::product(alg, dual(*b), dual(a), og::Op::Outer));
  else if (op == "RightContraction") r = og::graded(alg, a, *b, og::Graded::Right);
  else if (op == "ScalarProduct") r = og::graded(alg, a, *b, og::Graded::Scalar);
  else throw std::invalid_argument("gabench: unknown binary operation " + op);
  return by_name(m, r);
}

double rel_diff(const Named& x, const Named& y) {
  double d = 0, scale = 1;
  for (const auto& [k, v] : x) {
    d = std::max(d, std::abs(v - (y.count(k) ? y.at(k) : 0.0)));
    scale = std::max(scale, std::abs(v));
  }
  for (const auto& [k, v] : y) {
    d = std::max(d, std::abs(v - (x.count(k) ? x.at(k) : 0.0)));
    scale = std::max(scale, std::abs(v));
  }
  return d / scale;
}

// GATL prints a multivector as terms "coefficient * <blade>" joined by " + ": a coefficient is a number, a
// negative number in parentheses, or a constant <k>; a blade is "1" or GATL vector names joined by '^'.
Named parse_gatl(const std::string& model_name, const std::string& text) {
  const Model& m = model(model_name);
  Named out;
  auto fail = [&](const std::string& why) {
    throw std::runtime_error("gabench: cannot read GATL's result (" + why + "): " + text);
  };
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find(" + ", pos);
    if (end == std::string::npos) end = text.size();
    const std::string term = text.substr(pos, end - pos);
    pos = end == text.size() ? end : end + 3;
    const std::size_t star = term.rfind(" * <");
    if (star == std::string::npos || term.back() != '>') fail("term '" + term + "'");
    std::string coef = term.substr(0, star);
    const std::string blade = term.substr(star + 4, term.size() - star - 5);
    coef.erase(std::remove_if(coef.begin(), coef.end(), [](char ch) { return ch == '(' || ch == ')' || ch == '<' || ch == '>'; }),
               coef.end());
    char* stop = nullptr;
    const double c = std::strtod(coef.c_str(), &stop);
    if (coef.empty() || *stop != '\0') fail("coefficient '" + coef + "'");
    if (c == 0.0) continue;
    // GATL's vectors -> cgagen's, sorted into cgagen's order with the permutation's sign.
    std::vector<int> idx;
    if (blade != "1") {
      std::size_t p = 0;
      while (p <= blade.size()) {
        std::size_t q = blade.find('^', p);
        if (q == std::string::npos) q = blade.size();
        const std::string v = blade.substr(p, q - p);
        const auto it = std::find(m.gatl.begin(), m.gatl.end(), v);
        if (it == m.gatl.end()) fail("vector '" + v + "'");
        idx.push_back(m.gatl_to_cg[static_cast<std::size_t>(it - m.gatl.begin())]);
        p = q + 1;
      }
    }
    int sign = 1;
    for (std::size_t i = 0; i < idx.size(); ++i)
      for (std::size_t j = i + 1; j < idx.size(); ++j)
        if (idx[i] > idx[j]) sign = -sign;
    std::sort(idx.begin(), idx.end());
    std::string name;
    for (int i : idx) name += (name.empty() ? "" : "^") + m.cg[static_cast<std::size_t>(i)];
    out[name.empty() ? "1" : name] += sign * c;
  }
  return out;
}

}  // namespace gabench
