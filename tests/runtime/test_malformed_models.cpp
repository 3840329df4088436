// Malformed model files must never take the process down: the loader imports in a child process (loader.hpp),
// so a crash inside Assimp's parsers becomes a LoadError naming the file and the signal. Also: seeded
// mutants of the four formats the tests use (each gives a usable character or a LoadError), and non-finite
// positions, normals and weights (each named in a warning with mesh and vertex, and repaired or dropped so
// that the character holds only finite numbers). Files are written to a temporary folder at run time.
#include <catch2/catch.hpp>

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <random>
#include <string>
#include <vector>

#include "cga/io/loader.hpp"
#include "model_files.hpp"
#include "isolated.hpp"

using namespace cga;
namespace fs = std::filesystem;

namespace {

using cga_test::model;
using cga_test::read_bytes;
using cga_test::temp_file;

bool finite(float x) { return std::isfinite(x); }
bool finite_transform(const Transform& x) {
  return finite(x.translation.x) && finite(x.translation.y) && finite(x.translation.z) && finite(x.rotation.w) &&
         finite(x.rotation.x) && finite(x.rotation.y) && finite(x.rotation.z) && finite(x.scale);
}

// What a loaded character must be safe for: indices inside their arrays, every number finite, weights summing
// to 1.
void check_usable(const Character& ch) {
  REQUIRE(ch.skeleton.joint_count() > 0);
  for (int j = 0; j < ch.skeleton.joint_count(); ++j) {
    INFO("joint " << j);
    REQUIRE(ch.skeleton.parents[j] < j);
    REQUIRE(finite_transform(ch.skeleton.rest_local[j]));
  }
  for (const SkinnedMesh& m : ch.meshes) {
    INFO("mesh " << m.name);
    const std::size_t nv = m.vertex_count();
    REQUIRE(m.py.size() == nv);
    REQUIRE(m.pz.size() == nv);
    REQUIRE(m.joints.size() == nv);
    REQUIRE(m.weights.size() == nv);
    REQUIRE((m.nx.empty() || (m.nx.size() == nv && m.ny.size() == nv && m.nz.size() == nv)));
    REQUIRE(m.indices.size() % 3 == 0);
    for (std::uint32_t i : m.indices) REQUIRE(i < nv);
    for (int j : m.joint_remap) REQUIRE((j >= 0 && j < ch.skeleton.joint_count()));
    for (std::size_t b = 0; b < m.inverse_bind.size(); ++b) {
      INFO("bone " << b);
      REQUIRE(finite_transform(m.inverse_bind[b]));
      for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r) REQUIRE(finite(m.inverse_bind_matrix[b][c][r]));
    }
    for (std::size_t v = 0; v < nv; ++v) {
      INFO("vertex " << v);
      REQUIRE((finite(m.px[v]) && finite(m.py[v]) && finite(m.pz[v])));
      if (m.has_normals()) REQUIRE((finite(m.nx[v]) && finite(m.ny[v]) && finite(m.nz[v])));
      float sum = 0.0f;
      for (int k = 0; k < 4; ++k) {
        REQUIRE(m.joints[v][k] < m.joint_remap.size());
        REQUIRE(finite(m.weights[v][k]));
        REQUIRE(m.weights[v][k] >= 0.0f);
        sum += m.weights[v][k];
      }
      REQUIRE(std::abs(sum - 1.0f) < 1e-5f);
    }
  }
  for (const Clip& c : ch.clips) {
    REQUIRE(c.keys.size() == std::size_t(ch.skeleton.joint_count()));
    for (const JointKeys& k : c.keys) {
      REQUIRE(k.size() >= 1);
      for (std::size_t i = 0; i < k.size(); ++i) {
        INFO("clip " << c.name << " key " << i);
        REQUIRE(finite(k.times[i]));
        REQUIRE(finite_transform(k.transforms[i]));
      }
    }
  }
}

// Loads `path`: a usable character, or a LoadError whose message names the path. Returns the error message,
// empty when it loaded.
std::string load_or_error(const std::string& path) {
  try {
    check_usable(load_character(path));
    return {};
  } catch (const LoadError& e) {
    INFO(e.what());
    CHECK(std::string(e.what()).find(path) != std::string::npos);
    return e.what();
  }
}

