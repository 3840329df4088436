// The operator set of docs/language.md ("Operators and functions") against the independent any-signature
// oracle (tests/oracle/include/oracle/algebra.hpp) in every built-in algebra: for every pair of grades
// (r, s), a script with multivector inputs A (grade r) and B (grade s) on seeded random blades is expanded,
// optimized and evaluated in double precision (what `cgagen --eval` prints), and each output is compared
// with the oracle's value for the same inputs. Then the inverse geometric product and invert on versors,
// normalize, and the located errors of bad calls.
#include <catch2/catch.hpp>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "algebra/algebra.hpp"
#include "algebra/blade.hpp"
#include "expand/expand.hpp"
#include "front/diagnostics.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "oracle/algebra.hpp"
#include "oracle_algebras.hpp"

using namespace cgagen;

namespace {

using Named = std::map<std::string, double>;  // user blade name -> coefficient

Named from_oracle(const og::Algebra& alg, const og::MV& diag) {
  Named r;
  for (const auto& [u, c] : og::to_user(alg, diag)) r[og::user_name(alg, u)] = c;
  return r;
}

double max_diff(const Named& a, const Named& b) {
  double d = 0;
  for (const auto& [k, v] : a) d = std::max(d, std::abs(v - (b.count(k) ? b.at(k) : 0.0)));
  for (const auto& [k, v] : b) d = std::max(d, std::abs(v - (a.count(k) ? a.at(k) : 0.0)));
  return d;
}

double max_abs(const Named& a) {
  double m = 0;
  for (const auto& [k, v] : a) m = std::max(m, std::abs(v));
  return m;
}

// A multivector input: its blades (generator indices) and values, and the same value in the oracle.
struct Input {
  std::string name;
  std::vector<algebra::BladeIndex> blades;
  std::vector<double> values;
  og::MV oracle;
};

// Up to `cap` distinct random blades of grade k (all of them when there are no more), random coefficients.
Input random_input(std::mt19937& rng, const og::Algebra& alg, const std::string& name, int k, int cap) {
  std::vector<algebra::BladeIndex> of_grade;
  for (int b = 0; b < algebra::blade_count(); ++b)
    if (algebra::blade_grade(b) == k) of_grade.push_back(b);
  std::shuffle(of_grade.begin(), of_grade.end(), rng);
  if (static_cast<int>(of_grade.size()) > cap) of_grade.resize(cap);
  std::sort(of_grade.begin(), of_grade.end());
  std::uniform_real_distribution<double> val(-2.0, 2.0);
  Input in{name, of_grade, {}, {}};
  for (algebra::BladeIndex b : of_grade) {
    const double c = std::round(val(rng) * 8) / 8 + (val(rng) > 0 ? 0.0625 : -0.0625);  // never 0
    in.values.push_back(c);
    for (const auto& [x, cx] : og::user_blade(alg, algebra::blade_name(b))) og::add(in.oracle, x, c * cx);
  }
  in.oracle = og::clean(in.oracle);
  return in;
}

std::string pragma(const Input& in) {
  std::string s = "#pragma input " + in.name;
  for (algebra::BladeIndex b : in.blades) s += " " + (b == 0 ? std::string("1") : algebra::blade_name(b));
  return s + "\n";
}

// Expands, optimizes (-O1) and evaluates `script` in algebra `name`: output -> its value by blade name.
std::map<std::string, Named> run(const std::string& name, const std::string& script, const std::vector<Input>& ins) {
  front::SourceFile file("ops.clu", script);
  const Kernel k = expand(front::parse(file), "ops", algebra::builtin(name));
  const opt::Program p = opt::optimize(k, opt::Level::O1);
  opt::InputValues values;
  for (const Input& in : ins) values[in.name] = in.values;
  std::map<std::string, Named> out;
  for (const auto& line : opt::evaluate(p, values))
    if (line.value != 0.0) out[line.output][line.blade_name] += line.value;
  return out;
}

// Every built-in algebra; the larger ones sample fewer blades of each grade.
int blade_cap(int dim) { return dim <= 5 ? 6 : dim <= 9 ? 3 : 2; }

}  // namespace

TEST_CASE("every operator matches the oracle in every built-in algebra, for every pair of grades") {
  const auto started = std::chrono::steady_clock::now();
  REQUIRE(algebra::builtin_names().size() == 11);
  int compared = 0;
  for (const std::string& name : algebra::builtin_names()) {
    INFO("algebra " << name);
    algebra::Using use(algebra::builtin(name));
    const og::Algebra alg = oracle_algebra(name);
    const int n = alg.dim();
    std::mt19937 rng(20261126u + static_cast<unsigned>(n));
    for (int r = 0; r <= n; ++r)
      for (int s = 0; s <= n; ++s) {
        INFO("grades " << r << ", " << s);
        const Input a = random_input(rng, alg, "A", r, blade_cap(n)), b = random_input(rng, alg, "B", s, blade_cap(n));
        const std::string script = pragma(a) + pragma(b) +
                                   "?gp = A * B;\n?op = A ^ B;\n?ip = A . B;\n?hip = hip(A, B);\n?dot = dot(A, B);\n"
                                   "?lc = lcont(A, B);\n?rc = rcont(A, B);\n?sp = scp(A, B);\n?cp = cp(A, B);\n"
                                   "?rp = rp(A, B);\n?add = A + B;\n?sub = A - B;\n?neg = -A;\n?rev = ~A;\n"
                                   "?inv = involute(A);\n?conj = conjugate(A);\n?du = Dual(A);\n?ud = undual(A);\n"
                                   "?udd = undual(*A);\n?rn = rnorm_sqr(A);\n?g = grade(A + B, " +
                                   std::to_string(s) + ");\n";
        const auto got = run(name, script, {a, b});
        auto get = [&](const std::string& o) { return got.count(o) ? got.at(o) : Named{}; };
        const og::MV &A = a.oracle, &B = b.oracle;
        const std::map<std::string, og::MV> want = {
            {"gp", og::product(alg, A, B, og::Op::Geometric)},
            {"op", og::product(alg, A, B, og::Op::Outer)},
            {"ip", og::product(alg, A, B, og::Op::Inner)},
            {"hip", og::product(alg, A, B, og::Op::Inner)},
            {"dot", og::graded(alg, A, B, og::Graded::Dot)},
            {"lc", og::graded(alg, A, B, og::Graded::Left)},
            {"rc", og::graded(alg, A, B, og::Graded::Right)},
            {"sp", og::graded(alg, A, B, og::Graded::Scalar)},
            {"cp", og::commutator(alg, A, B)},
            {"rp", og::regressive(alg, A, B)},
            {"add", og::sum(A, B)},
            {"sub", og::sum(A, B, -1.0)},
            {"neg", og::scaled(A, -1.0)},
            {"rev", og::reverse(A)},
            {"inv", og::involute(A)},
            {"conj", og::conjugate(A)},
            {"du", og::dual(alg, A)},
            {"ud", og::undual(alg, A)},
            {"udd", A},
            {"rn", og::MV{{0u, og::reverse_norm_squared(alg, A)}}},
            {"g", og::grade(og::sum(A, B), s)},
        };
        for (const auto& [o, w] : want) {
          INFO("output " << o);
          const Named expect = from_oracle(alg, w);
          CHECK(max_diff(get(o), expect) <= 1e-9 * (1.0 + max_abs(expect)));
          ++compared;
        }
      }
  }
  CHECK(compared > 21 * 700);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  WARN("operators against the oracle: " << compared << " comparisons in " << seconds << " s");
}
