// Every function of the generated libraries (libraries/*.gal through `cgagen --library`: the C++ target, and
// built a second time with CGA_LIBRARY_CUDA, the CUDA target compiled as host C++) against
// the any-signature oracle (tests/oracle) on seeded random operands, three draws each, in float against the
// oracle's double:
//  - products, sums, involutions, duals and norms against their definitions;
//  - inverse by a * inverse(a) = 1, normalize and norm by <a ~a>_0;
//  - exp against the power series; log by exp(log(m)) = m on m = exp(x);
//  - sandwich(a, b) = the grades of b in a b a^-1 for a versor a: exp of a bivector for a type with the scalar
//    blade, a normalized vector or dual vector for a type of grade 1 or n-1 (other types are listed, not run).
// The comparison covers every blade: a result with something outside its result type's blades fails, so the
// result types are checked too.
#include <catch2/catch.hpp>

#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "oracle_algebras.hpp"
#ifdef CGA_LIBRARY_CUDA  // the CUDA files as host C++ (their qualifiers defined away on the command line)
#include "cga3.cuh"
#include "cga_rigid.cuh"
#include "e3.cuh"
#include "pga3.cuh"
#else
#include "cga3.hpp"
#include "cga_rigid.hpp"
#include "e3.hpp"
#include "pga3.hpp"
#endif

