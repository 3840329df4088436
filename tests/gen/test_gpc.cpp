// cgagen --gpc: sources with GPC blocks (tests/gen/gpc/) rewritten by the built tool, compiled by the C++
// compiler and run; their numbers checked against the oracle (tests/oracle). Also the #line mapping (a
// deliberate C error reported at the original file's line), located diagnostics of bad blocks, and the
// same text on every run. CGAGEN_EXE, CXX_COMPILER, CGA_BINARY_DIR and GPC_DIR come from CMakeLists.txt.
#include <catch2/catch.hpp>

#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "oracle_algebras.hpp"

namespace {

const og::Algebra& cga() {
  static const og::Algebra a = oracle_algebra("cga");
  return a;
}

using Shell = cga_test::Result;

Shell sh(const std::string& cmd) { return cga_test::shell(cmd + " 2>&1"); }

std::string slurp(const std::string& path) { return cga_test::read_text(path); }

// A folder per process: ctest runs the test cases as parallel processes, which must not share files.
std::string work_dir() {
  const std::string d = std::string(CGA_BINARY_DIR) + "/gpc_work/" + std::to_string(getpid());
  std::filesystem::create_directories(d);
  return d;
}

std::string write(const std::string& name, const std::string& text) {
  const std::string path = work_dir() + "/" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

std::string replace_all(std::string s, const std::string& from, const std::string& to) {
  for (size_t p = s.find(from); p != std::string::npos; p = s.find(from, p + to.size())) s.replace(p, from.size(), to);
  return s;
}

// The blades of grade k of CGA as bitmaps over e1 e2 e3 einf e0, in the algebra's order (by grade, then
// lexicographic in the vector order): the order the contract gives outputs their blades.
std::vector<og::Bits> blades_in_order(const std::vector<og::Bits>& set) {
  std::vector<og::Bits> v = set;
  auto key = [](og::Bits b) {
    std::vector<int> idx;
    for (int k = 0; k < 32; ++k)
      if (b & (1u << k)) idx.push_back(k);
    return std::make_pair(static_cast<int>(idx.size()), idx);
  };
  std::sort(v.begin(), v.end(), [&](og::Bits a, og::Bits b) { return key(a) < key(b); });
  return v;
}

std::vector<og::Bits> grade_blades(int grade, const og::Algebra& alg = cga()) {
  std::vector<og::Bits> v;
  for (og::Bits b = 0; b < (1u << alg.dim()); ++b)
    if (std::popcount(b) == grade) v.push_back(b);
  return blades_in_order(v);
}

// A blade's name with its vectors in the given order (reversed: e2^e1, which mv_from_array reads as -e1^e2).
std::string blade_text(og::Bits b, bool reversed = false, const og::Algebra& alg = cga()) {
  std::vector<std::string> names;
  for (int k = 0; k < alg.dim(); ++k)
    if (b & (1u << k)) names.push_back(alg.names[static_cast<size_t>(k)]);
  if (names.empty()) return "1";
  if (reversed) std::reverse(names.begin(), names.end());
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : "^") + n;
  return s;
}

std::string blade_list(const std::vector<og::Bits>& blades, bool reversed = false, const og::Algebra& alg = cga()) {
  std::string s;
  for (og::Bits b : blades) s += (s.empty() ? "" : ", ") + blade_text(b, reversed, alg);
  return s;
}

// The oracle multivector sum_k values[k] * blade k (each named as written, so reversed names count with sign).
og::MV from_values(const std::vector<og::Bits>& blades, const std::vector<double>& values, bool reversed = false,
                   const og::Algebra& alg = cga()) {
  og::MV m;
  for (size_t k = 0; k < blades.size(); ++k)
    m = og::sum(m, og::scaled(og::user_blade(alg, blade_text(blades[k], reversed, alg)), values[k]));
  return m;
}

// An oracle result over the user blades: its nonzero blades in the contract's order and their values.
std::pair<std::vector<og::Bits>, std::vector<double>> expected(const og::MV& diag, const og::Algebra& alg = cga()) {
  std::vector<og::Bits> blades;
  std::map<og::Bits, double> by;
  for (const auto& [u, c] : og::to_user(alg, diag))
    if (std::abs(c) > 1e-9) blades.push_back(u), by[u] = c;
  blades = blades_in_order(blades);
  std::vector<double> values;
  for (og::Bits b : blades) values.push_back(by[b]);
  return {blades, values};
}

std::vector<double> random_values(size_t n, std::mt19937& rng) {
  std::uniform_real_distribution<double> d(-2.0, 2.0);
  std::vector<double> v(n);
  for (auto& x : v) x = d(rng);
  return v;
}

std::string array_literal(const std::vector<double>& v) {
  std::ostringstream os;
  os.precision(17);
  os << "{";
  for (size_t k = 0; k < v.size(); ++k) os << (k ? ", " : "") << v[k];
  return os.str() + "}";
}

std::vector<std::vector<double>> parse_lines(const std::string& out) {
  std::vector<std::vector<double>> rows;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream ls(line);
    std::vector<double> row;
    double x;
    while (ls >> x) row.push_back(x);
    rows.push_back(row);
  }
  return rows;
}

