// Staging tests (opt/stage.hpp): the op-count targets docs/generator.md and the README state,
// prepare then body equal to the unstaged kernel on 1000 random inputs for every bundled script, located
// errors for bad uniforms, and the CLI's --stats / --eval / --diff / every target for a staged kernel.
// (The compiled C++ of the staged kernels against the oracle: tests/kernels/test_kernels.cpp.)
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "a1_hand.hpp"
#include "cli_run.hpp"
#include "emit/emit.hpp"
#include "expand/expand.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"
#include "opt/report.hpp"
#include "opt/stage.hpp"

using namespace cgagen;
using opt::Level;

namespace {

const std::filesystem::path kRuntime = std::filesystem::path(CGA_SOURCE_DIR) / "runtime" / "scripts";
const std::filesystem::path kTests = std::filesystem::path(CGA_TEST_SCRIPTS);
// The hand-derived splits that staging replaced in the runtime, kept as tests (motor_to_matrix.clu).
const std::filesystem::path kHandScripts = std::filesystem::path(CGA_SOURCE_DIR) / "tests" / "kernels" / "scripts";

// The paper's A.1 script: every key parameter uniform, the vertex X, Y, Z per element.
const std::vector<std::string> kPaperUniforms = {"transX", "transY", "transZ", "axis1X", "axis1Y", "axis1Z",
                                                 "angle1", "d1",     "trans2X", "trans2Y", "trans2Z", "axis2X",
                                                 "axis2Y", "axis2Z", "angle2", "d2",     "alpha"};

Kernel load(const std::filesystem::path& path) {
  auto file = front::SourceFile::load(path.string());
  return expand(front::parse(file), path.stem().string());
}

opt::StagedProgram staged(const std::filesystem::path& path, const std::vector<std::string>& uniforms,
                          Level level = Level::O2) {
  Kernel k = load(path);
  return opt::stage(opt::optimize(k, level), opt::uniform_inputs(k, uniforms));
}

std::string uniform_arg(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

}  // namespace

TEST_CASE("staged transform_point (M uniform): 9 mul + 9 add per point, prepare no dearer than the hand "
          "motor_to_matrix", "[stage]") {
  const auto s = staged(kRuntime / "transform_point.clu", {"M"});
  const auto body = opt::program_stats(s.body).total, prepare = opt::program_stats(s.prepare).total;
  INFO("per element " << opt::format_counts(body) << "; prepare " << opt::format_counts(prepare));
  CHECK(body.mul <= 9);
  CHECK(body.add <= 9);
  CHECK(body.div == 0);
  CHECK(body.call == 0);
  // The hand split this replaces: runtime/scripts/motor_to_matrix.clu at -O2 (62 mul + 63 add + 1 div).
  const auto hand = opt::program_stats(opt::optimize(load(kHandScripts / "motor_to_matrix.clu"), Level::O2)).total;
  INFO("hand motor_to_matrix " << opt::format_counts(hand));
  CHECK(prepare.mul <= hand.mul);
  CHECK(prepare.add <= hand.add);
  CHECK(prepare.div <= hand.div);
  CHECK(prepare.call <= hand.call);
  // The figures docs/generator.md and the README give (an improvement lowers them).
  CHECK(prepare.mul <= 46);
  CHECK(prepare.add <= 63);
  CHECK(prepare.div == 0);
  // The 3x4 matrix and the weight: 12 + 1 prepared values.
  CHECK(s.prepare.outputs.at(0).slots.size() == 13);
}

TEST_CASE("staged transform_point_split (G, H, U uniform): skinning's matrix, against the hand "
          "motor_split_to_matrix", "[stage]") {
  // The runtime script's own pragma stages it (no --uniform): point and normal per element.
  const Kernel k = load(kRuntime / "transform_point_split.clu");
  const auto s = opt::stage(opt::optimize(k, Level::O2), opt::uniform_inputs(k, {}));
  CHECK(s.uniforms == std::vector<std::string>{"G", "H", "U"});
  const auto body = opt::program_stats(s.body).total, prepare = opt::program_stats(s.prepare).total;
  INFO("per element " << opt::format_counts(body) << "; prepare " << opt::format_counts(prepare));
  CHECK(body.mul <= 18);  // 9 for the point, 9 for the normal
  CHECK(body.add <= 15);  // 9 + 6 (no translation for the normal)
  CHECK(body.div == 0);
  CHECK(s.prepare.outputs.at(0).slots.size() == 12);  // the normalized 3x4: point and normal share it
  const auto hand =
      opt::program_stats(opt::optimize(load(kHandScripts / "motor_split_to_matrix.clu"), Level::O2)).total;
  INFO("hand motor_split_to_matrix " << opt::format_counts(hand));
  CHECK(prepare.add <= hand.add);
  CHECK(prepare.div <= hand.div);
  CHECK(prepare.call <= hand.call);
  // No dearer than the hand split (39 mul + 39 add + 1 div). The prepare inherited the unstaged program's
  // sharing (1/w times H as well as G: 43 mul) until stage.cpp also optimizes the prepared values afresh.
  CHECK(prepare.mul <= hand.mul);
}

TEST_CASE("staged paper A.1 (key parameters uniform): 9 mul + 9 add per vertex", "[stage]") {
  const auto s = staged(kTests / "paper_a1.clu", kPaperUniforms);
  const auto body = opt::program_stats(s.body).total, prepare = opt::program_stats(s.prepare).total;
  INFO("per element " << opt::format_counts(body) << "; prepare " << opt::format_counts(prepare));
  CHECK(body.mul <= 9);
  CHECK(body.add <= 9);
  CHECK(body.div == 0);
  CHECK(body.call == 0);
  // The figures docs/generator.md and the README give; unstaged -O2 is 178 mul + 142 add + 2 div per vertex.
  CHECK(prepare.mul <= 135);
  CHECK(prepare.add <= 125);
  CHECK(prepare.div <= 2);
  CHECK(s.prepare.outputs.at(0).slots.size() <= 13);
}

namespace {
// A scalar that counts the operations done on it (unary minus is free, as in the generator's counts).
struct CountedOps {
  long add = 0, mul = 0, div = 0;
};
CountedOps g_ops;
struct Counted {
  double v;
  Counted(double x = 0) : v(x) {}
};
Counted operator+(Counted a, Counted b) { return ++g_ops.add, Counted(a.v + b.v); }
Counted operator-(Counted a, Counted b) { return ++g_ops.add, Counted(a.v - b.v); }
Counted operator*(Counted a, Counted b) { return ++g_ops.mul, Counted(a.v * b.v); }
Counted operator/(Counted a, Counted b) { return ++g_ops.div, Counted(a.v / b.v); }
Counted operator-(Counted a) { return Counted(-a.v); }
}  // namespace

TEST_CASE("staged paper A.1: the prepare against the best hand-written per-bone code (a measurement)", "[stage]") {
  // tests/gen/a1_hand.hpp computes the same 13 prepared values by hand; its operations are counted here.
  const auto s = staged(kTests / "paper_a1.clu", kPaperUniforms);
  const auto prepare = opt::program_stats(s.prepare).total;
  g_ops = {};
  Counted cin[17], cout[13];
  cga_test::a1_hand(cin, cout);
  const CountedOps hand = g_ops;
  const double ratio_mul = double(prepare.mul) / hand.mul, ratio_add = double(prepare.add) / hand.add;
  INFO("staged prepare " << opt::format_counts(prepare) << "; hand " << hand.add << " add, " << hand.mul << " mul, "
                         << hand.div << " div; ratio mul " << ratio_mul << ", add " << ratio_add);
  // The figures docs/generator.md gives: hand 96 mul + 81 add + 2 div, staged 135 + 125 + 2 (1.41x, 1.54x:
  // a 1.2x target is not met). A change to either side shows here.
  CHECK(hand.mul == 96);
  CHECK(hand.add == 81);
  CHECK(hand.div == 2);
  CHECK(prepare.div <= hand.div);
  CHECK(ratio_mul <= 1.41);
  CHECK(ratio_add <= 1.55);
  // The hand code computes the staged prepare's values (same slot order) on 1000 random key poses.
  REQUIRE(s.prepare.outputs.at(0).slots.size() == 13);
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 1000; ++trial) {
    double in[17], out[13];
    opt::InputValues v;
    for (int i = 0; i < 17; ++i) {
      in[i] = u(rng);
      if (i == 7 || i == 15) in[i] = 0.5 + std::abs(in[i]);  // the scale factors d1, d2 > 0
      v[kPaperUniforms[i]] = {in[i]};
    }
    cga_test::a1_hand(in, out);
    const auto want = opt::evaluate(s.prepare, v);
    REQUIRE(want.size() == 13);
    for (int i = 0; i < 13; ++i) {
      INFO("trial " << trial << ", prepared value " << i);
      REQUIRE(std::abs(out[i] - want[i].value) <= 1e-12 * std::max(1.0, std::abs(want[i].value)));
    }
  }
}

