// Algorithms, not single products: the expander's cost model (gen/expand/cost.hpp) and the bounded work per
// statement. A chain of small statements (the n-joint arm of cga/testing/joint_chain.hpp) must cost ops
// linear in its length at every level; a product of long sums is compiled through bound temporaries (and
// computes the same values at every level); the 5-joint arm of bench/ik_arm keeps its exact blade support.
#include <catch2/catch.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>
#include <string>

#include "cga/testing/joint_chain.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"

using namespace cgagen;
using opt::Level;

namespace {

Kernel kernel_of(const std::string& text, const std::string& name) {
  front::SourceFile file(name + ".clu", text);
  return expand(front::parse(file), name);
}

long ops(const Kernel& k, Level level) { return opt::program_stats(opt::optimize(k, level)).total.total(); }

std::map<std::string, double> values(const opt::Program& p, const opt::InputValues& in) {
  std::map<std::string, double> m;
  for (const auto& l : opt::evaluate(p, in)) m[l.output + " " + l.blade_name] = l.value;
  return m;
}

std::string read(const std::string& path) {
  std::ifstream in(path);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

}  // namespace

TEST_CASE("an n-joint chain costs ops linear in n at every level", "[chains]") {
  for (Level level : {Level::O0, Level::O1, Level::O2}) {
    std::map<int, long> counts;
    for (int n : {5, 10, 20, 40}) counts[n] = ops(kernel_of(cga::testing::joint_chain_script(n), "chain"), level);
    INFO("level " << static_cast<int>(level) << ": ops " << counts[5] << ", " << counts[10] << ", " << counts[20]
                  << ", " << counts[40]);
    // Doubling the joints about doubles the code (each joint adds one statement of bounded size); the first
    // joints are cheaper (fewer blades before the chain turns out of the plane), hence the lower bound.
    for (int n : {5, 10, 20}) {
      const double ratio = static_cast<double>(counts[2 * n]) / static_cast<double>(counts[n]);
      CHECK(ratio > 1.6);
      CHECK(ratio < 2.4);
    }
  }
}

TEST_CASE("a product of long sums is bound to temporaries and keeps its values at every level", "[chains]") {
  // Five sums of ten inputs: expanded in one piece, the product would have 100000 terms per coefficient.
  std::string text = "?v = ";
  for (char f : std::string("abcdf")) {
    text += "(";
    for (int i = 0; i < 10; ++i) text += (i ? "+" : "") + std::string(1, f) + std::to_string(i);
    text += ")*";
  }
  text += "e1;\n";
  const Kernel k = kernel_of(text, "sums");
  // The parts the cost model bound are kernel values of their own.
  int parts = 0;
  for (const auto& v : k.values) parts += v.name.rfind("v_part", 0) == 0;
  CHECK(parts >= 1);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  opt::InputValues in;
  std::map<char, double> sums;
  for (const auto& input : k.inputs) {
    const double x = d(rng);
    in[input.name] = {x};
    sums[input.name[0]] += x;
  }
  const double expected = sums['a'] * sums['b'] * sums['c'] * sums['d'] * sums['f'];
  for (Level level : {Level::O0, Level::O1, Level::O2}) {
    const auto got = values(opt::optimize(k, level), in);
    REQUIRE(got.size() == 1);
    CHECK(got.at("v e1") == Approx(expected).epsilon(1e-12));
  }
}

TEST_CASE("the 5-joint arm: exact blade support, and few ops at -O2", "[chains]") {
  const Kernel k = kernel_of(read(std::string(CGA_SOURCE_DIR) + "/bench/ik_arm/arm5.clu"), "arm5");
  std::map<std::string, size_t> blades;
  for (const auto& o : k.outputs) blades[o.name] = o.blades.size();
  // R1 turns about z through the origin (scalar + e1^e2); R2, R3 about lines parallel to y (scalar + a line
  // of 5 blades: no e1^e2); T2 a translator; the gripper a point (5 blades). Nothing else survives the zero
  // tests: a blade left in would be a coefficient that is identically zero.
  CHECK(blades["R1"] == 2);
  CHECK(blades["R2"] == 6);
  CHECK(blades["R3"] == 6);
  CHECK(blades["T2"] == 4);
  CHECK(blades["Jg_f"] == 5);
  const long o2 = ops(k, Level::O2), o0 = ops(k, Level::O0);
  INFO("-O0 " << o0 << " ops, -O2 " << o2);
  CHECK(o2 < 900);  // 798 when written (330 add, 468 mul); Gaalop-style full expansion does not finish
  CHECK(o2 * 2 < o0);
}