// One edited line of a text file: its 1-based number, the text it must have, the text it gets.
struct LineEdit {
  std::size_t line;
  const char* was;
  const char* becomes;
};

std::string edit_lines(const std::string& text, const std::vector<LineEdit>& edits) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (;;) {
    const std::size_t nl = text.find('\n', start);
    lines.push_back(text.substr(start, nl == std::string::npos ? std::string::npos : nl - start));
    if (nl == std::string::npos) break;
    start = nl + 1;
  }
  for (const LineEdit& e : edits) {
    REQUIRE(e.line - 1 < lines.size());
    INFO("line " << e.line);
    REQUIRE(lines[e.line - 1] == e.was);  // another version of the test model: the edit would mean nothing
    lines[e.line - 1] = e.becomes;
  }
  std::string out;
  for (std::size_t i = 0; i < lines.size(); ++i) out += lines[i] + (i + 1 < lines.size() ? "\n" : "");
  return out;
}

}  // namespace

// ------------------------------------------------------------------------------------ the child process

TEST_CASE("the child-process runner returns the child's bytes, or says how the child ended") {
  using io_detail::ChildOutcome;
  using namespace std::chrono_literals;
  SECTION("a result larger than a pipe's buffer") {
    const ChildOutcome out = io_detail::run_in_child([] { return std::string(3 << 20, 'y'); }, 30s);
    CHECK(out.kind == ChildOutcome::Kind::finished);
    CHECK(out.output == std::string(3 << 20, 'y'));
  }
  SECTION("a crash") {
    const ChildOutcome out = io_detail::run_in_child([] { std::raise(SIGSEGV); return std::string("no"); }, 30s);
    CHECK(out.kind == ChildOutcome::Kind::signaled);
    CHECK(io_detail::signal_name(out.code) == "SIGSEGV");
  }
  SECTION("a hang is killed at the limit") {
    const auto t0 = std::chrono::steady_clock::now();
    const ChildOutcome out = io_detail::run_in_child([] { for (;;) ::pause(); return std::string(); }, 200ms);
    CHECK(out.kind == ChildOutcome::Kind::timed_out);
    CHECK(std::chrono::steady_clock::now() - t0 < 10s);
  }
  SECTION("an exception or an exit without a result") {
    CHECK(io_detail::run_in_child([]() -> std::string { throw std::runtime_error("x"); }, 30s).kind ==
          ChildOutcome::Kind::exited);
    const ChildOutcome out = io_detail::run_in_child([]() -> std::string { ::_exit(7); }, 30s);
    CHECK(out.kind == ChildOutcome::Kind::exited);
    CHECK(out.code == 7);
  }
  CHECK(io_detail::signal_name(SIGKILL) == "SIGKILL");
}

// ------------------------------------------------------------------------------------ importer crashes

// Two mutants of X/Testwuson.X on which Assimp 5.2.5's .X importer dies by SIGSEGV (found by mutating the
// test characters; rebuilt here from the original by their line edits rather than kept as 800 kB files).
// A vertex index past the mesh (a face index, a skin weight's vertex) makes the importer read past its
// arrays. The first file's skin weight of vertex 99999999 reads 1.2 GB past one: it crashes every time. The
// second one's indices 65536 read less than 1 MB past, so whether it crashes depends on what the heap holds
// there (it does in a small program, not always in this test): a usable character is fine too, since the
// loader checks every index it passes on.
TEST_CASE("files on which Assimp's importer crashes give a LoadError naming the file, and loading goes on") {
  const std::string original = read_bytes(model("X/Testwuson.X"));
  const std::vector<std::vector<LineEdit>> finds = {
      {{1285, "  0.357320;0.465251;-0.417054;,", "  0.357320;3.4e39;-0.417054;,"},
       {3108, "  -0.018613;1.323238;1.595557;,", "  -0.018613;-1;1.595557;,"},
       {11616, "   3;1102,1103,1149;,", "   3;1102,-2147483648,1149;,"},
       {12534, "   3;1821,1822,1823;,", "   3;65536,1822,1823;,"},
       {18459, "   1283,", "   99999999,"}},
      {{2932, "  -0.000000;1.257709;0.991296;,", "  -0.000000;1.257709;nan;,"},
       {4414, "  3;876,877,861;,", "  3;876,877,99999999;,"},
       {11379, "   3;957,763,958;,", "   3;957,763,65536;,"},
       {24968, "   169,", "   65536,"}},
  };
  for (std::size_t i = 0; i < finds.size(); ++i) {
    const std::string path = temp_file("crash_x_importer_" + std::to_string(i + 1) + ".X", edit_lines(original, finds[i]));
    INFO(path);
    const std::string error = load_or_error(path);
    std::cout << "crash_x_importer_" << i + 1 << ".X: " << (error.empty() ? "loaded" : error) << "\n";
    if (i == 0) {
      CHECK(error.find("the model importer crashed (SIG") != std::string::npos);
      CHECK(error.find("the file is malformed") != std::string::npos);
    }
  }
  // The process that saw the crashes loads a good file as before.
  const Character ch = load_character(model("X/BCN_Epileptic.X"));
  CHECK(ch.skeleton.joint_count() == 54);
  check_usable(ch);
}

