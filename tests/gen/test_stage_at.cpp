// Staging at named values (--stage-at, opt/stage_at.cpp): prepare then body equal to the unstaged kernel on
// 1000 random inputs at every level, for every skinning blend at the cut the runtime uses and for cuts through
// the middle of other scripts; the split's shape (the prepare takes every input the body does not read, so a
// kernel and its --outputs variant share one prepare); and clear errors for bad cuts.
#include <catch2/catch.hpp>

#include <algorithm>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "cli_run.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "opt/stage.hpp"

using namespace cgagen;
using opt::Level;

namespace {

const std::filesystem::path kScripts = std::filesystem::path(CGA_SOURCE_DIR) / "runtime" / "scripts";

Kernel load(const std::filesystem::path& path) {
  auto file = front::SourceFile::load(path.string());
  return expand(front::parse(file), path.stem().string());
}

std::vector<std::string> names_of(const std::vector<KernelInput>& inputs) {
  std::vector<std::string> out;
  for (const auto& i : inputs) out.push_back(i.name);
  return out;
}

// The largest relative difference of prepare-then-body against the unstaged kernel over `trials` random inputs.
double worst_error(const Kernel& k, const opt::StagedProgram& s, Level level, int trials, unsigned seed) {
  const opt::Program plain = opt::optimize(k, level);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> d(-1.5, 1.5);
  double worst = 0;
  for (int t = 0; t < trials; ++t) {
    opt::InputValues v;
    for (const auto& in : k.inputs)
      for (size_t i = 0; i < in.symbols.size(); ++i) v[in.name].push_back(d(rng));
    const auto check = opt::compare_staged(opt::evaluate_staged(s, v), opt::evaluate(plain, v));
    if (!check.ok) return check.max_rel_error;
    worst = std::max(worst, check.max_rel_error);
  }
  return worst;
}

struct Cut {
  const char* script;
  std::vector<std::string> at;
  size_t prepared;  // the named values' coefficients
};

// The skinning blends at their runtime cuts (generated/CMakeLists.txt), and cuts inside other scripts.
const Cut kCuts[] = {
    {"skin/skin_matrices.clu", {"A", "B", "C"}, 12},
    {"skin/skin_dual_quats.clu", {"B"}, 8},
    {"skin/skin_motors.clu", {"G", "H", "U"}, 12},
    {"skin/skin_motor_logs.clu", {"Lr", "Lt"}, 7},
    {"skin/skin_motor_logs.clu", {"Omega", "lambda", "v"}, 7},
};

}  // namespace

TEST_CASE("prepare then body equals the unstaged kernel, every level", "[stage_at]") {
  for (const Cut& c : kCuts) {
    const Kernel k = load(kScripts / c.script);
    for (Level level : {Level::O0, Level::O1, Level::O2}) {
      INFO(c.script << " at -O" << static_cast<int>(level));
      const opt::StagedProgram s = opt::stage_at(k, c.at, level);
      CHECK(s.at == c.at);
      CHECK(s.prepare.outputs.size() == 1);
      CHECK(s.prepare.outputs.at(0).slots.size() == c.prepared);
      CHECK(s.body.inputs.front().symbols.size() == c.prepared);
      const double worst = worst_error(k, s, level, level == Level::O2 ? 1000 : 200, 23);
      INFO("largest relative error " << worst);
      CHECK(worst <= 1e-9);
    }
  }
}