TEST_CASE("a uniform 1/w folds into the prepared matrix", "[stage]") {
  // The Euclidean point of M X ~M over the weight (which depends on M only): per element only
  // x*a + y*b + z*c + d for each coordinate, the division and the translation column prepared.
  const std::string path = cga_test::write_temp(
      "stage_normalized.clu",
      "//#pragma input M 1 e1^e2 e1^e3 e1^einf e2^e3 e2^einf e3^einf einf^e0 e1^e2^e3^einf e1^e2^einf^e0 "
      "e1^e3^einf^e0 e2^e3^einf^e0\n//#pragma output Q e1 e2 e3\n#pragma uniform M\nP0 = M*e0*~M;\n"
      "w = (einf^P0).(einf^e0);\n?Q = (M*VecN3(x,y,z)*~M)/w;\n");
  const auto s = staged(path, {});
  const auto body = opt::program_stats(s.body).total, prepare = opt::program_stats(s.prepare).total;
  INFO("per element " << opt::format_counts(body) << "; prepare " << opt::format_counts(prepare));
  CHECK(body.mul <= 9);
  CHECK(body.add <= 9);
  CHECK(body.div == 0);
  CHECK(prepare.div == 1);
  CHECK(prepare.mul <= 59);  // docs/generator.md and the README give 59 mul + 63 add + 1 div
  CHECK(prepare.add <= 63);
  CHECK(s.prepare.outputs.at(0).slots.size() == 12);  // the 3x4 matrix
  // It replaces the hand motor_to_matrix (62 mul + 63 add + 1 div at -O2) at no more cost.
  const auto hand = opt::program_stats(opt::optimize(load(kHandScripts / "motor_to_matrix.clu"), Level::O2)).total;
  CHECK(prepare.mul <= hand.mul);
  CHECK(prepare.add <= hand.add);
}