// ------------------------------------------------------------------------------------------ mutants
// A fixed seed per model: byte flips, a truncation, a zeroed span, or a number replaced by one a parser may
// trust (a count or index past the data, nan, an overflowing exponent). CGA_MODEL_FUZZ_COUNT raises the
// count per model (default 40) to explore; CGA_MODEL_FUZZ_SEED changes the seeds; CGA_MODEL_FUZZ_VERBOSE=1
// prints each mutant's outcome.

namespace {

std::string mutate(const std::string& in, std::mt19937& rng, int kind) {
  std::string s = in;
  auto pick = [&](std::size_t n) { return std::uniform_int_distribution<std::size_t>(0, n - 1)(rng); };
  switch (kind) {
    case 0: {  // flip 1 to 3 bytes (more break every parser at the first of them)
      const std::size_t n = 1 + pick(3);
      for (std::size_t i = 0; i < n; ++i) s[pick(s.size())] ^= char(1 + pick(255));
      break;
    }
    case 1:  // cut anywhere
      s.resize(pick(s.size()));
      break;
    case 2: {  // zero a span of 1 to 4096 bytes
      const std::size_t at = pick(s.size()), n = std::min(s.size() - at, 1 + pick(4096));
      std::fill(s.begin() + std::ptrdiff_t(at), s.begin() + std::ptrdiff_t(at + n), '\0');
      break;
    }
    default: {  // replace 1 or 2 numbers
      static const char* const numbers[] = {"nan", "inf", "-1", "0", "1e39", "65536", "99999999", "-2147483648",
                                            "4294967295"};
      const std::size_t n = 1 + pick(2);
      for (std::size_t i = 0; i < n; ++i) {
        std::size_t at = s.find_first_of("0123456789", pick(s.size()));
        if (at == std::string::npos) continue;
        std::size_t end = s.find_first_not_of("0123456789.eE-+", at);
        if (end == std::string::npos) end = s.size();
        s.replace(at, end - at, numbers[pick(std::size(numbers))]);
      }
      break;
    }
  }
  return s;
}

int env_int(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v && *v ? std::atoi(v) : fallback;
}

}  // namespace

TEST_CASE("seeded mutants of each format give a usable character or a LoadError, never a crash") {
  const int count = env_int("CGA_MODEL_FUZZ_COUNT", 40);
  const unsigned seed = unsigned(env_int("CGA_MODEL_FUZZ_SEED", 2024));
  const bool verbose = env_int("CGA_MODEL_FUZZ_VERBOSE", 0) != 0;
  const char* models[] = {"X/BCN_Epileptic.X", "FBX/animation_with_skeleton.fbx", "glTF2/simple_skin/simple_skin.gltf",
                          "BVH/01_01.bvh"};
  for (std::size_t mi = 0; mi < std::size(models); ++mi) {
    const char* rel = models[mi];
    const std::string bytes = read_bytes(model(rel));
    const std::string ext = fs::path(rel).extension().string();
    std::mt19937 rng(seed + unsigned(mi));
    int loaded = 0, refused = 0, crashed = 0;
    for (int i = 0; i < count; ++i) {
      const std::string mutant = mutate(bytes, rng, i % 4);
      const std::string path = temp_file("mutant_" + std::to_string(mi) + "_" + std::to_string(i) + ext, mutant);
      INFO(rel << " mutant " << i << " (kind " << i % 4 << ", seed " << seed << ")");
      const std::string error = load_or_error(path);
      if (verbose) std::cout << "  mutant " << i << " (kind " << i % 4 << "): " << (error.empty() ? "loaded" : error) << "\n";
      if (error.empty()) ++loaded;
      else ++refused, crashed += error.find("the model importer crashed") != std::string::npos;
    }
    std::cout << rel << ": " << count << " mutants: " << loaded << " loaded, " << refused << " refused (" << crashed
              << " of them importer crashes)\n";
  }
}