TEST_CASE("the prepare takes every input the body does not read, the body the rest", "[stage_at]") {
  const Kernel k = load(kScripts / "skin" / "skin_motor_logs.clu");
  const opt::StagedProgram s = opt::stage_at(k, {"Lr", "Lt"}, Level::O2);
  // Kr0 and Kt0 are read by neither side (influence 0 is the reference): the prepare still takes them, so
  // every blend's prepare takes its four entries and four weights in the script's order.
  const std::vector<std::string> pre = names_of(s.prepare.inputs);
  CHECK(pre == std::vector<std::string>{"Lr0", "Lt0", "Kr0", "Kt0", "Lr1", "Lt1", "Kr1", "Kt1", "Lr2", "Lt2", "Kr2",
                                        "Kt2", "Lr3", "Lt3", "Kr3", "Kt3", "w0", "w1", "w2", "w3"});
  CHECK(names_of(s.body.inputs) == std::vector<std::string>{"prepared", "x", "y", "z", "nx", "ny", "nz"});
  CHECK(s.uniforms == pre);
  // The labels name each prepared value by its value and blade.
  const auto& labels = s.body.labels.at("prepared");
  REQUIRE(labels.size() == 7);
  CHECK(labels.front().rfind("Lr.", 0) == 0);
  CHECK(labels.back().rfind("Lt.", 0) == 0);
  // Kept to the position, the body reads x, y, z only; the prepare is the same function.
  Kernel kp = k;
  std::erase_if(kp.outputs, [](const KernelOutput& o) { return o.name != "p"; });
  const opt::StagedProgram sp = opt::stage_at(kp, {"Lr", "Lt"}, Level::O2);
  CHECK(names_of(sp.body.inputs) == std::vector<std::string>{"prepared", "x", "y", "z"});
  CHECK(opt::program_stats(sp.prepare).total.weighted() == opt::program_stats(s.prepare).total.weighted());
}

TEST_CASE("the CLI: --stage-at in --stats, --eval and the targets, and clear errors for bad cuts", "[stage_at][cli]") {
  const std::string sm = (kScripts / "skin" / "skin_matrices.clu").string();
  auto r = cga_test::run("--stage-at A,B,C --stats " + sm);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("staged at A, B, C (prepare reads: A0, B0, C0, A1,") != std::string::npos);
  CHECK(r.out.find("\nprepare: 36 add, 48 mul, 0 div, 0 call\n") != std::string::npos);
  CHECK(r.out.find("\nprepared values: 12\n") != std::string::npos);
  r = cga_test::run("--stage-at A,B,C --target simd " + sm);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("inline void skin_matrices_prepare(const float A0[4],") != std::string::npos);
  CHECK(r.out.find("skin_matrices_batch(std::size_t n, const In& prepared, const In& x,") != std::string::npos);
  // --eval checks prepare then body against the unstaged kernel itself, and prints the same values.
  std::string values;
  int i = 0;
  for (const char* mv : {"A0", "B0", "C0", "A1", "B1", "C1", "A2", "B2", "C2", "A3", "B3", "C3"}) {
    values += std::string(" ") + mv + "=";
    for (int b = 0; b < 4; ++b) values += (b ? "," : "") + std::to_string(0.1 * (++i % 7) - 0.3);
  }
  values += " w0=0.4 w1=0.3 w2=0.2 w3=0.1 x=1 y=2 z=3 nx=0 ny=1 nz=0";
  r = cga_test::run("--stage-at A,B,C --eval " + sm + values);
  INFO(r.out);
  CHECK(r.code == 0);
  CHECK(std::count(r.out.begin(), r.out.end(), '\n') == 6);
  r = cga_test::run("--stage-at Q " + sm);
  CHECK(r.code == 2);
  CHECK(r.out.find("--stage-at names 'Q', which the script does not assign (it assigns: A, B, C, P, N, p, n)") !=
        std::string::npos);
  r = cga_test::run("--stage-at p " + sm);
  CHECK(r.code == 2);
  CHECK(r.out.find("--stage-at names 'p', which is an output") != std::string::npos);
  // A reads the weights, which B and C after the cut read too: a cut must leave each input on one side.
  r = cga_test::run("--stage-at A " + sm);
  CHECK(r.code == 2);
  CHECK(r.out.find("--stage-at A: input 'w0' is read both before the cut (by the named values) and after it") !=
        std::string::npos);
  r = cga_test::run("--stage-at A --uniform w0 " + sm);
  CHECK(r.code == 2);
  CHECK(r.out.find("--stage-at excludes --uniform") != std::string::npos);
}