TEST_CASE("prepare then body equals the unstaged kernel on 1000 random inputs, every bundled script", "[stage]") {
  std::vector<std::filesystem::path> scripts;
  for (const auto& dir : {kRuntime, kTests})
    for (const auto& e : std::filesystem::directory_iterator(dir))
      if (e.path().extension() == ".clu") scripts.push_back(e.path());
  std::sort(scripts.begin(), scripts.end());
  REQUIRE(scripts.size() >= 10);
  std::mt19937 rng(19);
  std::uniform_real_distribution<double> d(0.2, 1.5);
  int checked = 0;
  for (const auto& path : scripts) {
    Kernel k = load(path);
    if (k.inputs.size() < 2) continue;
    // Two splits: the first input uniform, and every input but the last uniform.
    std::vector<std::vector<std::string>> choices = {{k.inputs.front().name}, {}};
    for (size_t i = 0; i + 1 < k.inputs.size(); ++i) choices[1].push_back(k.inputs[i].name);
    if (path.stem() == "paper_a1") choices.push_back(kPaperUniforms);
    const opt::Program plain = opt::optimize(k, Level::O2);
    for (const auto& uniforms : choices) {
      INFO(path.filename().string() << " --uniform " << uniform_arg(uniforms));
      opt::StagedProgram s;
      try {
        s = opt::stage(plain, opt::uniform_inputs(k, uniforms));
      } catch (const std::invalid_argument& e) {
        // No output depends on these uniforms alone (nothing to prepare): said, not staged wrongly.
        CHECK(std::string(e.what()).find("nothing to prepare") != std::string::npos);
        continue;
      }
      ++checked;
      double worst = 0;
      for (int trial = 0; trial < 1000; ++trial) {
        opt::InputValues v;
        for (const auto& in : k.inputs)
          for (size_t i = 0; i < in.symbols.size(); ++i) v[in.name].push_back(d(rng));
        const auto check = opt::compare_staged(opt::evaluate_staged(s, v), opt::evaluate(plain, v));
        worst = std::max(worst, check.max_rel_error);
        if (!check.ok) {
          INFO("trial " << trial << ": relative error " << check.max_rel_error);
          REQUIRE(check.ok);
        }
      }
      INFO("largest relative error " << worst);
      CHECK(worst <= 1e-9);
    }
  }
  CHECK(checked >= 10);
}

TEST_CASE("staging at every level computes the same values", "[stage]") {
  for (Level level : {Level::O0, Level::O1, Level::O2}) {
    Kernel k = load(kRuntime / "transform_point.clu");
    const opt::Program plain = opt::optimize(k, level);
    const auto s = opt::stage(plain, {"M"});
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> d(-2, 2);
    for (int trial = 0; trial < 100; ++trial) {
      opt::InputValues v;
      for (const auto& in : k.inputs)
        for (size_t i = 0; i < in.symbols.size(); ++i) v[in.name].push_back(d(rng));
      REQUIRE(opt::compare_staged(opt::evaluate_staged(s, v), opt::evaluate(plain, v)).ok);
    }
  }
}