// cgagen --gpc SOURCE -o OUT (more options in `options`); fails the test on a nonzero status.
std::string gpc(const std::string& source, const std::string& out, const std::string& options = "") {
  const Shell r = sh(std::string(CGAGEN_EXE) + " --gpc " + options + " " + source + " -o " + out);
  INFO(r.out);
  REQUIRE(r.code == 0);
  return out;
}

// Compiles the driver (C++17, warnings as errors) and runs it: its standard output.
std::string build_and_run(const std::string& name, const std::string& driver, const std::string& flags = "") {
  const std::string src = write(name + ".cpp", driver);
  const std::string exe = work_dir() + "/" + name;
  const Shell c = sh(std::string(CXX_COMPILER) + " -std=c++17 -O1 -Wall -Wextra -Werror " + flags + " -I" + work_dir() +
                     " -o " + exe + " " + src);
  INFO(c.out);
  REQUIRE(c.code == 0);
  const Shell r = sh(exe);
  INFO(r.out);
  REQUIRE(r.code == 0);
  return r.out;
}

const char* kPrint = R"(#include <array>
#include <cstdio>
template <std::size_t N>
void print(const std::array<double, N>& a) {
  for (double x : a) std::printf(" %.17g", x);
  std::printf("\n");
}
)";

void check_row(const std::vector<double>& got, const std::vector<double>& want, const std::string& what,
               double tolerance = 1e-9) {
  INFO(what);
  REQUIRE(got.size() == want.size());
  for (size_t k = 0; k < got.size(); ++k) CHECK(std::abs(got[k] - want[k]) <= tolerance * (1 + std::abs(want[k])));
}