// ----------------------------------------------------------------------------- non-finite numbers
// A two-joint .X character: six vertices, four triangles, normals, weights, a clip moving the top joint.
// `position` is vertex 5's y, `normal` vertex 1's x, `weight` the "bottom" bone's weight of vertex 2 (the
// file's numbering; Assimp's may differ, the warnings use Assimp's), `rest_y` the y translation of the bottom
// joint's rest transform, `key_x` the x of the top joint's second translation key (of three).

namespace {

std::string small_x(const char* position, const char* normal, const char* weight, const char* rest_y = "0.0",
                    const char* key_x = "0.0") {
  return std::string(R"(xof 0303txt 0032
Frame Root {
  FrameTransformMatrix { 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0;; }
  Frame bottom {
    FrameTransformMatrix { 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, )") + rest_y + R"(, 0.0, 1.0;; }
    Frame top {
      FrameTransformMatrix { 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 1.0;; }
    }
  }
  Frame body {
    Mesh quad {
      6;
      0.0; 0.0; 0.0;,
      1.0; 0.0; 0.0;,
      1.0; 1.0; 0.0;,
      0.0; 1.0; 0.0;,
      0.0; 2.0; 0.0;,
      1.0; )" + position + R"(; 0.0;;
      4;
      3; 0, 1, 2;,
      3; 0, 2, 3;,
      3; 3, 2, 5;,
      3; 3, 5, 4;;
      MeshNormals {
        6;
        0.0; 0.0; 1.0;,
        )" + normal + R"(; 0.0; 1.0;,
        0.0; 0.0; 1.0;,
        0.0; 0.0; 1.0;,
        0.0; 0.0; 1.0;,
        0.0; 0.0; 1.0;;
        4;
        3; 0, 1, 2;,
        3; 0, 2, 3;,
        3; 3, 2, 5;,
        3; 3, 5, 4;;
      }
      XSkinMeshHeader { 2; 2; 2; }
      SkinWeights {
        "bottom";
        4;
        0, 1, 2, 3;
        1.0, 1.0, )" + weight + R"(, 0.5;
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0;;
      }
      SkinWeights {
        "top";
        4;
        2, 3, 4, 5;
        0.5, 0.5, 1.0, 1.0;
        1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, -1.0, 0.0, 1.0;;
      }
    }
  }
}
AnimationSet walk {
  Animation {
    {top}
    AnimationKey {
      2;
      3;
      0;3;0.0,1.0,0.0;;,
      10;3;)" + key_x + R"(,1.0,0.0;;,
      20;3;0.0,1.0,0.0;;;
    }
  }
}
)";
}

// The warnings that contain every one of `parts`.
std::vector<std::string> warnings_with(const Character& ch, const std::vector<std::string>& parts) {
  std::vector<std::string> out;
  for (const std::string& w : ch.warnings) {
    bool all = true;
    for (const std::string& p : parts) all = all && w.find(p) != std::string::npos;
    if (all) out.push_back(w);
  }
  return out;
}

std::string all_warnings(const Character& ch) {
  std::string s;
  for (const std::string& w : ch.warnings) s += "  " + w + "\n";
  return s;
}

}  // namespace