TEST_CASE("bad uniforms are located errors", "[stage][diagnostics]") {
  auto r = cga_test::run("--uniform Q " + cga_test::script("transform_point.clu"));
  CHECK(r.code == 2);
  CHECK(r.out.find("--uniform names 'Q', which is not an input of the script (inputs: M, x, y, z)") !=
        std::string::npos);
  r = cga_test::run("--uniform P " + cga_test::script("transform_point.clu"));
  CHECK(r.code == 2);
  CHECK(r.out.find("--uniform names 'P', which is an output; only inputs can be uniform") != std::string::npos);
  const std::string bad = cga_test::write_temp("stage_bad.clu", "#pragma uniform M foo\n?P = M*VecN3(x,y,z)*~M;\n");
  r = cga_test::run(bad);
  CHECK(r.code == 1);
  CHECK(r.out.find("stage_bad.clu:1:19: error: '#pragma uniform' names 'foo', which is not an input of the script") !=
        std::string::npos);
  const std::string out = cga_test::write_temp("stage_out.clu", "#pragma uniform P\n?P = M*VecN3(x,y,z)*~M;\n");
  r = cga_test::run(out);
  CHECK(r.code == 1);
  CHECK(r.out.find("stage_out.clu:1:17: error: '#pragma uniform' names 'P', which is an output") != std::string::npos);
  const std::string empty = cga_test::write_temp("stage_empty.clu", "#pragma uniform\n?P = x;\n");
  r = cga_test::run(empty);
  CHECK(r.code == 1);
  CHECK(r.out.find("stage_empty.clu:1:1: error: '#pragma uniform' needs at least one input name") != std::string::npos);
}

TEST_CASE("the CLI prints the staged form: --stats, --eval, --diff", "[stage][cli]") {
  const std::string tp = cga_test::script("transform_point.clu");
  auto r = cga_test::run("--uniform M --stats " + tp);
  REQUIRE(r.code == 0);
  CHECK(r.out.find("\nprepare: ") != std::string::npos);
  CHECK(r.out.find("\nper element: 9 add, 9 mul, 0 div, 0 call\n") != std::string::npos);
  const std::string m = "M=0.9,0.1,0.2,0.3,0.4,0.5,0.6,0.05,0.01,0.02,0.03,0.04 x=1 y=2 z=3";
  r = cga_test::run("--uniform M --eval " + tp + " " + m);
  CHECK(r.code == 0);
  auto plain = cga_test::run("--eval " + tp + " " + m);
  CHECK(plain.code == 0);
  CHECK(r.out.find("P e0 ") != std::string::npos);
  r = cga_test::run("--uniform M --diff -O2 -O2 " + tp);
  CHECK(r.code == 0);
  CHECK(r.out.find("+++ transform_point -O2 staged") != std::string::npos);
  CHECK(r.out.find("+inline void transform_point_prepare(const float M[12], float prepared[13]) {") !=
        std::string::npos);
  CHECK(r.out.find("per element: 9 add, 9 mul") != std::string::npos);
  // The pragma gives the same code as the option.
  const std::string pragma = cga_test::write_temp(
      "transform_point.clu", "#pragma uniform M\n" + std::string(std::istreambuf_iterator<char>(
                                                          std::ifstream(tp).rdbuf()), {}));
  CHECK(cga_test::run(pragma).out == cga_test::run("--uniform M " + tp).out);
}

TEST_CASE("every target emits both functions of a staged kernel", "[stage][targets]") {
  const std::string tp = cga_test::script("transform_point.clu");
  for (const auto& sx : emit::targets()) {
    INFO(sx.name);
    auto r = cga_test::run("--target " + sx.name + " --uniform M " + tp);
    REQUIRE(r.code == 0);
    // Both functions (LaTeX escapes the underscore; dot draws one graph of both, no function names).
    if (sx.kind == emit::Syntax::Kind::Code)
      CHECK((r.out.find("transform_point_prepare") != std::string::npos ||
             r.out.find("transform\\_point\\_prepare") != std::string::npos));
    CHECK(r.out.find("prepared") != std::string::npos);
  }
}

