// cga-demo --web: exports the character, its per-frame bone palettes (computed by the C++ runtime and
// prepared for every method of the method table), the table's names and colours, the twist strip and the
// CPU skinning jobs' vertices of one frame into the page template that web/ assembles at build time from
// cgagen's generated WGSL and GLSL ES blends (cga/web/page_template.hpp). The page is one file: data is
// base64 little-endian float32/uint32 inside a <script>, since a page opened from file:// cannot fetch()
// its neighbours.
#include "web.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "cga/runtime/motor.hpp"
#include "cga/runtime/packed_palette.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "cga/testing/twist_strip.hpp"
#include "cga/web/page_template.hpp"

namespace demo {
namespace {

using namespace cga;

// Floats per vertex: position 3, normal 3, 4 palette indices (as floats: exact below 2^24), 4 weights.
constexpr int kVertexFloats = 14;

std::string base64(const void* data, std::size_t bytes) {
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  const auto* p = static_cast<const unsigned char*>(data);
  std::string s;
  s.reserve((bytes + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes; i += 3) {
    const std::uint32_t n = (std::uint32_t(p[i]) << 16) | (i + 1 < bytes ? std::uint32_t(p[i + 1]) << 8 : 0) |
                            (i + 2 < bytes ? std::uint32_t(p[i + 2]) : 0);
    s += abc[(n >> 18) & 63];
    s += abc[(n >> 12) & 63];
    s += i + 1 < bytes ? abc[(n >> 6) & 63] : '=';
    s += i + 2 < bytes ? abc[n & 63] : '=';
  }
  return s;
}
template <class T>
std::string base64(const std::vector<T>& v) {
  static_assert(sizeof(T) == 4, "the page reads 32-bit little-endian words");
  return base64(v.data(), v.size() * sizeof(T));
}

// What the demo does for its method comparison (main.cpp palettes_from_motors): every method's palette from
// the one motor palette; dqs gets the rigid part (a dual quaternion has no scale).
struct Palettes {
  MotorPalette motors;
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
};
Palettes from_motors(const MotorPalette& motors) {
  Palettes p;
  p.motors = motors;
  for (const Motor& m : motors) {
    p.matrices.push_back(motor_matrix(m));
    Transform x = motor_to_transform(m);
    x.scale = 1.0f;
    p.dual_quats.push_back(to_dual_quat(x));
  }
  return p;
}

// Floats of one palette entry over every method: the page's palette of one pose holds each method's prepared
// palette (the entries its generated blend reads) one after the other, in table order.
std::size_t all_methods_entry_floats() {
  std::size_t n = 0;
  for (SkinningMethod method : kAllSkinningMethods) n += prepared_entry_floats(method);
  return n;
}

// One pose of the page: for every method in table order, its prepared palette of every mesh (meshes one
// after the other, as concatenate() numbers their entries). `entries` is the meshes' entry count.
void append_entries(const std::vector<Palettes>& per_mesh, std::size_t entries, std::vector<float>& out) {
  const std::size_t at = out.size();
  for (SkinningMethod method : kAllSkinningMethods)
    for (const Palettes& p : per_mesh) append_packed_palette(method, p.matrices, p.dual_quats, p.motors, out);
  if (out.size() - at != entries * all_methods_entry_floats())
    throw std::runtime_error("web: the poses' palettes do not have one entry per joint of the meshes");
}

// Meshes concatenated: one vertex array, one index array, joints offset into one concatenated palette.
struct PageMesh {
  std::vector<float> vertices;
  std::vector<std::uint32_t> indices;
  std::vector<std::size_t> palette_base;  // per mesh
  std::size_t entries = 0;
};
PageMesh concatenate(const std::vector<const SkinnedMesh*>& meshes) {
  PageMesh pm;
  std::uint32_t vbase = 0;
  for (const SkinnedMesh* m : meshes) {
    pm.palette_base.push_back(pm.entries);
    for (std::size_t v = 0; v < m->vertex_count(); ++v) {
      float n[3] = {0, 0, 0};
      if (m->has_normals()) n[0] = m->nx[v], n[1] = m->ny[v], n[2] = m->nz[v];
      const float row[kVertexFloats] = {m->px[v], m->py[v], m->pz[v], n[0], n[1], n[2],
                                        float(pm.entries + m->joints[v][0]), float(pm.entries + m->joints[v][1]),
                                        float(pm.entries + m->joints[v][2]), float(pm.entries + m->joints[v][3]),
                                        m->weights[v][0], m->weights[v][1], m->weights[v][2], m->weights[v][3]};
      pm.vertices.insert(pm.vertices.end(), row, row + kVertexFloats);
    }
    for (std::uint32_t i : m->indices) pm.indices.push_back(vbase + i);
    vbase += std::uint32_t(m->vertex_count());
    pm.entries += m->joint_remap.size();
  }
  return pm;
}

// The CPU jobs' skinned positions (x y z per vertex, meshes concatenated) for every method, method-major.
std::vector<float> cpu_reference(const std::vector<const SkinnedMesh*>& meshes, const std::vector<Palettes>& pal) {
  std::vector<float> out;
  for (SkinningMethod method : kAllSkinningMethods) {
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      SkinnedOutput o;
      SkinningJob job = make_skinning_job(method, *meshes[m], o);
      job.motors = pal[m].motors, job.matrices = pal[m].matrices, job.dual_quats = pal[m].dual_quats;
      if (!job.Run()) throw std::runtime_error("web: CPU skinning failed: " + job.ValidationError());
      for (std::size_t v = 0; v < o.px.size(); ++v) out.insert(out.end(), {o.px[v], o.py[v], o.pz[v]});
    }
  }
  return out;
}

std::string json_string(const std::string& s) {  // a JSON string (names of clips and files)
  std::string q = "\"";
  for (char c : s) {
    if (c == '"' || c == '\\') q += '\\', q += c;
    else if (c == '<') q += "\\u003c";  // never "</script>" inside the data
    else if (static_cast<unsigned char>(c) < 0x20) q += fmt::format("\\u{:04x}", int(c));
    else q += c;
  }
  return q + "\"";
}

// The method table for the page (CGA_DATA.methods): name, caption, colour and vec4s per prepared entry, in
// table order (a method's index is its code in the page's shaders).
std::string methods_json() {
  std::vector<std::string> rows;
  for (SkinningMethod method : kAllSkinningMethods) {
    const SkinningMethodInfo& info = skinning_method_info(method);
    rows.push_back(fmt::format("{{name: {}, caption: {}, colour: [{:g}, {:g}, {:g}], vec4s: {}}}",
                               json_string(std::string(info.name)), json_string(std::string(info.caption)),
                               info.colour[0], info.colour[1], info.colour[2], info.entry_vec4s));
  }
  return fmt::format("[{}]", fmt::join(rows, ", "));
}

}  // namespace

std::string write_web_page(const WebInput& in, const std::string& dir) {
  const Character& ch = *in.character;
  if (ch.meshes.empty()) throw std::runtime_error("--web: the character has no skinned mesh");
  std::vector<const SkinnedMesh*> meshes;
  for (const SkinnedMesh& m : ch.meshes) meshes.push_back(&m);
  const PageMesh body = concatenate(meshes);

  // Palettes: mode-major, then time step, then weight step, then entries.
  std::vector<float> palettes, centers;
  std::vector<std::string> mode_names;
  const int selftest_t = in.times / 2, selftest_w = in.weights / 2;
  std::vector<Palettes> selftest_pal;
  std::string selftest_mode;
  for (Interpolation mode : in.modes) {
    mode_names.push_back(json_string(std::string(to_string(mode))));
    for (int t = 0; t < in.times; ++t) {
      for (int w = 0; w < in.weights; ++w) {
        const std::vector<MotorPalette> per_mesh =
            in.pose(mode, float(t) / float(in.times - 1), float(w) / float(in.weights - 1));
        std::vector<Palettes> pal;
        for (const MotorPalette& mp : per_mesh) pal.push_back(from_motors(mp));
        append_entries(pal, body.entries, palettes);
        // The camera follows the character: the centre of its bounding box in this pose (cga-motors).
        glm::vec3 lo(INFINITY), hi(-INFINITY);
        for (std::size_t m = 0; m < meshes.size(); ++m) {
          SkinnedOutput o;
          SkinningJob job = make_skinning_job(SkinningMethod::cga_motors, *meshes[m], o);
          job.motors = pal[m].motors;
          if (!job.Run()) throw std::runtime_error("web: CPU skinning failed: " + job.ValidationError());
          for (std::size_t v = 0; v < o.px.size(); ++v)
            lo = glm::min(lo, glm::vec3(o.px[v], o.py[v], o.pz[v])), hi = glm::max(hi, glm::vec3(o.px[v], o.py[v], o.pz[v]));
        }
        const glm::vec3 c = 0.5f * (lo + hi);
        centers.insert(centers.end(), {c.x, c.y, c.z});
        if (mode == Interpolation::screw && t == selftest_t && w == selftest_w)
          selftest_pal = pal, selftest_mode = "screw";
      }
    }
  }
  if (selftest_pal.empty()) throw std::runtime_error("--web: the page's self-test needs the screw mode");
  const std::vector<float> reference = cpu_reference(meshes, selftest_pal);

  // The twist strip: joint 1 turned from 0 to 180 degrees in 12 steps (the demo's candy-wrapper test).
  const TwistCylinder cyl = make_twist_cylinder();
  const PageMesh strip = concatenate({&cyl.mesh});
  const int angles = 13;
  std::vector<float> twist_palettes;
  std::vector<Palettes> twist_last;
  for (int a = 0; a < angles; ++a) {
    const float angle = std::numbers::pi_v<float> * float(a) / float(angles - 1);
    Palettes p;
    for (const Transform& x : twist_cylinder_skinning_transforms(cyl.spec, angle)) {
      p.motors.push_back(motor_from_transform(x));
    }
    p = from_motors(p.motors);
    append_entries({p}, strip.entries, twist_palettes);
    if (a == angles - 1) twist_last = {p};
  }
  const std::vector<float> twist_reference = cpu_reference({&cyl.mesh}, twist_last);

  std::string data = "const CGA_DATA = {\n";
  data += fmt::format("  model: {}, fade: {}, size: {:.9g},\n", json_string(in.model), json_string(in.fade_description), in.size);
  data += fmt::format("  methods: {},\n", methods_json());
  data += fmt::format("  modes: [{}], times: {}, weights: {}, vertexFloats: {},\n", fmt::join(mode_names, ", "),
                      in.times, in.weights, kVertexFloats);
  if (in.time_label) {
    std::vector<std::string> labels;
    for (int t = 0; t < in.times; ++t) labels.push_back(json_string(in.time_label(float(t) / float(in.times - 1))));
    data += fmt::format("  timeLabels: [{}],\n", fmt::join(labels, ", "));
  }
  data += fmt::format("  character: {{entries: {}, vertexCount: {}, vertices: \"{}\", indices: \"{}\", palettes: \"{}\", centers: \"{}\"}},\n",
                      body.entries, body.vertices.size() / kVertexFloats, base64(body.vertices), base64(body.indices),
                      base64(palettes), base64(centers));
  data += fmt::format("  twist: {{entries: {}, vertexCount: {}, angles: {}, size: {:.9g}, vertices: \"{}\", indices: \"{}\", palettes: \"{}\", reference: \"{}\"}},\n",
                      strip.entries, strip.vertices.size() / kVertexFloats, angles, cyl.spec.length,
                      base64(strip.vertices), base64(strip.indices), base64(twist_palettes), base64(twist_reference));
  data += fmt::format("  selftest: {{mode: {}, time: {}, weight: {}, reference: \"{}\"}}\n",
                      json_string(selftest_mode), selftest_t, selftest_w, base64(reference));
  data += "};\n";

  std::string page(cga::web::page_template());
  const std::string marker = "/*@CGA_DATA@*/";
  const std::size_t at = page.find(marker);
  if (at == std::string::npos) throw std::runtime_error("web: the page template has no data marker");
  page.replace(at, marker.size(), data);

  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw std::runtime_error(fmt::format("cannot create folder {}: {}", dir, ec.message()));
  const std::string path = dir + "/index.html";
  std::ofstream f(path, std::ios::binary);
  f << page;
  if (!f.flush()) throw std::runtime_error("cannot write " + path);
  return fmt::format("{} ({:.0f} KiB: {} vertices, {} palette entries x {} methods x {} modes x {} times x {} weights)",
                     path, double(page.size()) / 1024.0, body.vertices.size() / kVertexFloats, body.entries,
                     kSkinningMethodCount, in.modes.size(), in.times, in.weights);
}

}  // namespace demo