// The binary template for each pair of grades of `alg` (its definition file `algebra_file`, or a built-in
// name), rewritten, compiled in one driver and compared with the oracle.
void check_binary(const std::string& tag, const og::Algebra& alg, const std::string& algebra_option,
                  const std::vector<std::pair<int, int>>& pairs) {
  const std::string tmpl = slurp(std::string(GPC_DIR) + "/binary_ops.hpg.in");
  REQUIRE(!tmpl.empty());
  std::mt19937 rng(20261126);
  std::string driver = kPrint;
  std::string body;
  std::vector<std::vector<std::vector<double>>> want;  // per pair: add, sub, gp, op, ip
  for (const auto& [l, r] : pairs) {
    const std::string id = tag + "_" + std::to_string(l) + "_" + std::to_string(r);
    // The right operand's blades are written with their vectors reversed (e2^e1): mv_from_array reads the
    // coefficient of that order, i.e. minus the canonical one for an odd permutation.
    const auto lb = grade_blades(l, alg), rb = grade_blades(r, alg);
    const std::string text = replace_all(replace_all(tmpl, "@LEFT_BASIS_BLADES@", blade_list(lb, false, alg)),
                                         "@RIGHT_BASIS_BLADES@", blade_list(rb, true, alg));
    const std::string source = write(id + ".hpg", text);
    gpc(source, work_dir() + "/" + id + ".hpp", "--type double " + algebra_option);
    driver += "namespace " + id + " {\n#include \"" + id + ".hpp\"\n}\n";
    const auto lv = random_values(lb.size(), rng), rv = random_values(rb.size(), rng);
    body += "  {\n    const double lhs[] = " + array_literal(lv) + ";\n    const double rhs[] = " + array_literal(rv) +
            ";\n";
    for (const char* fn : {"gpc_add", "gpc_sub", "gpc_gp", "gpc_op", "gpc_ip"})
      body += "    print(" + id + "::" + fn + "(lhs, rhs));\n";
    body += "  }\n";
    const og::MV A = from_values(lb, lv, false, alg), B = from_values(rb, rv, true, alg);
    std::vector<std::vector<double>> w;
    for (const og::MV& m : {og::sum(A, B), og::sum(A, B, -1.0), og::product(alg, A, B, og::Op::Geometric),
                            og::product(alg, A, B, og::Op::Outer), og::product(alg, A, B, og::Op::Inner)})
      w.push_back(expected(m, alg).second);
    want.push_back(w);
  }
  driver += "int main() {\n" + body + "  return 0;\n}\n";
  const auto rows = parse_lines(build_and_run(tag + "_driver", driver));
  REQUIRE(rows.size() == 5 * pairs.size());
  const char* names[] = {"a + b", "a - b", "a * b", "a ^ b", "a . b"};
  for (size_t p = 0; p < pairs.size(); ++p)
    for (size_t f = 0; f < 5; ++f)
      check_row(rows[p * 5 + f], want[p][f],
                std::string(names[f]) + " of grades " + std::to_string(pairs[p].first) + ", " + std::to_string(pairs[p].second));
}

}  // namespace

TEST_CASE("gpc: binary operations from a template, per pair of grades, against the oracle", "[gpc]") {
  check_binary("binary", cga(), "", {{1, 1}, {1, 2}, {2, 1}, {2, 2}, {1, 3}, {2, 3}, {1, 4}});
}

TEST_CASE("gpc: --algebra with a definition file naming its vectors eo and ei, as ga-benchmark's", "[gpc]") {
  // Conformal 2D over e1 e2 eo ei (the CGA pattern of tests/gen/test_algebras.cpp, other names).
  const std::string csv = write("conf2d.csv", "1,e1,e2,eo,ei\n"
                                              "ep=0.5*ei-eo,em=0.5*ei+eo\n"
                                              "1,e1,e2,ep,em\n"
                                              "e1=1,e2=1,ep=1,em=-1\n"
                                              "eo=0.5*em-0.5*ep,ei=em+ep\n");
  auto alg = og::Algebra::diagonal({1, 1, 1, -1}, {"e1", "e2", "eo", "ei"});
  alg.null_pair(2, 3, 2, 3);
  check_binary("conf2d", alg, "--algebra " + csv, {{1, 1}, {1, 2}, {2, 2}, {1, 3}});
}