TEST_CASE("a kernel without uniforms is emitted exactly as before staging existed", "[stage]") {
  // generated/ (checked by generated_up_to_date) holds the unstaged kernels; here: no uniform, no prepare.
  auto r = cga_test::run(cga_test::script("transform_point.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.find("prepare") == std::string::npos);
}

TEST_CASE("GLSL: the prepared values as an array, a mat3x4, a uniform block or a storage buffer (glslang)",
          "[stage][targets]") {
  // transform_point_split: 12 prepared values (G H U uniform by its pragma). Each packing is emitted, wrapped
  // in a #version 450 vertex shader that calls the prepare and the body, and compiled by glslangValidator.
  const std::string tps = cga_test::script("transform_point_split.clu");
  const std::string prepare_call =
      "  float g[4] = float[4](1.0, 0.1, 0.2, 0.3), h[4] = float[4](0.9, 0.1, 0.2, 0.3), u[4] = float[4](0.1, 0.2, "
      "0.3, 0.4);\n";
  struct Case {
    std::string kind, expect, call;
  };
  const Case cases[] = {
      {"array", "void transform_point_split(in float prepared[12], float x,",
       "  float prep[12];\n  transform_point_split_prepare(g, h, u, prep);\n"
       "  transform_point_split(prep, pos.x, pos.y, pos.z, 0.0, 0.0, 1.0, p, n);\n"},
      {"mat3x4", "void transform_point_split(in mat3x4 prepared, float x,",
       "  mat3x4 prep;\n  transform_point_split_prepare(g, h, u, prep);\n"
       "  transform_point_split(prep, pos.x, pos.y, pos.z, 0.0, 0.0, 1.0, p, n);\n"},
      {"block",
       "layout(std140) uniform transform_point_split_prepared_block {\n  vec4 transform_point_split_prepared[3];",
       "  float prep[12];\n  transform_point_split_prepare(g, h, u, prep);  // what the host uploads\n"
       "  transform_point_split(pos.x, pos.y, pos.z, 0.0, 0.0, 1.0, p, n);\n"},
      {"buffer",
       "layout(std430) readonly buffer transform_point_split_prepared_buffer {\n  float "
       "transform_point_split_prepared[];",
       "  float prep[12];\n  transform_point_split_prepare(g, h, u, prep);\n"
       "  transform_point_split(gl_InstanceID, pos.x, pos.y, pos.z, 0.0, 0.0, 1.0, p, n);\n"},
  };
  for (const Case& c : cases) {
    INFO("--pack prepared=" << c.kind);
    auto r = cga_test::run("--target glsl " + (c.kind == "array" ? "" : "--pack prepared=" + c.kind + " ") + tps);
    REQUIRE(r.code == 0);
    CHECK(r.out.find(c.expect) != std::string::npos);
    if (c.kind == "block") CHECK(r.out.find("transform_point_split_prepared[2][3]") != std::string::npos);
    if (c.kind == "buffer") {
      CHECK(r.out.find("void transform_point_split(int prepared_index, float x,") != std::string::npos);
      CHECK(r.out.find("transform_point_split_prepared[prepared_index * 12 + 11]") != std::string::npos);
    }
    // The prepare function still writes its values (an array, or the mat3x4).
    CHECK(r.out.find(c.kind == "mat3x4" ? "out mat3x4 prepared)" : "out float prepared[12])") != std::string::npos);
    const std::string path = std::string(CGA_BINARY_DIR) + "/stage_pack_" + c.kind + ".vert";
    std::ofstream(path) << "#version 450\n" << r.out
                        << "\nlayout(location = 0) in vec3 pos;\nlayout(location = 0) out vec3 o;\nvoid main() {\n"
                        << prepare_call << "  float p[3], n[3];\n" << c.call
                        << "  o = vec3(p[0], p[1], p[2]) + vec3(n[0], n[1], n[2]);\n  gl_Position = vec4(o, 1.0);\n}\n";
    const int status = std::system((std::string(GLSLANG_VALIDATOR) + " " + path + " > " + path + ".log 2>&1").c_str());
    INFO(std::ifstream(path + ".log").rdbuf());
    CHECK(status == 0);
  }
  // Block and buffer apply to the prepared values only; mat3x4 holds at most 12 (transform_point has 13).
  auto r = cga_test::run("--target glsl --pack G=block " + tps);
  CHECK(r.code == 1);
  CHECK(r.out.find("--pack G=block: block and buffer apply to a staged kernel's prepared values only") !=
        std::string::npos);
  r = cga_test::run("--target glsl --uniform M --pack prepared=mat3x4 " + cga_test::script("transform_point.clu"));
  CHECK(r.code == 1);
  CHECK(r.out.find("cannot pack 'prepared' (13 blades) as mat3x4") != std::string::npos);
  r = cga_test::run("--target glsl --uniform M --pack prepared=block " + cga_test::script("transform_point.clu"));
  CHECK(r.code == 0);
  CHECK(r.out.find("vec4 transform_point_prepared[4];") != std::string::npos);
}
