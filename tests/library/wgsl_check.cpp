// wgsl_check LIBRARY WGSL PYTHON TARGETS_DIR CHROMIUM WORK_DIR [COUNT]: a generated library's WGSL (cgagen
// --library --target wgsl) run as WebGPU compute shaders in headless Chromium (Tint, then SwiftShader's
// Vulkan on the CPU) against the same library's C++ (which tests/library checks against the oracle), through
// tests/targets' harness unchanged: browser_harness.js is inlined into a page of cases and browser_run.py
// (in TARGETS_DIR) drives Chromium. COUNT functions (default 150; 0: every function) are drawn with a fixed
// seed (check_sample.hpp), each on kRows seeded operand rows; a case is one shader of up to kChunk functions,
// one thread per row, that loads the row into the operand structs, calls LIBRARY_OP_A_B(a, b) and stores the
// result. Tint's errors fail the check. Every value must agree with the C++ within 1e-4 (1 + |value|).
//
// Sine and cosine: WGSL promises only an absolute error of 2^-11 for them and SwiftShader uses that room
// (tests/targets saw 4e-4), more than the tolerance. So, as tests/targets does, the library's sin and cos
// calls are renamed to accurate float versions (kSinCos): the kernels are checked at float precision.
// Exit status 0 when every value agrees.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

#include "cga3.hpp"
#include "cga_rigid.hpp"
#include "check_sample.hpp"
#include "e3.hpp"
#include "pga3.hpp"

