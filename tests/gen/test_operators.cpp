// The operator set of docs/language.md ("Operators and functions") against the independent any-signature
// oracle (tests/oracle/include/oracle/algebra.hpp) in every built-in algebra: for every pair of grades
// (r, s), a script with multivector inputs A (grade r) and B (grade s) on seeded random blades is expanded,
// optimized and evaluated in double precision (what `cgagen --eval` prints), and each output is compared
// with the oracle's value for the same inputs. Then the inverse geometric product and invert on versors,
// normalize, and the located errors of bad calls.
#include <catch2/catch.hpp>

#include <algorithm>
#include <bit>
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
#include "expand_error.hpp"
#include "oracle_algebras.hpp"

using namespace cgagen;

namespace {

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
int blade_cap(int dim) { return dim <= 5 ? 10 : dim <= 9 ? 4 : 2; }
int trials(int dim) { return dim <= 5 ? 3 : 1; }

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
    for (int t = 0; t < trials(n); ++t)
    for (int r = 0; r <= n; ++r)
      for (int s = 0; s <= n; ++s) {
        INFO("grades " << r << ", " << s << ", trial " << t);
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
  CHECK(compared == 21 * (3 * (9 + 16 + 16 + 25 + 25 + 25 + 36) + 81 + 100 + 121 + 289));
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  WARN("operators against the oracle: " << compared << " comparisons in " << seconds << " s");
}

namespace {

// k random vector inputs v1..vk (on every vector blade, or 4 of them in the large algebras): their product is
// a versor.
std::vector<Input> random_vectors(std::mt19937& rng, const og::Algebra& alg, int k) {
  std::vector<Input> vs;
  const int cap = alg.dim() <= 5 ? alg.dim() : 4;  // sparser vectors in the large algebras
  for (int i = 1; i <= k; ++i) {
    Input v = random_input(rng, alg, "v" + std::to_string(i), 1, cap);
    while (std::abs(og::reverse_norm_squared(alg, v.oracle)) < 0.25)  // not (nearly) null: invertible
      v = random_input(rng, alg, v.name, 1, cap);
    vs.push_back(v);
  }
  return vs;
}

}  // namespace

TEST_CASE("igp, invert and normalize match the oracle on versors in every built-in algebra") {
  for (const std::string& name : algebra::builtin_names()) {
    INFO("algebra " << name);
    algebra::Using use(algebra::builtin(name));
    const og::Algebra alg = oracle_algebra(name);
    const int n = alg.dim();
    std::mt19937 rng(7700u + static_cast<unsigned>(n));
    for (int k = 1; k <= (n <= 5 ? 3 : 2); ++k)
      for (int r = 0; r <= n; ++r) {
        INFO("a versor of " << k << " vectors, A of grade " << r);
        std::vector<Input> ins = random_vectors(rng, alg, k);
        const Input a = random_input(rng, alg, "A", r, blade_cap(n));
        std::string script = pragma(a), versor;
        og::MV V{{0u, 1.0}};
        for (const Input& v : ins) {
          script += pragma(v);
          versor += (versor.empty() ? "" : " * ") + v.name;
          V = og::product(alg, V, v.oracle, og::Op::Geometric);
        }
        ins.push_back(a);
        script += "V = " + versor + ";\n?q = igp(A, V);\n?vi = invert(V);\n?nv = normalize(V);\n";
        const auto got = run(name, script, ins);
        auto get = [&](const std::string& o) { return got.count(o) ? got.at(o) : Named{}; };
        // The oracle's inverse of a versor: ~V / <V ~V>_0; and igp(A, V) * V must give A back.
        const double vv = og::reverse_norm_squared(alg, V), aa = og::reverse_norm_squared(alg, a.oracle);
        REQUIRE(std::abs(vv) > 1e-6);
        const og::MV vinv = og::scaled(og::reverse(V), 1.0 / vv);
        const Named q = get("q");
        CHECK(max_diff(q, from_oracle(alg, og::product(alg, a.oracle, vinv, og::Op::Geometric))) < 1e-9 * (1 + max_abs(q)));
        og::MV q_oracle;
        for (const auto& [blade, c] : q)
          for (const auto& [x, cx] : og::user_blade(alg, blade)) og::add(q_oracle, x, c * cx);
        const Named back = from_oracle(alg, og::product(alg, q_oracle, V, og::Op::Geometric));
        CHECK(max_diff(back, from_oracle(alg, a.oracle)) < 1e-8 * (1 + max_abs(back)));
        CHECK(max_diff(get("vi"), from_oracle(alg, vinv)) < 1e-9 * (1 + max_abs(get("vi"))));
        CHECK(max_diff(get("nv"), from_oracle(alg, og::scaled(V, 1.0 / std::sqrt(std::abs(vv))))) < 1e-9);
        // A of one grade: normalize is refused only where <A ~A>_0 is identically 0 (a null blade set: PGA's
        // blades with e0, CGA's with einf and not e0, ...).
        std::map<std::string, Named> normalized;
        try {
          normalized = run(name, pragma(a) + "?na = normalize(A);\n", {a});
        } catch (const front::CompileError& e) {
          CHECK_THAT(e.what(), Catch::Matchers::Contains("squared norm <X ~X>_0 is 0"));
          CHECK(aa == 0.0);
        }
        if (!normalized.empty()) {
          const Named na = normalized.at("na");
          CHECK(max_diff(na, from_oracle(alg, og::scaled(a.oracle, 1.0 / std::sqrt(std::abs(aa))))) < 1e-9);
          og::MV na_oracle;
          for (const auto& [blade, c] : na)
            for (const auto& [x, cx] : og::user_blade(alg, blade)) og::add(na_oracle, x, c * cx);
          CHECK(std::abs(std::abs(og::reverse_norm_squared(alg, na_oracle)) - 1.0) < 1e-9);
        }
      }
  }
}

TEST_CASE("invert inverts any invertible multivector, not only versors, in every built-in algebra") {
  // X mixes grades, so X ~X is not a scalar: the inverse comes from X conj(X) or from the adjugate. In up to 4
  // dimensions X holds every blade; in 5 (CGA, CRA) a scalar and 4 bivectors, the most the work budget takes
  // for the adjugate of 5D (7 products); above, a scalar and a vector (X conj(X) is a scalar).
  for (const std::string& name : algebra::builtin_names()) {
    INFO("algebra " << name);
    algebra::Using use(algebra::builtin(name));
    const og::Algebra alg = oracle_algebra(name);
    const int n = alg.dim();
    std::mt19937 rng(9100u + static_cast<unsigned>(n));
    for (int t = 0; t < 3; ++t) {
      Input x{"X", {}, {}, {}};
      auto add_grade = [&](int k, int cap) {
        const Input g = random_input(rng, alg, "X", k, cap);
        x.blades.insert(x.blades.end(), g.blades.begin(), g.blades.end());
        x.values.insert(x.values.end(), g.values.begin(), g.values.end());
        x.oracle = og::sum(x.oracle, g.oracle);
      };
      if (n <= 4) {
        for (int k = 0; k <= n; ++k) add_grade(k, 1 << n);
      } else if (n == 5) {
        add_grade(0, 1);
        add_grade(2, 4);
      } else {
        add_grade(0, 1);
        add_grade(1, 2);
      }
      INFO(pragma(x));
      const auto got = run(name, pragma(x) + "?xi = invert(X);\n?q = igp(" + alg.names[0] + ", X);\n", {x});
      og::MV xi;
      for (const auto& [blade, c] : got.at("xi"))
        for (const auto& [b, cb] : og::user_blade(alg, blade)) og::add(xi, b, c * cb);
      const og::MV one{{0u, 1.0}};
      const double scale = 1 + max_abs(got.at("xi")) * (1 + max_abs(from_oracle(alg, x.oracle)));
      CHECK(max_diff(from_oracle(alg, og::product(alg, x.oracle, xi, og::Op::Geometric)), from_oracle(alg, one)) <
            1e-9 * scale);
      CHECK(max_diff(from_oracle(alg, og::product(alg, xi, x.oracle, og::Op::Geometric)), from_oracle(alg, one)) <
            1e-9 * scale);
      // igp(v, X) = v * invert(X) for the first basis vector v.
      og::MV e1;
      for (const auto& [b, cb] : og::user_blade(alg, alg.names[0])) og::add(e1, b, cb);
      const Named want = from_oracle(alg, og::product(alg, e1, xi, og::Op::Geometric));
      const Named q = got.count("q") ? got.at("q") : Named{};
      CHECK(max_diff(q, want) < 1e-9 * scale);
    }
  }
}


TEST_CASE("bad calls of the operators are located errors") {
  using Catch::Matchers::Contains;
  using Catch::Matchers::StartsWith;
  CHECK_THAT(error_of("3d", "?z = grade(e1 + e2, k);\n"),
             StartsWith("bad.clu:1:21: error: 'grade' takes as its second argument an integer constant from 0 to 3"));
  CHECK_THAT(error_of("cga", "?z = grade(e1, 6);\n"), StartsWith("bad.clu:1:16: error: 'grade'"));
  CHECK_THAT(error_of("cga", "?z = grade(e1, -1);\n"), StartsWith("bad.clu:1:16: error: 'grade'"));
  CHECK_THAT(error_of("sta", "?z = grade(e1, 1.5);\n"), StartsWith("bad.clu:1:16: error: 'grade'"));
  CHECK_THAT(error_of("sta", "?z = grade(e1, e2);\n"), StartsWith("bad.clu:1:16: error: 'grade'"));
  CHECK(error_of("3d", "?z = grade(e1 + e2, 1);\n") == "no error");
  CHECK(error_of("3d", "?z = lcont(e1);\n") == "bad.clu:1:6: error: 'lcont' takes 2 arguments, got 1");
  CHECK(error_of("3dpga", "?z = rp(e1, e2, e3);\n") == "bad.clu:1:6: error: 'rp' takes 2 arguments, got 3");
  CHECK(error_of("cga", "?z = conjugate();\n") == "bad.clu:1:6: error: 'conjugate' takes 1 argument, got 0");
  CHECK(error_of("cga", "?z = grade(e1);\n") == "bad.clu:1:6: error: 'grade' takes 2 arguments, got 1");
  // invert and igp refuse what is not invertible symbolically: a zero divisor (1 + e1)(1 - e1) = 0, a null
  // vector, an element whose determinant vanishes identically.
  CHECK(error_of("3d", "?x = invert(1 + e1);\n") ==
        "bad.clu:1:15: error: cannot divide by this multivector: it has no inverse (d*conjugate(d) = 0)");
  CHECK(error_of("sta", "?x = invert((1 + e0)*(a + e1 + e1^e2^e3));\n") ==
        "bad.clu:1:21: error: cannot divide by this multivector: it has no inverse (its determinant d*adj(d) is 0)");
  CHECK_THAT(error_of("cga", "?x = invert(a*einf);\n"), StartsWith("bad.clu:1:14: error: cannot divide by a null multivector"));
  CHECK_THAT(error_of("3dpga", "?y = igp(e1, e0);\n"), StartsWith("bad.clu:1:14: error: cannot divide by a null multivector"));
  CHECK(error_of("3d", "?y = igp(e1, a*e1 + b*e2);\n") == "no error");
  CHECK(error_of("cga", "?x = invert(0);\n") == "bad.clu:1:13: error: division by zero");
  CHECK(error_of("sta", "?x = igp(e1, 0);\n") == "bad.clu:1:14: error: division by zero");
  CHECK_THAT(error_of("cga", "?z = normalize(0);\n"), StartsWith("bad.clu:1:16: error: 'normalize' of a multivector"));
  CHECK_THAT(error_of("cga", "?z = normalize(x*einf + y*(e1^einf));\n"),
             StartsWith("bad.clu:1:23: error: 'normalize' of a multivector whose squared norm <X ~X>_0 is 0"));
  CHECK_THAT(error_of("3d", "?z = hip(e1);\n"), Contains("'hip' takes 2 arguments"));
}

TEST_CASE("the oracle's operators satisfy their textbook identities") {
  // Checks of the oracle itself, not of the generator: for a vector a and any B (B^ the grade involution),
  // a ⌋ B = (aB − B^a)/2, a ^ B = (aB + B^a)/2, B ⌊ a = (Ba − aB^)/2; A ⌋ dual(B) = dual(A ^ B) where the dual
  // is A I^-1; undual(dual(A)) = A; the conjugate is the involute of the reverse; the dot product is the
  // Hestenes inner product plus the scalar parts' multiples.
  for (const std::string name : {"3d", "sta", "cga", "3dpga"}) {
    INFO("algebra " << name);
    algebra::Using use(algebra::builtin(name));
    const og::Algebra alg = oracle_algebra(name);
    std::mt19937 rng(99);
    for (int t = 0; t < 20; ++t) {
      const og::MV a = random_input(rng, alg, "a", 1, alg.dim()).oracle;
      og::MV A, B;
      for (int k = 0; k <= alg.dim(); ++k) {
        A = og::sum(A, random_input(rng, alg, "A", k, 3).oracle);
        B = og::sum(B, random_input(rng, alg, "B", k, 3).oracle);
      }
      auto close = [&](const og::MV& x, const og::MV& y) { return max_diff(from_oracle(alg, x), from_oracle(alg, y)) < 1e-9; };
      const og::MV aB = og::product(alg, a, B, og::Op::Geometric), Ba = og::product(alg, B, a, og::Op::Geometric);
      const og::MV hBa = og::product(alg, og::involute(B), a, og::Op::Geometric);
      const og::MV ahB = og::product(alg, a, og::involute(B), og::Op::Geometric);
      CHECK(close(og::graded(alg, a, B, og::Graded::Left), og::scaled(og::sum(aB, hBa, -1.0), 0.5)));
      CHECK(close(og::product(alg, a, B, og::Op::Outer), og::scaled(og::sum(aB, hBa), 0.5)));
      CHECK(close(og::graded(alg, B, a, og::Graded::Right), og::scaled(og::sum(Ba, ahB, -1.0), 0.5)));
      CHECK(close(og::undual(alg, og::dual(alg, A)), A));
      CHECK(close(og::conjugate(A), og::involute(og::reverse(A))));
      CHECK(close(og::graded(alg, A, B, og::Graded::Scalar), og::grade(og::product(alg, A, B, og::Op::Geometric), 0)));
      const og::MV a0 = og::grade(A, 0), b0 = og::grade(B, 0);
      CHECK(close(og::graded(alg, A, B, og::Graded::Dot),
                  og::sum(og::sum(og::sum(og::product(alg, A, B, og::Op::Inner), og::product(alg, a0, B, og::Op::Geometric)),
                                  og::product(alg, A, b0, og::Op::Geometric)),
                          og::product(alg, a0, b0, og::Op::Geometric), -1.0)));
      if (name != std::string("3dpga"))
        CHECK(close(og::graded(alg, A, og::dual(alg, B), og::Graded::Left), og::dual(alg, og::product(alg, A, B, og::Op::Outer))));
    }
  }
  // The regressive product in 3D PGA: the join of two points is the line through them (a bivector).
  algebra::Using use(algebra::builtin("3dpga"));
  const og::Algebra alg = oracle_algebra("3dpga");
  auto point = [&](double x, double y, double z) {  // e123 - x e023 + y e013 - z e012 (createPoint)
    og::MV p;
    const std::pair<const char*, double> parts[] = {{"e1^e2^e3", 1}, {"e0^e2^e3", -x}, {"e0^e1^e3", y}, {"e0^e1^e2", -z}};
    for (const auto& [n, c] : parts)
      for (const auto& [b, cb] : og::user_blade(alg, n)) og::add(p, b, c * cb);
    return og::clean(p);
  };
  const og::MV P = point(1, 2, 3), Q = point(-1, 0, 4);
  const og::MV line = og::regressive(alg, P, Q);
  for (const auto& [b, c] : line) CHECK(std::popcount(b) == 2);
  CHECK(!line.empty());
  // The line contains P and Q: joining it with either gives 0; with a point off the line, a plane (a vector).
  CHECK(og::clean(og::regressive(alg, line, P), 1e-12).empty());
  CHECK(og::clean(og::regressive(alg, line, Q), 1e-12).empty());
  const og::MV plane = og::clean(og::regressive(alg, line, point(0, 0, 0)), 1e-12);
  CHECK(!plane.empty());
  for (const auto& [b, c] : plane) CHECK(std::popcount(b) == 1);
}