namespace {

double max_abs(const Named& a) {
  double m = 0;
  for (const auto& [k, v] : a) m = std::max(m, std::abs(v));
  return m;
}

struct TypeView {
  std::string name;
  std::vector<std::string> blades;
};

og::MV oracle_of(const og::Algebra& alg, const TypeView& t, const std::vector<float>& v) {
  og::MV m;
  for (size_t k = 0; k < v.size(); ++k)
    for (const auto& [x, c] : og::user_blade(alg, t.blades[k])) og::add(m, x, c * static_cast<double>(v[k]));
  return og::clean(m);
}

Named named_of(const TypeView& t, const std::vector<float>& v) {
  Named r;
  for (size_t k = 0; k < v.size(); ++k)
    if (v[k] != 0.0f) r[t.blades[k]] += v[k];
  return r;
}

og::MV series_exp(const og::Algebra& alg, const og::MV& x) {
  og::MV sum{{0u, 1.0}}, term{{0u, 1.0}};
  for (int k = 1; k <= 40; ++k) {
    term = og::scaled(og::product(alg, term, x, og::Op::Geometric), 1.0 / k);
    sum = og::sum(sum, term);
  }
  return og::clean(sum, 1e-15);
}

std::set<int> grades(const og::Algebra& alg, const TypeView& t) {
  std::set<int> g;
  for (const auto& b : t.blades)
    for (const auto& [x, c] : og::user_blade(alg, b)) g.insert(std::popcount(x)), (void)c;
  return g;
}

// Float coefficients in [-s, s] on a 1/256 grid (exact in float and double).
std::vector<float> random_values(std::mt19937& rng, size_t n, double s) {
  std::uniform_int_distribution<int> d(-256, 256);
  std::vector<float> v(n);
  for (auto& x : v) x = static_cast<float>(s * d(rng) / 256.0);
  return v;
}

// With `matrices` (the registry of the sandwiches' matrices): each matrix(a, of<B>) against the oracle's sandwich, column by
// column (M(b) = sum_j b_j m[j] for random b), on the same normalized versors.
template <class TypeInfo, class FunctionInfo, size_t NT, size_t NF, class... Matrices>
void check_library(const std::string& algebra_name, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF],
                   const Matrices&... matrices) {
  const og::Algebra alg = oracle_algebra(algebra_name);
  std::map<std::string, TypeView> tv;
  for (const auto& t : types) {
    TypeView v{std::string(t.name), {}};
    for (size_t k = 0; k < t.size; ++k) v.blades.emplace_back(t.blades[k]);
    tv[v.name] = v;
  }
  std::mt19937 rng(20261128u);
  auto fits = [&](const og::MV& m, const TypeView& t) {
    Named n = from_oracle(alg, m);
    for (const auto& [b, c] : n)
      if (std::abs(c) > 1e-9 && std::find(t.blades.begin(), t.blades.end(), b) == t.blades.end()) return false;
    return true;
  };
  auto project = [&](const og::MV& m, const TypeView& t) {
    Named n = from_oracle(alg, m);
    std::vector<float> v;
    for (const auto& b : t.blades) v.push_back(static_cast<float>(n.count(b) ? n.at(b) : 0.0));
    return v;
  };
  // A normalized versor of type t (<a ~a>_0 = +1, or -1 for a type whose norm is never positive), or empty.
  auto versor = [&](const TypeView& t) -> std::vector<float> {
    const bool has_scalar = std::find(t.blades.begin(), t.blades.end(), "1") != t.blades.end();
    if (has_scalar) {
      TypeView b2{"", {}};
      for (const auto& b : t.blades)
        if (grades(alg, TypeView{"", {b}}) == std::set<int>{2}) b2.blades.push_back(b);
      if (b2.blades.empty()) return {};
      const og::MV m = series_exp(alg, oracle_of(alg, b2, random_values(rng, b2.blades.size(), 0.5)));
      return fits(m, t) ? project(m, t) : std::vector<float>{};
    }
    const std::set<int> g = grades(alg, t);
    if (g.size() != 1 || (*g.begin() != 1 && *g.begin() != alg.dim() - 1)) return {};
    for (int sign : {1, -1})
      for (int tries = 0; tries < 200; ++tries) {
        std::vector<float> v = random_values(rng, t.blades.size(), 1.0);
        const double s = og::reverse_norm_squared(alg, oracle_of(alg, t, v));
        if (s * sign < 0.25) continue;
        for (auto& x : v) x = static_cast<float>(x / std::sqrt(std::abs(s)));
        return v;
      }
    return {};
  };

  int checked = 0;
  std::vector<std::string> not_run;
  for (const auto& f : fns) {
    const std::string name(f.name), an(f.a), bn(f.b), rn(f.result);
    const TypeView &ta = tv.at(an), &tr = tv.at(rn);
    INFO(algebra_name << ": " << name << "(" << an << (bn.empty() ? "" : ", " + bn) << ") -> " << rn);
    for (int draw = 0; draw < 3; ++draw) {
      std::vector<float> a, b, r(tr.blades.size(), std::nanf(""));
      og::MV expect;
      bool have = true;
      if (name == "sandwich") {
        a = versor(ta);
        if (a.empty()) {
          not_run.push_back(name + "(" + an + ", " + bn + ")");
          break;
        }
      } else if (name == "log") {
        a = versor(ta);
        if (a.empty()) {
          not_run.push_back(name + "(" + an + ")");
          break;
        }
      } else {
        for (int tries = 0; tries < 100; ++tries) {  // invertible, well away from a zero norm
          a = random_values(rng, ta.blades.size(), name == "exp" ? 0.5 : 1.0);
          const double s = og::reverse_norm_squared(alg, oracle_of(alg, ta, a));
          if ((name != "inverse" && name != "normalize") || std::abs(s) > 0.25) break;
        }
      }
      const og::MV A = oracle_of(alg, ta, a);
      if (f.arity == 2) {
        const TypeView& tb = tv.at(bn);
        b = random_values(rng, tb.blades.size(), 1.0);
        const og::MV B = oracle_of(alg, tb, b);
        f.binary(a.data(), b.data(), r.data());
        if (name == "gp") expect = og::product(alg, A, B, og::Op::Geometric);
        else if (name == "outer") expect = og::product(alg, A, B, og::Op::Outer);
        else if (name == "inner") expect = og::product(alg, A, B, og::Op::Inner);
        else if (name == "dot") expect = og::graded(alg, A, B, og::Graded::Dot);
        else if (name == "lcont") expect = og::graded(alg, A, B, og::Graded::Left);
        else if (name == "rcont") expect = og::graded(alg, A, B, og::Graded::Right);
        else if (name == "scp") expect = og::graded(alg, A, B, og::Graded::Scalar);
        else if (name == "cp") expect = og::commutator(alg, A, B);
        else if (name == "rp") expect = og::regressive(alg, A, B);
        else if (name == "add") expect = og::sum(A, B);
        else if (name == "sub") expect = og::sum(A, B, -1.0);
        else if (name == "sandwich") {
          const og::MV inv = og::scaled(og::reverse(A), 1.0 / og::reverse_norm_squared(alg, A));
          const og::MV full = og::product(alg, og::product(alg, A, B, og::Op::Geometric), inv, og::Op::Geometric);
          for (int k : grades(alg, tb)) expect = og::sum(expect, og::grade(full, k));
        } else have = false;
      } else {
        f.unary(a.data(), r.data());
        const double s = og::reverse_norm_squared(alg, A);
        if (name == "neg") expect = og::scaled(A, -1.0);
        else if (name == "reverse") expect = og::reverse(A);
        else if (name == "involute") expect = og::involute(A);
        else if (name == "conjugate") expect = og::conjugate(A);
        else if (name == "dual") expect = og::dual(alg, A);
        else if (name == "undual") expect = og::undual(alg, A);
        else if (name == "norm") expect = og::MV{{0u, std::sqrt(std::abs(s))}};
        else if (name == "norm_sqr") expect = og::MV{{0u, s}};
        else if (name == "normalize") expect = og::scaled(A, 1.0 / std::sqrt(std::abs(s)));
        else if (name == "exp") expect = series_exp(alg, A);
        else if (name == "inverse") {  // a * inverse(a) = 1
          const og::MV one = og::product(alg, A, oracle_of(alg, tr, r), og::Op::Geometric);
          const Named got = from_oracle(alg, one), want = {{"1", 1.0}};
          CHECK(max_diff(got, want) <= 1e-3);
          continue;
        } else if (name == "log") {  // exp(log(a)) = a
          const Named got = from_oracle(alg, series_exp(alg, oracle_of(alg, tr, r))), want = from_oracle(alg, A);
          CHECK(max_diff(got, want) <= 1e-4 * (1 + max_abs(want)));
          continue;
        } else have = false;
      }
      INFO("draw " << draw);
      REQUIRE(have);  // every operation of the table has its definition here
      const Named want = from_oracle(alg, og::clean(expect, 1e-12)), got = named_of(tr, r);
      CHECK(max_diff(got, want) <= 1e-4 * (1 + max_abs(want)));
    }
    ++checked;
  }
  std::string list;
  for (const auto& n : not_run) list += " " + n;
  WARN(algebra_name << ": " << NF << " functions, " << (checked - static_cast<int>(not_run.size()))
                    << " compared with the oracle; no versor operand of the type to draw for:" << list);
  CHECK(checked == static_cast<int>(NF));
  CHECK(not_run.size() < NF / 10);
  if constexpr (sizeof...(Matrices) == 1) {
    size_t compared = 0;
    for (const auto& m : (matrices, ...)) {
      const TypeView &ta = tv.at(std::string(m.a)), &tb = tv.at(std::string(m.b)), &tr = tv.at(std::string(m.result));
      INFO(algebra_name << ": matrix(" << m.a << ", of<" << m.b << ">) -> " << m.result);
      REQUIRE(m.cols == tb.blades.size());
      REQUIRE(m.rows == tr.blades.size());
      const std::vector<float> a = versor(ta);
      if (a.empty()) continue;
      std::vector<float> cols(m.cols * m.rows, std::nanf(""));
      m.columns(a.data(), cols.data());
      const og::MV A = oracle_of(alg, ta, a);
      const og::MV inv = og::scaled(og::reverse(A), 1.0 / og::reverse_norm_squared(alg, A));
      for (int draw = 0; draw < 3; ++draw) {
        const std::vector<float> b = random_values(rng, m.cols, 1.0);
        std::vector<float> r(m.rows, 0.0f);
        for (size_t j = 0; j < m.cols; ++j)
          for (size_t k = 0; k < m.rows; ++k) r[k] += b[j] * cols[j * m.rows + k];
        const og::MV full = og::product(alg, og::product(alg, A, oracle_of(alg, tb, b), og::Op::Geometric), inv, og::Op::Geometric);
        og::MV expect;
        for (int k : grades(alg, tb)) expect = og::sum(expect, og::grade(full, k));
        const Named want = from_oracle(alg, og::clean(expect, 1e-12)), got = named_of(tr, r);
        CHECK(max_diff(got, want) <= 1e-4 * (1 + max_abs(want)));
      }
      ++compared;
    }
    WARN(algebra_name << ": " << (matrices, ...).size() << " matrices, " << compared << " compared with the oracle");
    CHECK(compared == (matrices, ...).size());
  }
}

}  // namespace