TEST_CASE("a good small .X character loads without warnings (the base of the non-finite tests)") {
  const Character ch = load_character(temp_file("finite.x", small_x("2.0", "0.0", "0.5")));
  INFO(all_warnings(ch));
  CHECK(ch.warnings.empty());
  REQUIRE(ch.meshes.size() == 1);
  CHECK(ch.meshes[0].vertex_count() == 6);
  CHECK(ch.meshes[0].indices.size() == 12);
  check_usable(ch);
}

TEST_CASE("a nan or infinite vertex position is named with mesh and vertex, and the vertex dropped with its triangles") {
  // "1e39" overflows a float: Assimp reads it as infinity.
  for (const char* bad : {"nan", "inf", "-inf", "1e39"}) {
    INFO("position " << bad);
    const Character ch = load_character(temp_file(std::string("position_") + bad + ".x", small_x(bad, "0.0", "0.5")));
    INFO(all_warnings(ch));
    REQUIRE(ch.meshes.size() == 1);
    const SkinnedMesh& m = ch.meshes[0];
    const auto named = warnings_with(ch, {"mesh '" + m.name + "', vertex ", "position (", "is not finite",
                                          "dropped the vertex and its triangles"});
    CHECK(named.size() == 1);
    CHECK(ch.warnings.size() == 1);  // and nothing else to say about the file
    CHECK(m.vertex_count() == 5);
    CHECK(m.indices.size() == 6);  // the two triangles of the bad vertex are gone
    check_usable(ch);
    CHECK(std::isfinite(character_size(ch)));
    CHECK(character_size(ch) > 0.0f);
  }
}

TEST_CASE("a nan or infinite normal is named with mesh and vertex, and rebuilt from the vertex's triangles") {
  for (const char* bad : {"nan", "inf"}) {
    INFO("normal " << bad);
    const Character ch = load_character(temp_file(std::string("normal_") + bad + ".x", small_x("2.0", bad, "0.5")));
    INFO(all_warnings(ch));
    REQUIRE(ch.meshes.size() == 1);
    const SkinnedMesh& m = ch.meshes[0];
    CHECK(warnings_with(ch, {"mesh '" + m.name + "', vertex ", "normal (", "is not finite", "replaced"}).size() == 1);
    CHECK(m.vertex_count() == 6);
    check_usable(ch);
    // The quad lies in the z = 0 plane: every normal, the rebuilt one too, is +-z.
    for (std::size_t v = 0; v < m.vertex_count(); ++v) {
      INFO("vertex " << v);
      CHECK(std::abs(std::abs(m.nz[v]) - 1.0f) < 1e-5f);
    }
  }
}

TEST_CASE("an infinite bone weight is named with mesh, vertex and bone, and dropped") {
  // Assimp's .X importer drops a nan weight itself (it keeps only weights > 0); an infinite one reaches the
  // loader.
  const Character ch = load_character(temp_file("weight_inf.x", small_x("2.0", "0.0", "inf")));
  INFO(all_warnings(ch));
  REQUIRE(ch.meshes.size() == 1);
  const SkinnedMesh& m = ch.meshes[0];
  CHECK(warnings_with(ch, {"mesh '" + m.name + "', vertex ", "bone 'bottom'", "not finite", "dropped"}).size() == 1);
  CHECK(m.vertex_count() == 6);
  check_usable(ch);
}

TEST_CASE("a nan rest transform or animation key is named with joint (and clip and key) and replaced or dropped") {
  SECTION("rest transform") {
    const Character ch = load_character(temp_file("rest_nan.x", small_x("2.0", "0.0", "0.5", "nan")));
    INFO(all_warnings(ch));
    CHECK(warnings_with(ch, {"joint 'bottom': rest transform", "not finite", "identity"}).size() == 1);
    check_usable(ch);
  }
  SECTION("translation key") {
    const Character ch = load_character(temp_file("key_nan.x", small_x("2.0", "0.0", "0.5", "0.0", "nan")));
    INFO(all_warnings(ch));
    CHECK(warnings_with(ch, {"clip 'walk', bone 'top', translation key 1", "not finite", "dropped"}).size() == 1);
    check_usable(ch);
    REQUIRE(ch.clips.size() == 1);
    const int top = ch.skeleton.find("top");
    REQUIRE(top >= 0);
    CHECK(ch.clips[0].tracks[top].translations.size() == 2);  // the keys before and after it
  }
}
