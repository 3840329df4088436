// Every built-in algebra (and a user definition.csv) against the independent any-signature oracle
// (tests/oracle/include/oracle/algebra.hpp): geometric, outer and inner products, dual and reverse of the
// generator's symbolic multivectors on random sparse multivectors; then scripts through `cgagen --algebra
// ... --eval` (PGA, G3, STA, a user file), the op counts docs/generator.md quotes, generator time, and
// located errors for bad definition files.
#include <catch2/catch.hpp>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "algebra/algebra.hpp"
#include "algebra/blade.hpp"
#include "emit/emit.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "oracle/algebra.hpp"
#include "oracle_algebras.hpp"
#include "symbolic/multivector.hpp"

using namespace cgagen;
namespace og = oracle::ga;

namespace {

Named from_generator(const symbolic::Multivector& m) {
  Named r;
  for (const auto& [b, c] : m.terms()) {
    GiNaC::ex v = GiNaC::evalf(c);
    REQUIRE(GiNaC::is_a<GiNaC::numeric>(v));
    r[algebra::blade_name(b)] = GiNaC::ex_to<GiNaC::numeric>(v).to_double();
  }
  return r;
}

// A random sparse multivector: `blades` blades anywhere among the algebra's 2^n, small integer coefficients.
struct Pair {
  symbolic::Multivector gen;
  og::MV oracle;
};
Pair random_mv(std::mt19937& rng, const og::Algebra& alg, int blades) {
  std::uniform_int_distribution<int> pick(0, algebra::blade_count() - 1), num(-5, 5);
  Pair p;
  for (int k = 0; k < blades; ++k) {
    const int b = pick(rng), c = num(rng);
    if (c == 0) continue;
    p.gen += symbolic::Multivector::blade(b, c);
    for (const auto& [x, cx] : og::user_blade(alg, algebra::blade_name(b))) og::add(p.oracle, x, c * cx);
  }
  p.oracle = og::clean(p.oracle);
  return p;
}

}  // namespace

TEST_CASE("every built-in algebra's products, dual and reverse match the oracle") {
  for (const std::string& name : algebra::builtin_names()) {
    INFO("algebra " << name);
    algebra::Using use(algebra::builtin(name));
    const og::Algebra alg = oracle_algebra(name);
    REQUIRE(algebra::current().dimension() == alg.dim());
    for (int k = 0; k < alg.dim(); ++k) REQUIRE(algebra::current().vector_names()[k] == alg.names[k]);
    std::mt19937 rng(1234);
    const bool big = alg.dim() > 10;  // ccga: sparse sampling, fewer and smaller multivectors
    const int trials = big ? 12 : 40, blades = big ? 3 : 5;
    for (int t = 0; t < trials; ++t) {
      Pair a = random_mv(rng, alg, blades), b = random_mv(rng, alg, blades);
      INFO("a = " << a.gen << ", b = " << b.gen);
      CHECK(max_diff(from_generator(a.gen * b.gen), from_oracle(alg, og::product(alg, a.oracle, b.oracle, og::Op::Geometric))) < 1e-9);
      CHECK(max_diff(from_generator(a.gen ^ b.gen), from_oracle(alg, og::product(alg, a.oracle, b.oracle, og::Op::Outer))) < 1e-9);
      CHECK(max_diff(from_generator(inner(a.gen, b.gen)), from_oracle(alg, og::product(alg, a.oracle, b.oracle, og::Op::Inner))) < 1e-9);
      CHECK(max_diff(from_generator(a.gen.dual()), from_oracle(alg, og::dual(alg, a.oracle))) < 1e-9);
      CHECK(max_diff(from_generator(a.gen.reverse()), from_oracle(alg, og::reverse(a.oracle))) < 1e-9);
    }
  }
}

TEST_CASE("blade order: by grade, then lexicographic in the algebra's vector order") {
  algebra::Using use(algebra::builtin("3dpga"));
  CHECK(algebra::blade_count() == 16);
  CHECK(algebra::blade_name(1) == "e0");
  CHECK(algebra::blade_name(5) == "e0^e1");
  CHECK(algebra::blade_name(11) == "e0^e1^e2");
  CHECK(algebra::blade_ident(11) == "e012");
  CHECK(algebra::blade_name(15) == "e0^e1^e2^e3");
  algebra::Using big(algebra::builtin("ccga"));
  CHECK(algebra::blade_count() == 65536);
  CHECK(algebra::blade_name(65535).size() > 40);
  CHECK(algebra::blade_ident(algebra::parse_blade("eo1^ei1")->index) == "eo1_i1");
}