namespace {

constexpr size_t kRows = 4;    // operand rows per function
constexpr size_t kChunk = 32;  // functions per shader, as glsl_check (a smaller switch per pipeline)
constexpr int kTimeout = 240;  // seconds for browser_run.py: a hung browser fails the check

// Cephes' sinf/cosf (Cody-Waite reduction by pi/2, minimax polynomials, ~1 ulp): tests/targets' kSinCosWgsl.
const char* kSinCos =
    "fn cgagen_sincos(x: f32) -> vec2<f32> {  // (sin x, cos x)\n"
    "  let k = round(x * 0.63661977236758134);\n"
    "  let r = ((x - k * 1.5703125) - k * 4.837512969970703125e-4) - k * 7.54978995489188216e-8;\n"
    "  let z = r * r;\n"
    "  let s = r + r * z * (-1.6666654611e-1 + z * (8.3321608736e-3 + z * -1.9515295891e-4));\n"
    "  let c = 1.0 - 0.5 * z + z * z * (4.166664568298827e-2 + z * (-1.388731625493765e-3 + z * 2.443315711809948e-5));\n"
    "  let q = i32(k) & 3;\n"
    "  if (q == 0) { return vec2(s, c); }\n  if (q == 1) { return vec2(c, -s); }\n"
    "  if (q == 2) { return vec2(-s, -c); }\n  return vec2(-c, s);\n}\n"
    "fn cgagen_sin(x: f32) -> f32 { return cgagen_sincos(x).x; }\n"
    "fn cgagen_cos(x: f32) -> f32 { return cgagen_sincos(x).y; }\n";

std::string read(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// Little-endian float32 bytes in base64, as the harness's cgagenDecode reads them (and back).
std::string base64(const std::vector<float>& v) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* b = reinterpret_cast<const unsigned char*>(v.data());
  const size_t n = v.size() * sizeof(float);
  std::string out;
  for (size_t i = 0; i < n; i += 3) {
    unsigned x = b[i] << 16 | (i + 1 < n ? b[i + 1] << 8 : 0) | (i + 2 < n ? b[i + 2] : 0);
    out += abc[x >> 18 & 63];
    out += abc[x >> 12 & 63];
    out += i + 1 < n ? abc[x >> 6 & 63] : '=';
    out += i + 2 < n ? abc[x & 63] : '=';
  }
  return out;
}

std::vector<float> unbase64(const std::string& s) {
  std::string bytes;
  unsigned x = 0;
  int bits = 0;
  for (char ch : s) {
    int d = ch >= 'A' && ch <= 'Z' ? ch - 'A' : ch >= 'a' && ch <= 'z' ? ch - 'a' + 26
          : ch >= '0' && ch <= '9' ? ch - '0' + 52 : ch == '+' ? 62 : ch == '/' ? 63 : -1;
    if (d < 0) continue;  // '=' padding
    x = x << 6 | d;
    bits += 6;
    if (bits >= 8) bytes += static_cast<char>(x >> (bits -= 8) & 255);
  }
  std::vector<float> v(bytes.size() / sizeof(float));
  std::copy(bytes.begin(), bytes.begin() + static_cast<long>(v.size() * sizeof(float)), reinterpret_cast<char*>(v.data()));
  return v;
}

// A JavaScript string literal; '<' escaped so that no "</script>" ends the page's script early.
std::string js_string(const std::string& s) {
  std::string out = "\"";
  char buf[8];
  for (unsigned char ch : s) {
    if (ch == '"' || ch == '\\') out += std::string("\\") + static_cast<char>(ch);
    else if (ch == '\n') out += "\\n";
    else if (ch < 0x20 || ch == '<') std::snprintf(buf, sizeof buf, "\\u%04x", ch), out += buf;
    else out += static_cast<char>(ch);
  }
  return out + "\"";
}

template <class TypeInfo, class FunctionInfo, class Matrices, size_t NT, size_t NF>
int check(const std::string& lib, const TypeInfo (&types)[NT], const FunctionInfo (&fns)[NF], const Matrices& matrices,
          const std::string& wgsl,
          const std::string& python, const std::string& targets_dir, const std::string& chromium,
          const std::string& work, size_t count) {
  const auto t0 = std::chrono::steady_clock::now();
  const std::string library = std::regex_replace(read(wgsl), std::regex("\\b(sin|cos)\\("), "cgagen_$1(");
  // A type's name as the file spells it (a WGSL reserved word gets a trailing _).
  auto type = [&](const std::string& t) {
    return library.find("struct " + lib + "_" + t + " {") != std::string::npos ? lib + "_" + t : lib + "_" + t + "_";
  };
  std::vector<library_check::Case> picked = library_check::sample("wgsl_check", types, fns, count, kRows);
  if (picked.empty()) return 1;
  const size_t sampled = picked.size();
  for (auto& c : library_check::matrix_cases(types, matrices, kRows)) picked.push_back(std::move(c));
  size_t nin = 1, nout = 1;
  for (const auto& c : picked) nin = std::max(nin, c.na + c.nb), nout = std::max(nout, c.nr);
  const std::string NIN = std::to_string(nin) + "u", NOUT = std::to_string(nout) + "u", R = std::to_string(kRows) + "u";
  std::string page = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>cgagen library " + lib +
                     "</title></head><body>\n<script>\nconst CGAGEN_API = \"webgpu\";\nconst CGAGEN_CASES = [\n";
  std::vector<std::string> ids;
  for (size_t first = 0; first < picked.size(); first += kChunk) {
    const size_t n = std::min(kChunk, picked.size() - first);
    // Thread `row` runs function row / kRows of the chunk on operand row row % kRows.
    std::string body;
    std::vector<float> in(n * kRows * nin, 0.0f);
    for (size_t i = 0; i < n; ++i) {
      const library_check::Case& c = picked[first + i];
      for (size_t r = 0; r < kRows; ++r)
        std::copy_n(c.x.begin() + static_cast<long>(r * (c.na + c.nb)), c.na + c.nb,
                    in.begin() + static_cast<long>((i * kRows + r) * nin));
      body += "    case " + std::to_string(i) + "u: {\n      var a: " + type(c.a) + ";\n      for (var k = 0u; k < " +
              std::to_string(c.na) + "u; k++) { a.v[k] = cgagen_in[i + k]; }\n";
      if (c.arity == 2)
        body += "      var b: " + type(c.b) + ";\n      for (var k = 0u; k < " + std::to_string(c.nb) +
                "u; k++) { b.v[k] = cgagen_in[i + " + std::to_string(c.na) + "u + k]; }\n";
      if (c.name == "matrix")
        body += "      let r = " + lib + "_apply_" + c.a + "_" + c.b + "(" + lib + "_matrix_" + c.a + "_" + c.b + "(a), b);\n";
      else
        body += "      let r = " + lib + "_" + c.name + "_" + c.a + (c.arity == 2 ? "_" + c.b + "(a, b);\n" : "(a);\n");
      body += "      for (var k = 0u; k < " + std::to_string(c.nr) + "u; k++) { cgagen_out[o + k] = r.v[k]; }\n    }\n";
    }
    const std::string shader =
        library + "\n" + kSinCos +
        "\n@group(0) @binding(0) var<storage, read> cgagen_in: array<f32>;\n"
        "@group(0) @binding(1) var<storage, read_write> cgagen_out: array<f32>;\n\n"
        "@compute @workgroup_size(64)\nfn cgagen_main(@builtin(global_invocation_id) cgagen_id: vec3<u32>) {\n"
        "  let row = cgagen_id.x;\n  if (row >= " + std::to_string(n * kRows) + "u) { return; }\n"
        "  let i = row * " + NIN + ";\n  let o = row * " + NOUT + ";\n  switch (row / " + R + ") {\n" + body +
        "    default: {}\n  }\n}\n";
    const std::string id = lib + "_" + std::to_string(first / kChunk);
    std::ofstream(work + "/" + id + ".wgsl") << shader;  // to read a failure by hand
    page += "{name: \"" + id + "\", rows: " + std::to_string(n * kRows) + ", nin: " + std::to_string(nin) +
            ", nout: " + std::to_string(nout) + ",\n input: \"" + base64(in) + "\",\n code: " + js_string(shader) + "},\n";
    ids.push_back(id);
  }
  page += "];\n</script>\n<script>\n" + read(targets_dir + "/browser_harness.js") + "</script>\n</body></html>\n";
  const std::string html = work + "/" + lib + ".html", out = work + "/" + lib + ".txt", err = work + "/" + lib + ".err";
  std::ofstream(html) << page;
  std::filesystem::remove(out);
  const std::string cmd = python + " " + targets_dir + "/browser_run.py " + chromium + " webgpu " + html + " " + out +
                          " " + std::to_string(kTimeout) + " 2> " + err;
  if (std::system(cmd.c_str()) != 0) {
    std::fprintf(stderr, "wgsl_check: %s failed:\n%s", cmd.c_str(), read(err).c_str());
    return 1;
  }
  // The page's lines: device, then per case "case ID COMPILE_MS RUN_MS BASE64" or "fail ID MESSAGE", total.
  std::map<std::string, std::vector<float>> values;
  std::istringstream lines(read(out));
  std::string device, total;
  int fails = 0;
  for (std::string line; std::getline(lines, line);) {
    std::istringstream ls(line);
    std::string kind, id, compile_ms, run_ms, data;
    ls >> kind;
    if (kind == "device") device = line.substr(7);
    else if (kind == "total") ls >> total;
    else if (kind == "fail") std::fprintf(stderr, "wgsl_check: %s\n", line.c_str()), ++fails;
    else if (kind == "case" && ls >> id >> compile_ms >> run_ms >> data) values[id] = unbase64(data);
  }
  if (fails) return 1;
  std::vector<std::vector<double>> got;
  std::vector<std::vector<std::string>> forms;
  for (size_t i = 0; i < picked.size(); ++i) {
    const std::vector<float>& v = values[ids[i / kChunk]];
    const size_t first_row = (i % kChunk) * kRows;
    std::vector<double> g;
    for (size_t r = 0; r < kRows && (first_row + r + 1) * nout <= v.size(); ++r)
      for (size_t k = 0; k < picked[i].nr; ++k) g.push_back(v[(first_row + r) * nout + k]);
    got.push_back(g);
    forms.push_back({"WGSL"});
  }
  const int bad = library_check::compare("wgsl_check", lib, picked, got, forms, kRows);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("wgsl_check: %s: %zu of %zu functions and %zu matrices run in WGSL on %s (%zu shaders, page %s ms, %.1f s "
              "in all), %d coefficients off\n", lib.c_str(), sampled, NF, picked.size() - sampled, device.c_str(),
              ids.size(), total.c_str(), wall, bad);
  return bad ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 7) {
    std::fprintf(stderr, "usage: wgsl_check LIBRARY WGSL PYTHON TARGETS_DIR CHROMIUM WORK_DIR [COUNT]\n");
    return 2;
  }
  const std::string lib = argv[1];
  const size_t count = argc > 7 ? std::strtoul(argv[7], nullptr, 10) : 150;
  // CGA_TEST_CHROMIUM overrides the configured path, as in tests/targets.
  const std::string chromium = std::getenv("CGA_TEST_CHROMIUM") ? std::getenv("CGA_TEST_CHROMIUM") : argv[5];
  if (lib == "pga3") return check(lib, pga3::types, pga3::functions, pga3::matrices, argv[2], argv[3], argv[4], chromium, argv[6], count);
  if (lib == "cga3") return check(lib, cga3::types, cga3::functions, cga3::matrices, argv[2], argv[3], argv[4], chromium, argv[6], count);
  if (lib == "e3") return check(lib, e3::types, e3::functions, e3::matrices, argv[2], argv[3], argv[4], chromium, argv[6], count);
  if (lib == "cga_rigid")
    return check(lib, cga_rigid::types, cga_rigid::functions, cga_rigid::matrices, argv[2], argv[3], argv[4], chromium, argv[6], count);
  std::fprintf(stderr, "wgsl_check: unknown library %s\n", lib.c_str());
  return 2;
}