TEST_CASE("gpc: unary operations, mv_to_array over every blade and mv_get_bladecoeff, against the oracle", "[gpc]") {
  const std::string tmpl = slurp(std::string(GPC_DIR) + "/unary_ops.hpg.in");
  REQUIRE(!tmpl.empty());
  std::vector<og::Bits> all;
  for (int g = 0; g <= 5; ++g)
    for (og::Bits b : grade_blades(g)) all.push_back(b);
  std::mt19937 rng(7);
  std::string driver = "#include <cstdio>\n";
  std::string body;
  std::vector<std::vector<double>> want;
  for (int grade = 1; grade <= 4; ++grade) {
    const std::string id = "unary_" + std::to_string(grade);
    const std::string text = replace_all(replace_all(tmpl, "@BASIS_BLADES@", blade_list(grade_blades(grade))),
                                         "@ALL_BLADES@", blade_list(all));
    gpc(write(id + ".hpg", text), work_dir() + "/" + id + ".hpp", "--type double");
    driver += "namespace " + id + " {\n#include \"" + id + ".hpp\"\n}\n";
    const auto v = random_values(grade_blades(grade).size(), rng);
    body += "  {\n    const double arg[] = " + array_literal(v) + ";\n    double out[32];\n";
    for (const char* fn : {"gpc_dual", "gpc_reverse", "gpc_negate"})
      body += "    " + id + "::" + fn + "(arg, out);\n    for (double x : out) std::printf(\" %.17g\", x);\n"
              "    std::printf(\"\\n\");\n";
    body += "    std::printf(\"%.17g\\n\", " + id + "::gpc_squared_norm(arg));\n  }\n";
    const og::MV A = from_values(grade_blades(grade), v);
    for (const og::MV& m : {og::dual(cga(), A), og::reverse(A), og::scaled(A, -1.0)}) {
      std::vector<double> row(32, 0.0);
      for (const auto& [u, c] : og::to_user(cga(), m))
        row[static_cast<size_t>(std::find(all.begin(), all.end(), u) - all.begin())] = c;
      want.push_back(row);
    }
    const og::MV n = og::product(cga(), A, og::reverse(A), og::Op::Geometric);
    const auto user = og::to_user(cga(), n);
    want.push_back({user.count(0u) ? user.at(0u) : 0.0});
  }
  driver += "int main() {\n" + body + "  return 0;\n}\n";
  const auto rows = parse_lines(build_and_run("unary_driver", driver));
  REQUIRE(rows.size() == want.size());
  for (size_t k = 0; k < rows.size(); ++k) check_row(rows[k], want[k], "row " + std::to_string(k));
}

TEST_CASE("gpc: a multi-statement chain with scalar inputs and a macro, against the oracle", "[gpc]") {
  // In double as C++ and in float as CUDA's spelling (C math names), which the host compiler compiles too.
  for (const std::string target : {"cpp", "cuda"}) {
  const std::string type = target == "cpp" ? "double" : "float";
  INFO("--target " + target + " --type " + type);
  const std::string header = "chain_" + target + ".hpp";
  gpc(std::string(GPC_DIR) + "/chain.hpg", work_dir() + "/" + header, "--type " + type + " --target " + target);
  const double ang1 = 0.7, ang2 = -1.1, len = 1.5, x = 0.3, y = -0.8, z = 2.0;
  std::ostringstream call;
  call.precision(17);
  call << "gpc_chain(" << ang1 << ", " << ang2 << ", " << len << ", " << x << ", " << y << ", " << z << ", point)";
  const std::string driver = std::string(kPrint) +
                             "template <std::size_t N>\nvoid print(const std::array<float, N>& a) {\n"
                             "  for (float x : a) std::printf(\" %.9g\", x);\n  std::printf(\"\\n\");\n}\n"
                             "using T = " + type + ";\nusing chain_real = T;\n#include \"" + header + "\"\nint main() {\n  T point[5];\n  print(" +
                             call.str() +
                             ");\n  for (T p : point) std::printf(\" %.17g\", static_cast<double>(p));\n  std::printf(\"\\n\");\n}\n";
  const auto rows = parse_lines(build_and_run("chain_driver_" + target, driver));
  const double tol = type == "double" ? 1e-9 : 2e-5;
  REQUIRE(rows.size() == 2);
  auto user = [](const std::map<std::string, double>& named) {
    og::MV m;
    for (const auto& [n, c] : named) m = og::sum(m, og::scaled(og::user_blade(cga(), n), c));
    return m;
  };
  const og::MV R1 = user({{"1", std::cos(ang1 / 2)}, {"e1^e2", -std::sin(ang1 / 2)}});
  const og::MV T1 = user({{"1", 1.0}, {"e1^einf", -0.5 * len}});
  const og::MV R2 = user({{"1", std::cos(ang2 / 2)}, {"e1^e3", -std::sin(ang2 / 2)}});
  const og::MV M = og::product(cga(), og::product(cga(), R1, T1, og::Op::Geometric), R2, og::Op::Geometric);
  const og::MV X = user({{"e1", x}, {"e2", y}, {"e3", z}, {"einf", 0.5 * (x * x + y * y + z * z)}, {"e0", 1.0}});
  const og::MV P = og::product(cga(), og::product(cga(), M, X, og::Op::Geometric), og::reverse(M), og::Op::Geometric);
  check_row(rows[0], expected(M).second, "to_array(M)", tol);
  std::vector<double> point;
  const auto pu = og::to_user(cga(), P);
  for (const char* b : {"e1", "e2", "e3", "einf", "e0"}) {
    const og::Bits bits = og::to_user(cga(), og::user_blade(cga(), b)).begin()->first;
    point.push_back(pu.count(bits) ? pu.at(bits) : 0.0);
  }
  check_row(rows[1], point, "mv_to_array(P, e1, e2, e3, einf, e0)", tol);
  }
}

