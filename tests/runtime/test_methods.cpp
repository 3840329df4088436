// The skinning method table (skinning_methods.hpp, generated from runtime/skinning_methods.txt) and its
// promise: every blend is written once, as a script.
// The shader and CUDA sources of the repository (everything but the generated outputs) are scanned for a
// hand-written blend: an expression that multiplies by a skin weight.
#include <catch2/catch.hpp>

#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cga/runtime/skinning.hpp"

using namespace cga;

namespace {

// Lines of `text` that multiply by a skin weight: w, wk, w[k], w.x, weight(s), in_weights[...] on either side
// of a '*' (a blend is a weighted sum; passing the weights on to a generated function multiplies nothing).
// A swizzle .w (q.w * q.w) is not a weight.
std::vector<std::string> weighted_lines(const std::string& text) {
  static const std::regex weight(
      R"(((^|[^.\w])(w|wk|weight|weights|in_weights)\b\s*(\[[^\]]*\]|\.[xyzw])?\s*\*[^/*])|(\*\s*(w|wk|weight|weights|in_weights)\b))");
  std::vector<std::string> hits;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const std::string code = line.substr(0, line.find("//"));  // comments may speak of weights
    if (std::regex_search(code, weight)) hits.push_back(std::to_string(number) + ": " + line);
  }
  return hits;
}

}  // namespace

TEST_CASE("the method table names every method once, in enum order, with a blend and a prepared entry") {
  std::set<std::string_view> names;
  for (std::size_t i = 0; i < kSkinningMethods.size(); ++i) {
    const SkinningMethodInfo& m = kSkinningMethods[i];
    INFO(m.name);
    CHECK(static_cast<std::size_t>(m.method) == i);
    CHECK(names.insert(m.name).second);
    CHECK(parse_skinning_method(m.name) == m.method);
    CHECK(!m.blend_script.empty());
    CHECK(prepared_entry_floats(m.method) == 4 * m.entry_vec4s);
    CHECK((m.entry_vec4s >= 1 && m.entry_vec4s <= 4));
  }
  CHECK(kAllSkinningMethods.size() == kSkinningMethodCount);
  CHECK(parse_skinning_method("cga_log") == SkinningMethod::cga_log);
}

TEST_CASE("the blend scan finds a hand-written blend") {
  // The GLSL dqs blend as it was once written by hand, and the CUDA and WGSL spellings of a weighted sum.
  CHECK(weighted_lines("  vec4 r = w[0] * r0;\n").size() == 1);
  CHECK(weighted_lines("    float wk = dot(r0, rk) < 0.0 ? -w[k] : w[k];\n    r += wk * rk;\n").size() == 1);
  CHECK(weighted_lines("  acc = acc + m * w.y;\n").size() == 1);
  CHECK(weighted_lines("    s1 += weights[k] * c1;\n").size() == 1);
  // Passing the weights on, and comments, are not blends.
  CHECK(weighted_lines("  skin_motors(a, b, w[0], w[1], w[2], w[3], p.x);\n").empty());
  CHECK(weighted_lines("  // the blend: w[0] * M0 + ...\n").empty());
  CHECK(weighted_lines("  gl_Position = u_view_projection * vec4(p, 1.0);\n").empty());
  CHECK(weighted_lines("  float s = q.w * q.w;\n").empty());
}

TEST_CASE("no GLSL, WGSL or CUDA source outside the generated outputs blends by hand") {
  namespace fs = std::filesystem;
  const fs::path root = CGA_SOURCE_DIR;
  const std::set<std::string> shader_ext = {".glsl", ".vert", ".frag", ".comp", ".wgsl", ".cu", ".cuh"};
  std::size_t scanned = 0;
  std::vector<std::string> found;
  for (const char* dir : {"runtime", "web", "examples"}) {
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / dir)) {
      if (!e.is_regular_file() || !shader_ext.count(e.path().extension().string())) continue;
      std::ifstream in(e.path());
      std::stringstream text;
      text << in.rdbuf();
      ++scanned;
      for (const std::string& hit : weighted_lines(text.str()))
        found.push_back(fs::relative(e.path(), root).string() + ":" + hit);
    }
  }
  INFO("scanned " << scanned << " shader and CUDA sources");
  CHECK(scanned >= 8);  // the GL stage mains, the page's shaders, the CUDA kernels
  std::string all;
  for (const std::string& f : found) all += f + "\n";
  INFO(all);
  CHECK(found.empty());
}
