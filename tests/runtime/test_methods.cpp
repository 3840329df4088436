// The skinning method table (skinning_methods.hpp, generated from runtime/skinning_methods.txt) and its
// promise: every blend is written once, as a script.
// The shader and CUDA sources of the repository (everything but the generated outputs) are scanned for a
// hand-written blend: an expression that multiplies by a skin weight. The C++ of runtime/ is scanned for x86
// intrinsics and its skinning sources for weighted sums: both may stand only in the hand-written SIMD loops
// still kept beside the generated batch path, and each of those is listed, so the list cannot outlive them.
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

// Lines of `text` (numbered, as "N: line") whose code before any `//` comment matches `pattern`: comments may
// speak of weights and intrinsics.
std::vector<std::string> matching_lines(const std::string& text, const std::regex& pattern) {
  std::vector<std::string> hits;
  std::istringstream in(text);
  std::string line;
  for (int number = 1; std::getline(in, line); ++number)
    if (std::regex_search(line.substr(0, line.find("//")), pattern)) hits.push_back(std::to_string(number) + ": " + line);
  return hits;
}

// Shader lines that multiply by a skin weight: w, wk, w[k], w.x, weight(s), in_weights[...] on either side of a
// '*' (a blend is a weighted sum; passing the weights on to a generated function multiplies nothing). A
// swizzle .w (q.w * q.w) is not a weight.
std::vector<std::string> weighted_lines(const std::string& text) {
  static const std::regex weight(
      R"(((^|[^.\w])(w|wk|weight|weights|in_weights)\b\s*(\[[^\]]*\]|\.[xyzw])?\s*\*[^/*])|(\*\s*(w|wk|weight|weights|in_weights)\b))");
  return matching_lines(text, weight);
}

// C++ lines that multiply by a skin weight (w[k], wk, w0..w3 on either side of a '*'; a pointer declaration
// `const float* w` names no weight of these) or call an x86 intrinsic (_mm_, _mm256_, _mm512_).
const std::regex& cpp_weighted() {
  static const std::regex r(R"((\b(w\[\w+\]|wk|w[0-3])\s*\*[^/*])|(\*\s*(w\[\w+\]|wk|w[0-3])\b))");
  return r;
}
const std::regex& cpp_intrinsic() {
  static const std::regex r(R"(\b_mm(256|512)?_\w+\s*\()");
  return r;
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
  // The C++ scan: a weighted sum of entries and an intrinsic call are found; declarations and forwarding not.
  CHECK(matching_lines("    const v8 lo = (w[0] * load8(a) + w[1] * load8(b));\n", cpp_weighted()).size() == 1);
  CHECK(matching_lines("    lo += wk * load8(q);\n", cpp_weighted()).size() == 1);
  CHECK(matching_lines("  acc[c] = w0 * ref[c];\n", cpp_weighted()).size() == 1);
  CHECK(matching_lines("  const __m256 w0 = _mm256_broadcast_ss(w);\n", cpp_intrinsic()).size() == 1);
  CHECK(matching_lines("void f(const float* w, float* out);\n", cpp_weighted()).empty());
  CHECK(matching_lines("  K::prepare(e0, e1, w[0], w[1], w[2], w[3], out);\n", cpp_weighted()).empty());
  CHECK(matching_lines("  // _mm256_fmadd_ps(w0 * a)\n", cpp_intrinsic()).empty());
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

TEST_CASE("no x86 intrinsics or hand skinning blends anywhere in runtime/'s C++") {
  // CPU skinning runs its blends' generated batch kernels only (docs/skinning.md, "Code layout"); what is
  // hand-written there is method-blind (loops, prefetch, the rows' offsets for the generated transposer).
  namespace fs = std::filesystem;
  const fs::path root = CGA_SOURCE_DIR;
  std::size_t scanned = 0;
  std::vector<std::string> found;
  for (const fs::directory_entry& e : fs::recursive_directory_iterator(root / "runtime")) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".cpp" && ext != ".hpp" && ext != ".h")) continue;
    const std::string rel = fs::relative(e.path(), root).generic_string();
    std::ifstream in(e.path());
    std::stringstream text;
    text << in.rdbuf();
    ++scanned;
    std::vector<std::string> hits = matching_lines(text.str(), cpp_intrinsic());
    if (rel.rfind("runtime/src/skinning/", 0) == 0)
      for (std::string& hit : matching_lines(text.str(), cpp_weighted())) hits.push_back(std::move(hit));
    for (const std::string& hit : hits) found.push_back(rel + ":" + hit);
  }
  INFO("scanned " << scanned << " C++ sources under runtime/");
  CHECK(scanned >= 40);
  std::string all;
  for (const std::string& f : found) all += f + "\n";
  INFO(all);
  CHECK(found.empty());
}