TEST_CASE("gpc: blocks inside #if groups compile and run, and #line maps C errors to the original lines", "[gpc]") {
  const std::string source = std::string(GPC_DIR) + "/conditional.hpg";
  gpc(source, work_dir() + "/conditional.hpp", "--type double");
  const std::string driver = "#include <cstdio>\n#include \"conditional.hpp\"\nint main() {\n"
                             "  const double u[] = {1, 2, 3}, v[] = {-1, 0.5, 2}, w[] = {0.25, -3, 1};\n"
                             "  std::printf(\"%.17g\\n\", gpc_volume(u, v, w));\n}\n";
  const auto rows = parse_lines(build_and_run("conditional_driver", driver));
  REQUIRE(rows.size() == 1);
  // det [u; v; w]
  const double det = 1 * (0.5 * 1 - 2 * -3) - 2 * (-1 * 1 - 2 * 0.25) + 3 * (-1 * -3 - 0.5 * 0.25);
  check_row(rows[0], {det}, "the e1^e2^e3 coefficient of a ^ b ^ c");

  // With GPC_LINE_CHECK, two undeclared names: the compiler must name conditional.hpg and their own lines.
  const std::string original = slurp(source);
  auto line_of = [&](const std::string& needle) {
    const size_t at = original.find(needle);
    REQUIRE(at != std::string::npos);
    return 1 + std::count(original.begin(), original.begin() + static_cast<long>(at), '\n');
  };
  const Shell c = sh(std::string(CXX_COMPILER) + " -std=c++17 -fsyntax-only -DGPC_LINE_CHECK -x c++ " + work_dir() +
                     "/conditional.hpp");
  INFO(c.out);
  CHECK(c.code != 0);
  CHECK(c.out.find("conditional.hpg:" + std::to_string(line_of("= undeclared_after_block")) + ":") != std::string::npos);
  CHECK(c.out.find("conditional.hpg:" + std::to_string(line_of("= undeclared_after_skipped_group")) + ":") !=
        std::string::npos);
  CHECK(c.out.find("conditional.hpp:") == std::string::npos);
}

TEST_CASE("gpc: a C error inside the generated statements is reported in the block's script", "[gpc]") {
  // The array mv_from_array names does not exist: the compiler's error is at the line of that
  // mv_from_array (line 4), in the original file.
  const std::string source = write("missing_array.hpg", "#include <cmath>\n"
                                                        "float f() {\n"
                                                        "#pragma gpc begin\n"
                                                        "    a = mv_from_array(no_such_array, e1, e2);\n"
                                                        "#pragma clucalc begin\n"
                                                        "    n = a . a;\n"
                                                        "    ?r = n * n;\n"
                                                        "#pragma clucalc end\n"
                                                        "#pragma gpc end\n"
                                                        "    return mv_get_bladecoeff(r, 1);\n"
                                                        "}\n");
  gpc(source, work_dir() + "/missing_array.hpp");
  const Shell c = sh(std::string(CXX_COMPILER) + " -std=c++17 -fsyntax-only -x c++ " + work_dir() + "/missing_array.hpp");
  INFO(c.out);
  CHECK(c.code != 0);
  CHECK(c.out.find("missing_array.hpg:4:") != std::string::npos);
  CHECK(c.out.find("missing_array.hpg:6:") == std::string::npos);
  CHECK(c.out.find("missing_array.hpg:7:") == std::string::npos);
  CHECK(c.out.find("no_such_array") != std::string::npos);
}