TEST_CASE("the PGA dual is Gaalop's complement map, an involution") {
  algebra::Using use(algebra::builtin("3dpga"));
  auto b = [](const char* n) { return symbolic::Multivector::blade(algebra::parse_blade(n)->index); };
  CHECK(b("e0").dual() == b("e1^e2^e3"));
  CHECK(b("e0^e1").dual() == b("e2^e3"));
  CHECK(b("e1^e3").dual() == b("e0^e2"));
  CHECK(symbolic::Multivector(GiNaC::ex(1)).dual() == b("e0^e1^e2^e3"));
  GiNaC::realsymbol x("x"), y("y");
  const symbolic::Multivector m = x * b("e0^e1") + y * b("e1^e2^e3") + b("e2");
  CHECK(m.dual().dual() == m);
}

// ---- definition files ----------------------------------------------------------------------------------

namespace {

std::string write(const std::string& name, const std::string& text) {
  std::string path = std::string(CGA_BINARY_DIR) + "/algebra_test_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Conformal 1D geometry in a file: e1, ni, no over diagonal e1, ep, em (the CGA pattern).
const char* kUserCsv =
    "1,e1,no,ni\n"
    "ep=0.5*ni-no,em=0.5*ni+no\n"
    "1,e1,ep,em\n"
    "e1=1,ep=1,em=-1\n"
    "no=0.5*em-0.5*ep,ni=em+ep\n";

std::string expect_error(const std::string& text) {
  try {
    algebra::parse_definition(text, "bad.csv", "bad");
  } catch (const algebra::AlgebraError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST_CASE("a user definition.csv matches the oracle") {
  auto a = algebra::load(write("conf1d.csv", kUserCsv));
  CHECK(a->name() == "algebra_test_conf1d");
  algebra::Using use(a);
  auto alg = og::Algebra::diagonal({1, 1, -1}, {"e1", "no", "ni"});
  alg.null_pair(1, 2, 1, 2);
  std::mt19937 rng(7);
  for (int t = 0; t < 30; ++t) {
    Pair x = random_mv(rng, alg, 4), y = random_mv(rng, alg, 4);
    CHECK(max_diff(from_generator(x.gen * y.gen), from_oracle(alg, og::product(alg, x.oracle, y.oracle, og::Op::Geometric))) < 1e-9);
    CHECK(max_diff(from_generator(x.gen.dual()), from_oracle(alg, og::dual(alg, x.oracle))) < 1e-9);
  }
}

TEST_CASE("bad definition files give located errors") {
  CHECK(expect_error("e1,e2\n\n1,e1,e2\ne1=1,e2=1\n\n") == "bad.csv:1: error: a basis line starts with 1 (the scalar), e.g. 1,e1,e2,e3");
  CHECK(expect_error("1,e1,e2\n\n1,e1,e2\ne1=1,e2=2\n\n").rfind("bad.csv:4: error: the metric of 'e2' is '2'", 0) == 0);
  CHECK(expect_error("1,e1,e2\n\n1,e1,e2\ne1=1\n\n") == "bad.csv:4: error: no metric for diagonal vector 'e2'");
  CHECK(expect_error("1,e1,e2\n\n1,e1,e3\ne1=1,e3=1\n\n").rfind("bad.csv:2: error: diagonal vector 'e3'", 0) == 0);
  CHECK(expect_error("1,e1,n\nep=n\n1,e1,ep\ne1=1,ep=1\nn=2*ep\n").rfind("bad.csv:5: error: user vector 'n' taken", 0) == 0);
  CHECK(expect_error("1,e1,e1\n\n1,e1,e2\ne1=1,e2=1\n\n") == "bad.csv:1: error: basis vector 'e1' is listed twice");
  CHECK(expect_error("1,e1,e2\n").rfind("bad.csv:1: error: a definition.csv has 5 lines", 0) == 0);
  CHECK(expect_error("1,e1,n\nep=0.70710678118654752*n\n1,e1,ep\ne1=1,ep=1\nn=ep\n").rfind("bad.csv:2: error: coefficient", 0) == 0);
  CHECK(expect_error("1,e1,n\nep=q\n1,e1,ep\ne1=1,ep=1\nn=ep\n").rfind("bad.csv:2: error: 'q' is not a vector", 0) == 0);
}

// ---- scripts through the CLI ---------------------------------------------------------------------------

namespace {

struct Cli {
  int code;
  std::string out;
};
Cli run_cli(const std::string& args) {
  std::string cmd = std::string(CGAGEN_EXE) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  REQUIRE(p);
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) out.append(buf, n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

// `cgagen --algebra A --eval SCRIPT VALUES`: "OUTPUT BLADE" -> value.
std::map<std::string, double> eval(const std::string& algebra_arg, const std::string& name, const std::string& script,
                                   const std::string& values) {
  Cli r = run_cli("--algebra " + algebra_arg + " --eval " + write(name, script) + " " + values);
  INFO(r.out);
  REQUIRE(r.code == 0);
  std::map<std::string, double> m;
  std::istringstream in(r.out);
  std::string out, blade;
  double v;
  while (in >> out >> blade >> v) m[out + " " + blade] = v;
  return m;
}

// The oracle's value of output `out` into the same keys (zero coefficients included as the tool prints them).
void expect_matches(const std::map<std::string, double>& got, const std::string& out, const og::Algebra& alg,
                    const og::MV& want) {
  Named w = from_oracle(alg, want);
  for (const auto& [k, v] : got) {
    if (k.rfind(out + " ", 0) != 0) continue;
    const std::string blade = k.substr(out.size() + 1);
    INFO(k);
    CHECK(std::abs(v - (w.count(blade) ? w.at(blade) : 0.0)) < 1e-9);
    w.erase(blade);
  }
  for (const auto& [blade, v] : w) {
    INFO(out << " " << blade << " missing from the tool's output");
    CHECK(std::abs(v) < 1e-12);
  }
}

og::MV user_mv(const og::Algebra& alg, const std::vector<std::pair<std::string, double>>& terms) {
  og::MV r;
  for (const auto& [n, c] : terms)
    for (const auto& [x, cx] : og::user_blade(alg, n)) og::add(r, x, c * cx);
  return og::clean(r);
}

}  // namespace

TEST_CASE("a PGA script gives the oracle's values through cgagen --algebra 3dpga --eval") {
  const auto alg = oracle_algebra("3dpga");
  const std::string script =
      "#pragma input M 1 e0^e1 e0^e2 e0^e3 e1^e2 e1^e3 e2^e3 e0^e1^e2^e3\n"
      "P = createPoint(x, y, z);\n"
      "?Q = M * P * ~M;\n"
      "?J = regProd(P, createPoint(1, 2, 4));\n"
      "?D = Dual(P);\n"
      "?N = Normalize(M);\n";
  const std::vector<double> mv = {0.8, 0.3, -0.2, 0.5, 0.1, -0.4, 0.35, 0.05};
  auto got = eval("3dpga", "pga.clu", script, "M=0.8,0.3,-0.2,0.5,0.1,-0.4,0.35,0.05 x=1.5 y=-0.5 z=2");
  const og::MV M = user_mv(alg, {{"1", mv[0]}, {"e0^e1", mv[1]}, {"e0^e2", mv[2]}, {"e0^e3", mv[3]}, {"e1^e2", mv[4]},
                                 {"e1^e3", mv[5]}, {"e2^e3", mv[6]}, {"e0^e1^e2^e3", mv[7]}});
  auto point = [&](double x, double y, double z) {  // e123 - x e023 + y e013 - z e012
    return user_mv(alg, {{"e1^e2^e3", 1}, {"e0^e2^e3", -x}, {"e0^e1^e3", y}, {"e0^e1^e2", -z}});
  };
  const og::MV P = point(1.5, -0.5, 2);
  expect_matches(got, "Q", alg, og::product(alg, og::product(alg, M, P, og::Op::Geometric), og::reverse(M), og::Op::Geometric));
  expect_matches(got, "J", alg, og::dual(alg, og::product(alg, og::dual(alg, P), og::dual(alg, point(1, 2, 4)), og::Op::Outer)));
  expect_matches(got, "D", alg, og::dual(alg, P));
  const og::MV mm = og::product(alg, M, og::reverse(M), og::Op::Geometric);
  og::MV n = M;
  for (auto& [b, c] : n) c /= std::sqrt(std::abs(mm.count(0u) ? mm.at(0u) : 0.0));
  expect_matches(got, "N", alg, n);
}

TEST_CASE("a G3 script gives the oracle's values through cgagen --algebra 3d --eval") {
  const auto alg = oracle_algebra("3d");
  const std::string script =
      "#pragma input R 1 e1^e2 e1^e3 e2^e3\n"
      "v = createPoint(x, y, z);\n"
      "u = createPoint(1, -2, 0.5);\n"
      "?w = R * v * ~R;\n"
      "?o = v ^ u;\n"
      "?i = (v ^ u) . v;\n"
      "?d = *v;\n";
  auto got = eval("3d", "g3.clu", script, "R=0.6,0.2,-0.5,0.3 x=0.7 y=1.1 z=-0.4");
  const og::MV R = user_mv(alg, {{"1", 0.6}, {"e1^e2", 0.2}, {"e1^e3", -0.5}, {"e2^e3", 0.3}});
  const og::MV v = user_mv(alg, {{"e1", 0.7}, {"e2", 1.1}, {"e3", -0.4}});
  const og::MV u = user_mv(alg, {{"e1", 1}, {"e2", -2}, {"e3", 0.5}});
  expect_matches(got, "w", alg, og::product(alg, og::product(alg, R, v, og::Op::Geometric), og::reverse(R), og::Op::Geometric));
  expect_matches(got, "o", alg, og::product(alg, v, u, og::Op::Outer));
  expect_matches(got, "i", alg, og::product(alg, og::product(alg, v, u, og::Op::Outer), v, og::Op::Inner));
  expect_matches(got, "d", alg, og::dual(alg, v));
}

TEST_CASE("#pragma normalized: sandwiches of normalized versors give the oracle's values at -O2") {
  // The rewritten outputs are right for inputs with X ~X = 1 (random unit G3 rotors, random PGA motors T R)
  // and, as promised, only for those: a rotor scaled by 2 gives a different value than the oracle's.
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto g3 = oracle_algebra("3d"), pga = oracle_algebra("3dpga");
  const std::string g3_script =
      "#pragma input R 1 e1^e2 e1^e3 e2^e3\n#pragma normalized R\nv = createPoint(x, y, z);\n?w = R * v * ~R;\n";
  const std::string pga_script =
      "#pragma input M 1 e0^e1 e0^e2 e0^e3 e1^e2 e1^e3 e2^e3 e0^e1^e2^e3\n#pragma normalized M\n"
      "P = createPoint(x, y, z);\n?Q = M * P * ~M;\n";
  const std::vector<std::string> motor_blades = {"1", "e0^e1", "e0^e2", "e0^e3", "e1^e2", "e1^e3", "e2^e3", "e0^e1^e2^e3"};
  auto fmt = [](double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.17g", v);
    return std::string(b);
  };
  for (int trial = 0; trial < 8; ++trial) {
    INFO("trial " << trial);
    const double x = 2 * u(rng), y = 2 * u(rng), z = 2 * u(rng);
    const std::string point_args = " x=" + fmt(x) + " y=" + fmt(y) + " z=" + fmt(z);
    // G3: a unit rotor.
    std::vector<double> q(4);
    double n2 = 0;
    for (auto& c : q) {
      c = u(rng);
      n2 += c * c;
    }
    for (auto& c : q) c /= std::sqrt(n2);
    const og::MV R = user_mv(g3, {{"1", q[0]}, {"e1^e2", q[1]}, {"e1^e3", q[2]}, {"e2^e3", q[3]}});
    const og::MV v = user_mv(g3, {{"e1", x}, {"e2", y}, {"e3", z}});
    auto got = eval("3d", "g3_normalized.clu", g3_script,
                    "R=" + fmt(q[0]) + "," + fmt(q[1]) + "," + fmt(q[2]) + "," + fmt(q[3]) + point_args);
    expect_matches(got, "w", g3, og::product(g3, og::product(g3, R, v, og::Op::Geometric), og::reverse(R), og::Op::Geometric));
    // PGA: M = T R, a rotor about a random axis through the origin, then a random translation.
    double b2 = 0;
    std::vector<double> b(3), t(3);
    for (auto& c : b) {
      c = u(rng);
      b2 += c * c;
    }
    for (auto& c : t) c = 2 * u(rng);
    const double angle = 3 * u(rng), cs = std::cos(angle / 2), sn = std::sin(angle / 2) / std::sqrt(b2);
    const og::MV Rm = user_mv(pga, {{"1", cs}, {"e1^e2", sn * b[0]}, {"e1^e3", sn * b[1]}, {"e2^e3", sn * b[2]}});
    const og::MV T = user_mv(pga, {{"1", 1}, {"e0^e1", t[0] / 2}, {"e0^e2", t[1] / 2}, {"e0^e3", t[2] / 2}});
    const og::MV M = og::product(pga, T, Rm, og::Op::Geometric);
    const Named m = from_oracle(pga, M);
    std::string margs = "M=";
    for (size_t i = 0; i < motor_blades.size(); ++i)
      margs += (i ? "," : "") + fmt(m.count(motor_blades[i]) ? m.at(motor_blades[i]) : 0.0);
    const og::MV P = user_mv(pga, {{"e1^e2^e3", 1}, {"e0^e2^e3", -x}, {"e0^e1^e3", y}, {"e0^e1^e2", -z}});
    got = eval("3dpga", "pga_normalized.clu", pga_script, margs + point_args);
    expect_matches(got, "Q", pga, og::product(pga, og::product(pga, M, P, og::Op::Geometric), og::reverse(M), og::Op::Geometric));
  }
  // A rotor that is not normalized (R = 2): the sandwich is 4 v, which the plain kernel gives and the
  // rewritten one does not (it has used R ~R = 1).
  auto got = eval("3d", "g3_normalized.clu", g3_script, "R=2,0,0,0 x=1 y=0 z=0");
  CHECK(std::abs(got.at("w e1") - 4.0) > 1);
  got = eval("3d", "g3_plain.clu", "#pragma input R 1 e1^e2 e1^e3 e2^e3\nv = createPoint(x, y, z);\n?w = R * v * ~R;\n",
             "R=2,0,0,0 x=1 y=0 z=0");
  CHECK(std::abs(got.at("w e1") - 4.0) < 1e-12);
}

TEST_CASE("#pragma normalized names must be multivector inputs (located errors)") {
  Cli scalar = run_cli("--algebra 3d " + write("normalized_scalar.clu", "#pragma normalized s\n?w = s * e1;\n"));
  CHECK(scalar.code == 1);
  CHECK(scalar.out.find("normalized_scalar.clu:1:20: error: '#pragma normalized' names 's', which is not a multivector "
                        "input (declare it with '#pragma input s BLADE...')") != std::string::npos);
  Cli none = run_cli("--algebra 3d " + write("normalized_none.clu", "#pragma normalized\n?w = e1;\n"));
  CHECK(none.code == 1);
  CHECK(none.out.find("'#pragma normalized' needs at least one input name") != std::string::npos);
}

TEST_CASE("an STA script gives the oracle's values through cgagen --algebra sta --eval") {
  const auto alg = oracle_algebra("sta");
  const std::string script =
      "#pragma input B e0^e1 e0^e2 e1^e2\n"
      "a = createPoint(t, x, y, z);\n"
      "?r = B * a * ~B;\n"
      "?g = a * (e0 + 0.5*e3);\n"
      "?d = *a;\n"
      "?s = a . a;\n";
  auto got = eval("sta", "sta.clu", script, "B=0.4,-0.7,0.2 t=2 x=0.5 y=-1 z=0.25");
  const og::MV B = user_mv(alg, {{"e0^e1", 0.4}, {"e0^e2", -0.7}, {"e1^e2", 0.2}});
  const og::MV a = user_mv(alg, {{"e0", 2}, {"e1", 0.5}, {"e2", -1}, {"e3", 0.25}});
  expect_matches(got, "r", alg, og::product(alg, og::product(alg, B, a, og::Op::Geometric), og::reverse(B), og::Op::Geometric));
  expect_matches(got, "g", alg, og::product(alg, a, user_mv(alg, {{"e0", 1}, {"e3", 0.5}}), og::Op::Geometric));
  expect_matches(got, "d", alg, og::dual(alg, a));
  expect_matches(got, "s", alg, og::product(alg, a, a, og::Op::Inner));
}

TEST_CASE("a user-file algebra script gives the oracle's values through cgagen --algebra FILE --eval") {
  auto alg = og::Algebra::diagonal({1, 1, -1}, {"e1", "no", "ni"});
  alg.null_pair(1, 2, 1, 2);
  const std::string csv = write("conf1d_cli.csv", kUserCsv);
  const std::string script =
      "X = x*e1 + 0.5*x*x*ni + no;\n"
      "Y = 2*e1 + 2*ni + no;\n"
      "?d = X . Y;\n"
      "?R = X * Y;\n"
      "?D = *X;\n"
      "?m = ep + em;\n";  // diagonal names are usable too: ep + em = ni
  auto got = eval(csv, "conf1d.clu", script, "x=1.5");
  const og::MV X = user_mv(alg, {{"e1", 1.5}, {"ni", 0.5 * 1.5 * 1.5}, {"no", 1}});
  const og::MV Y = user_mv(alg, {{"e1", 2}, {"ni", 2}, {"no", 1}});
  expect_matches(got, "d", alg, og::product(alg, X, Y, og::Op::Inner));
  expect_matches(got, "R", alg, og::product(alg, X, Y, og::Op::Geometric));
  expect_matches(got, "D", alg, og::dual(alg, X));
  expect_matches(got, "m", alg, user_mv(alg, {{"ni", 1}}));
  // -(x - 2)^2 / 2: the conformal distance
  CHECK(std::abs(got.at("d 1") + 0.5 * (1.5 - 2) * (1.5 - 2)) < 1e-12);
}

TEST_CASE("bad --algebra arguments are clear errors, not crashes") {
  Cli r = run_cli("--algebra nosuch " + write("x.clu", "?a = e1;\n"));
  CHECK(r.code == 1);
  CHECK(r.out.find("unknown algebra 'nosuch'") != std::string::npos);
  r = run_cli("--algebra " + write("broken.csv", "1,e1\n\n1,e1\ne1=5\n\n") + " " + write("x.clu", "?a = e1;\n"));
  CHECK(r.code == 1);
  CHECK(r.out.find("broken.csv:4: error: the metric of 'e1' is '5'") != std::string::npos);
  r = run_cli("--algebra 3dpga " + write("v.clu", "?a = VecN3(1, 2, 3);\n"));
  CHECK(r.code == 1);
  CHECK(r.out.find("'VecN3' is a CGA built-in; the algebra '3dpga' does not have it") != std::string::npos);
  r = run_cli("--algebra 3dpga " + write("v.clu", "?a = einf;\n"));  // a CGA name is an input in PGA
  CHECK(r.code == 0);
  // A fault inside a built-in macro is reported where the script calls it.
  r = run_cli("--algebra 3dpga " + write("n.clu", "z = 0;\n?a = Normalize(z*e1);\n"));
  CHECK(r.code == 1);
  CHECK(r.out.find("n.clu:2:6: error: in the 3dpga built-in 'Normalize': ") != std::string::npos);
}

// ---- op counts and generator time (docs/generator.md, "Algebras") --------------------------------------

#include <sys/resource.h>
#include <sys/wait.h>

namespace {

// "output Q: 36 add, 31 mul, ..." -> {add, mul} of the kernel's total line.
std::pair<int, int> total_ops(const std::string& stats) {
  auto at = stats.find("total: ");
  REQUIRE(at != std::string::npos);
  int add = -1, mul = -1;
  std::sscanf(stats.c_str() + at, "total: %d add, %d mul", &add, &mul);
  return {add, mul};
}

// CPU seconds (user + system) the children of this process have used so far: the generator's own time,
// not the wall clock of a shared machine.
double children_cpu() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-6;
}

// A 200-line script for an algebra whose createPoint takes `arity` coordinates: 100 points, 98 joins of
// neighbours (outer product; regProd of the duals in PGA, where points are (d)-vectors), two outputs that
// multiply, dualize, normalize, contract and reverse them.
std::string script_200(const std::string& algebra, int arity, bool inner_joins = false) {
  const bool pga = algebra.find("pga") != std::string::npos;
  std::string s;
  for (int k = 0; k < 100; ++k) {
    s += "P" + std::to_string(k) + " = createPoint(";
    for (int i = 0; i < arity; ++i) s += (i ? ", c" : "c") + std::to_string(k) + "_" + std::to_string(i);
    s += ");\n";
  }
  for (int k = 1; k < 99; ++k) {
    const std::string a = "P" + std::to_string(k), b = "P" + std::to_string(k - 1);
    s += "L" + std::to_string(k) + " = " +
         (pga ? "regProd(" + a + ", " + b + ")" : inner_joins ? a + " . " + b : a + " ^ " + b) + ";\n";
  }
  s += "?A = L1 * L2 + *L3 + L4 / abs(L4);\n";
  s += "?B = (L5 . P6) + ~L7;\n";
  return s;
}

const std::map<std::string, int> kArity = {{"2d", 2},  {"3d", 3},  {"2dpga", 2}, {"3dpga", 3}, {"cra", 2}, {"sta", 4},
                                           {"cga", 3}, {"gac", 2}, {"qga", 3},   {"dcga", 3},  {"ccga", 2}};

}  // namespace

TEST_CASE("op counts: PGA motor and G3 rotor sandwiches at -O2 (the numbers docs/generator.md quotes)") {
  // 3D PGA: a motor (scalar, six bivector blades, e0123) applied to a point, as the plain sandwich M*P*~M.
  Cli pga = run_cli("--algebra 3dpga --stats " +
                    write("pga_sandwich.clu", "#pragma input M 1 e0^e1 e0^e2 e0^e3 e1^e2 e1^e3 e2^e3 e0^e1^e2^e3\n"
                                              "P = createPoint(x, y, z);\n?Q = M * P * ~M;\n"));
  REQUIRE(pga.code == 0);
  CHECK(total_ops(pga.out) == std::pair{36, 31});  // add, mul; the hand form for a normalized M: 18, 25
  // G3: a rotor on a vector.
  Cli g3 = run_cli("--algebra 3d --stats " + write("g3_sandwich.clu", "#pragma input R 1 e1^e2 e1^e3 e2^e3\n"
                                                                     "v = createPoint(x, y, z);\n?w = R * v * ~R;\n"));
  REQUIRE(g3.code == 0);
  CHECK(total_ops(g3.out) == std::pair{21, 22});  // the quaternion form for a unit q: 12, 18
  // The same with `#pragma normalized`: -O2 may use X ~X = 1 (docs/generator.md, "Normalized inputs").
  Cli pga_n = run_cli("--algebra 3dpga --stats " +
                      write("pga_sandwich_n.clu", "#pragma input M 1 e0^e1 e0^e2 e0^e3 e1^e2 e1^e3 e2^e3 e0^e1^e2^e3\n"
                                                  "#pragma normalized M\nP = createPoint(x, y, z);\n?Q = M * P * ~M;\n"));
  REQUIRE(pga_n.code == 0);
  CHECK(total_ops(pga_n.out) == std::pair{18, 21});  // the hand form: 18 add, 25 mul
  Cli g3_n = run_cli("--algebra 3d --stats " + write("g3_sandwich_n.clu", "#pragma input R 1 e1^e2 e1^e3 e2^e3\n#pragma normalized R\n"
                                                                         "v = createPoint(x, y, z);\n?w = R * v * ~R;\n"));
  REQUIRE(g3_n.code == 0);
  CHECK(total_ops(g3_n.out) == std::pair{12, 18});  // the quaternion form: 12 add, 18 mul
}

TEST_CASE("a 200-line script in every built-in algebra compiles at -O2") {
  // Times are benchmark figures (bench/bench_generator.cpp, docs/generator.md), not verdicts. dcga's joins of
  // points are 4-vectors of up to 210 quartic coefficients (~3.5 s of CPU at -O2, 9 s before the work of
  // docs/generator.md "Generator time"; more under the sanitizers); the test
  // compiles the same script with inner-product joins, and the benchmark keeps the heavy one.
  for (const auto& [name, arity] : kArity) {
    INFO("algebra " << name);
    const bool heavy = name == "dcga";
    const std::string text = script_200(name, arity, heavy);
    const std::string path = write("t200_" + name + ".clu", text);
    const double before = children_cpu();
    Cli r = run_cli("--algebra " + name + " --stats " + path);
    INFO(r.out);
    REQUIRE(r.code == 0);
    CHECK(std::count(text.begin(), text.end(), '\n') == 200);
    CHECK(r.out.find("total:") != std::string::npos);
    std::printf("200-line %s script%s: %.2f s CPU (a figure, not a verdict)\n", name.c_str(),
                heavy ? " (inner-product joins)" : "", children_cpu() - before);
  }
}

TEST_CASE("every target, --stats and --diff work for every built-in algebra") {
  Cli list = run_cli("--target list");
  REQUIRE(list.code == 0);
  std::vector<std::string> targets;
  std::istringstream in(list.out);
  for (std::string t; in >> t;) targets.push_back(t);
  REQUIRE(targets.size() >= 3);
  for (const auto& [name, arity] : kArity) {
    INFO("algebra " << name);
    std::string args;
    for (int i = 0; i < arity; ++i) args += (i ? ", " : "") + std::string(i ? "y" : "x") + std::to_string(i);
    const std::string path = write("targets_" + name + ".clu", "P = createPoint(" + args + ");\n?D = *P;\n?S = P * ~P;\n");
    for (const std::string& t : targets) {
      INFO("target " << t);
      Cli r = run_cli("--algebra " + name + " --target " + t + " " + path);
      INFO(r.out);
      CHECK(r.code == 0);
    }
    CHECK(run_cli("--algebra " + name + " --stats " + path).code == 0);
    CHECK(run_cli("--algebra " + name + " --diff -O0 -O2 " + path).code == 0);
  }
  // Output blade names are the algebra's own, in its blade order.
  Cli pga = run_cli("--algebra 3dpga " + write("pga_names.clu", "?P = createPoint(x, y, z);\n"));
  CHECK(pga.out.find("{\"e0^e1^e2\", \"e0^e1^e3\", \"e0^e2^e3\", \"e1^e2^e3\"}") != std::string::npos);
}

TEST_CASE("output is byte-identical across processes in other algebras too") {
  for (const auto& [name, arity] : kArity) {
    if (name != "3dpga" && name != "qga" && name != "ccga" && name != "gac") continue;
    INFO("algebra " << name);
    const std::string path = write("det_" + name + ".clu", script_200(name, arity, true));
    const Cli first = run_cli("--algebra " + name + " " + path);
    REQUIRE(first.code == 0);
    for (int k = 0; k < 3; ++k) CHECK(run_cli("--algebra " + name + " " + path).out == first.out);
  }
  // `#pragma normalized`: its rules come from GiNaC sums, whose term order changes from process to process.
  const std::string motor = write("det_pga_normalized.clu",
                                  "#pragma input M 1 e0^e1 e0^e2 e0^e3 e1^e2 e1^e3 e2^e3 e0^e1^e2^e3\n#pragma normalized M\n"
                                  "P = createPoint(x, y, z);\n?Q = M * P * ~M;\n");
  const Cli first = run_cli("--algebra 3dpga " + motor);
  REQUIRE(first.code == 0);
  for (int k = 0; k < 5; ++k) CHECK(run_cli("--algebra 3dpga " + motor).out == first.out);
}

TEST_CASE("the algebra travels with the kernel: two algebras compiled side by side in one process") {
  // No algebra::use(): expand() takes the algebra, the Kernel and the Program carry it, and optimize(),
  // emit() and the reports install it for their duration. The thread's algebra stays CGA throughout.
  const std::string pga_text =
      "#pragma input M 1 e0^e1 e0^e2 e0^e3 e1^e2 e1^e3 e2^e3 e0^e1^e2^e3\nP = createPoint(x, y, z);\n?Q = M * P * ~M;\n";
  const std::string cga_text = "P = createPoint(x, y, z);\n?S = P - 0.5 * r * r * einf;\n";
  auto kernel = [](const std::string& text, std::shared_ptr<const algebra::Algebra> a) {
    front::SourceFile file("t.clu", text);
    return expand(front::parse(file), "t", std::move(a));
  };
  auto code = [](const Kernel& k) { return emit::emit(opt::optimize(k, opt::Level::O2), emit::EmitOptions{}); };
  const auto pga = algebra::builtin("3dpga"), cga = algebra::builtin("cga");
  const std::string pga_alone = code(kernel(pga_text, pga));
  const std::string cga_alone = code(kernel(cga_text, cga));
  CHECK(pga_alone.find("e0^e1^e2") != std::string::npos);  // PGA's blade names in PGA's output
  CHECK(cga_alone.find("e1^e2^e3") == std::string::npos);   // ... and not CGA's (its sphere is a vector)

  // Interleaved: both expanded first, then optimized and emitted in the other order.
  const Kernel kp = kernel(pga_text, pga), kc = kernel(cga_text, nullptr);  // null: the thread's, CGA
  REQUIRE(kp.algebra == pga);
  REQUIRE(kc.algebra == cga);
  const opt::Program pc = opt::optimize(kc, opt::Level::O2), pp = opt::optimize(kp, opt::Level::O2);
  CHECK(pp.algebra == pga);
  CHECK(emit::emit(pc, emit::EmitOptions{}) == cga_alone);
  CHECK(emit::emit(pp, emit::EmitOptions{}) == pga_alone);
  const std::string eval = opt::format_eval(opt::evaluate(pp, {{"x", {1}}, {"y", {2}}, {"z", {3}}, {"M", {1, 0, 0, 0, 0, 0, 0, 0}}}));
  CHECK(eval.find("Q e0^e1^e2") != std::string::npos);
  CHECK(&algebra::current() == cga.get());
}