TEST_CASE("library pga3: every function agrees with the oracle") {
  check_library(std::string(pga3::algebra), pga3::types, pga3::functions, pga3::matrices);
}
TEST_CASE("library cga3: every function agrees with the oracle") {
  check_library(std::string(cga3::algebra), cga3::types, cga3::functions, cga3::matrices);
}
TEST_CASE("library e3: every function agrees with the oracle") { check_library(std::string(e3::algebra), e3::types, e3::functions, e3::matrices); }
TEST_CASE("library cga_rigid (the runtime's): every function agrees with the oracle") {
  check_library(std::string(cga_rigid::algebra), cga_rigid::types, cga_rigid::functions, cga_rigid::matrices);
}

#ifndef CGA_LIBRARY_CUDA
// The array forms run the scalar kernel, directly or (a costly kernel) through blocks of 32 elements in
// structure-of-arrays scratch: element by element they agree with one call, across block boundaries and in
// the last, partial block.
template <class A, class B, class MakeA>
void check_array_forms(const char* what, MakeA make_a) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1, 1);
  constexpr size_t n = 150;  // whole blocks and a partial one, not a multiple of any vector width
  std::vector<A> a(n);
  std::vector<B> x(n), pairs(n), one(n);
  for (size_t k = 0; k < n; ++k) {
    a[k] = make_a(rng);
    for (float& c : x[k].v) c = u(rng);
  }
  pga3::sandwich(a.data(), x.data(), pairs.data(), n);
  pga3::sandwich(a[3], x.data(), one.data(), n);
  for (size_t k = 0; k < n; ++k) {
    INFO(what << ", element " << k);
    const B p = pga3::sandwich(a[k], x[k]), q = pga3::sandwich(a[3], x[k]);
    for (size_t c = 0; c < std::size(p.v); ++c) {
      CHECK(std::abs(pairs[k].v[c] - p.v[c]) <= 1e-5f * (1 + std::abs(p.v[c])));
      CHECK(std::abs(one[k].v[c] - q.v[c]) <= 1e-5f * (1 + std::abs(q.v[c])));
    }
  }
}

TEST_CASE("library pga3: the array forms agree with one call per element") {
  auto motor = [](std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1, 1);
    pga3::line l;
    for (float& c : l.v) c = u(rng);
    return pga3::exp(l);
  };
  check_array_forms<pga3::motor, pga3::point>("motor on points (direct: sizes 8 and 4)", motor);
  check_array_forms<pga3::motor, pga3::line>("motor on lines (staged: a line is 6)", motor);
  check_array_forms<pga3::motor, pga3::direction>("motor on directions (direct: 30 operations)", motor);
  std::mt19937 rng(8);
  constexpr size_t n = 150;
  std::vector<pga3::motor> m(n), products(n);
  for (auto& x : m) x = motor(rng);
  pga3::gp(m.data(), m.data(), products.data(), n);
  for (size_t k = 0; k < n; ++k)
    for (size_t c = 0; c < 8; ++c) CHECK(std::abs(products[k].v[c] - pga3::gp(m[k], m[k]).v[c]) <= 1e-5f * (1 + std::abs(products[k].v[c])));
}
#endif