TEST_CASE("gpc: the same source gives the same text on every run", "[gpc]") {
  const std::string a = slurp(gpc(std::string(GPC_DIR) + "/chain.hpg", work_dir() + "/chain_a.hpp", "-O2"));
  const std::string b = slurp(gpc(std::string(GPC_DIR) + "/chain.hpg", work_dir() + "/chain_b.hpp", "-O2"));
  CHECK(!a.empty());
  CHECK(a == b);
}

// cgagen_generate() rewrote tests/gen/gpc/rotate.hpg at build time (tests/gen/CMakeLists.txt).
#include "rotate.hpp"

TEST_CASE("gpc: cgagen_generate() turns a .hpg source into a header, against the oracle", "[gpc]") {
  const double angle = 0.9, v[] = {1.0, -0.5, 2.0};
  const std::array<double, 3> got = gpc_generated::rotate(angle, v);
  auto named = [](const std::map<std::string, double>& m) {
    og::MV r;
    for (const auto& [n, c] : m) r = og::sum(r, og::scaled(og::user_blade(cga(), n), c));
    return r;
  };
  const og::MV R = named({{"1", std::cos(angle / 2)}, {"e1^e2", -std::sin(angle / 2)}});
  const og::MV w = og::product(cga(), og::product(cga(), R, named({{"e1", v[0]}, {"e2", v[1]}, {"e3", v[2]}}),
                                                  og::Op::Geometric),
                               og::reverse(R), og::Op::Geometric);
  check_row({got[0], got[1], got[2]}, expected(w).second, "rotate");
  CHECK(std::abs(got[2] - v[2]) < 1e-12);
}

// tests/gen/CMakeLists.txt filled binary_ops.hpg.in with configure_file() (vectors x bivectors) and ran it
// through cgagen_generate().
namespace configured {
#include "binary_ops_1_2.hpp"
}

TEST_CASE("gpc: a .hpg.in filled by configure_file() and built by cgagen_generate(), against the oracle", "[gpc]") {
  const std::vector<std::string> left{"e1", "e2", "e3", "einf", "e0"};
  const std::vector<std::string> right{"e1^e2", "e1^e3", "e1^einf", "e1^e0", "e2^e3",
                                       "e2^einf", "e2^e0", "e3^einf", "e3^e0", "einf^e0"};
  std::mt19937 rng(11);
  const auto lv = random_values(left.size(), rng), rv = random_values(right.size(), rng);
  og::MV A, B;
  for (size_t k = 0; k < left.size(); ++k) A = og::sum(A, og::scaled(og::user_blade(cga(), left[k]), lv[k]));
  for (size_t k = 0; k < right.size(); ++k) B = og::sum(B, og::scaled(og::user_blade(cga(), right[k]), rv[k]));
  auto row = [](const auto& a) { return std::vector<double>(a.begin(), a.end()); };
  check_row(row(configured::gpc_gp(lv.data(), rv.data())),
            expected(og::product(cga(), A, B, og::Op::Geometric)).second, "a * b");
  check_row(row(configured::gpc_op(lv.data(), rv.data())), expected(og::product(cga(), A, B, og::Op::Outer)).second,
            "a ^ b");
  check_row(row(configured::gpc_ip(lv.data(), rv.data())), expected(og::product(cga(), A, B, og::Op::Inner)).second,
            "a . b");
  check_row(row(configured::gpc_sub(lv.data(), rv.data())), expected(og::sum(A, B, -1.0)).second, "a - b");
}
