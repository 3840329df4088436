// cga-gl-bench: crowd skinning throughput on the OpenGL backend (cga::gpu), per method and GL path (vertex
// shader + transform feedback, compute shader), against the memory bandwidth a compute shader reaches (a
// 16-B-per-invocation copy, measured in the same run; glCopyNamedBufferSubData's figure is printed too: on
// NVIDIA it is far below the memory's); the GL counterpart of cga-cuda-bench. Many instances of one mesh, 64
// bones by default, >= 10^7 vertices in all: the coherent mesh (make_coherent_skinned_mesh, neighbouring
// vertices share bones as in real characters) and the random one (4 random bones per vertex, the worst
// case), --mesh picks. Two input layouts:
//   shared        every instance reads the one rest mesh (what cga::gpu::Skinner::set_mesh does): the rest
//                 vertices are read once per dispatch and stay in cache, so the bytes streamed per skinned
//                 vertex are its outputs (12 B, 24 with normals) plus the rest mesh spread over the instances
//                 (36 B, 48 with normals, / instances);
//   per-instance  each instance reads its own copy of the rest mesh (Skinner::set_mesh_per_instance): the
//                 crowd layout, 48 B per vertex (12 position + 8 joints u16x4 + 16 weights f32x4 in,
//                 12 position out; 72 with normals), as cga-cuda-bench's "standard" layout.
// Palettes (bones x 32 or 48 B per instance) are not counted in either. Each dispatch is timed on the GPU with
// a GL_TIME_ELAPSED query around the draw / dispatch alone (uniforms and buffers are set up by a warm-up
// dispatch before; nothing is read back inside the timed part). Mesa's software renderers (llvmpipe,
// softpipe) run vertex shaders, compute shaders and buffer copies on the calling thread, outside what their
// GL_TIME_ELAPSED queries measure (they report ~0 for ten 4 MiB copies): there --timing auto (the default) uses
// the wall clock between glFinish calls around all iterations instead, and says so. For every row it prints vertices/s, bytes per
// vertex, the bandwidth bound (compute copy bandwidth / bytes per vertex), the fraction of it reached, and the largest
// distance between the first and last instance and the CPU SkinningJob (exit status 1 when one is off by more
// than 1e-4 of the scene size, 2 on an error).
//
//   cga-gl-bench [--vertices N] [--instances I] [--bones B] [--iterations K] [--normals]
//                [--inputs shared|per-instance|both] [--path vertex|compute|both] [--copy-mib M]
//                [--timing auto|query|wall] [--mesh coherent|random|both]
#include <fmt/core.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cga/gpu/context.hpp"
#include "cga/gpu/skinning.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;
using namespace cga::gpu;

namespace {

struct Options {
  std::size_t vertices = 16384;
  std::size_t instances = 1024;
  std::size_t bones = 64;
  int iterations = 10;
  bool normals = false;
  std::string inputs = "both";
  std::string path = "both";
  std::size_t copy_mib = 512;
  std::string timing = "auto";
  std::string mesh = "both";
  bool help = false;
};

constexpr std::string_view kUsage =
    "usage: cga-gl-bench [--vertices N] [--instances I] [--bones B] [--iterations K] [--normals]\n"
    "                    [--inputs shared|per-instance|both] [--path vertex|compute|both] [--copy-mib M]\n"
    "                    [--timing auto|query|wall] [--mesh coherent|random|both]\n"
    "defaults: 16384 vertices x 1024 instances, 64 bones, 10 iterations, positions only, both input layouts,\n"
    "both paths, both meshes, a 512 MiB buffer copy for the bandwidth, timing auto (GL_TIME_ELAPSED queries, the wall\n"
    "clock on Mesa's software renderers llvmpipe / softpipe, whose queries do not cover the work)\n";

std::size_t parse_size(std::string_view option, const std::string& text) {
  std::size_t used = 0;
  unsigned long long v = 0;
  try {
    v = std::stoull(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used != text.size() || text.empty() || text[0] == '-')
    throw std::invalid_argument(std::string(option) + " needs a non-negative integer, not '" + text + "'");
  return static_cast<std::size_t>(v);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + std::string(a));
      return argv[++i];
    };
    if (a == "--vertices") o.vertices = parse_size(a, value());
    else if (a == "--instances") o.instances = parse_size(a, value());
    else if (a == "--bones") o.bones = parse_size(a, value());
    else if (a == "--iterations") o.iterations = static_cast<int>(std::min<std::size_t>(parse_size(a, value()), 1u << 20));
    else if (a == "--normals") o.normals = true;
    else if (a == "--inputs") o.inputs = value();
    else if (a == "--path") o.path = value();
    else if (a == "--copy-mib") o.copy_mib = parse_size(a, value());
    else if (a == "--timing") o.timing = value();
    else if (a == "--mesh") o.mesh = value();
    else if (a == "--help" || a == "-h") o.help = true;
    else throw std::invalid_argument("unknown option " + std::string(a) + " (see --help)");
  }
  if (o.inputs != "shared" && o.inputs != "per-instance" && o.inputs != "both")
    throw std::invalid_argument("--inputs must be shared, per-instance or both");
  if (o.path != "vertex" && o.path != "compute" && o.path != "both")
    throw std::invalid_argument("--path must be vertex, compute or both");
  if (o.vertices == 0 || o.instances == 0) throw std::invalid_argument("--vertices and --instances must be >= 1");
  if (o.bones == 0 || o.bones > 65536) throw std::invalid_argument("--bones must be 1..65536");
  if (o.iterations < 1) throw std::invalid_argument("--iterations must be >= 1");
  if (o.mesh != "coherent" && o.mesh != "random" && o.mesh != "both")
    throw std::invalid_argument("--mesh must be coherent, random or both");
  if (o.timing != "auto" && o.timing != "query" && o.timing != "wall")
    throw std::invalid_argument("--timing must be auto, query or wall");
  if (o.copy_mib == 0 || o.copy_mib > 16384) throw std::invalid_argument("--copy-mib must be 1..16384");
  return o;
}

enum class Timing { query, wall };

bool software_renderer(const std::string& renderer) {
  return renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
}

// Seconds per call of `work` (queued GL commands), mean over `iterations` calls. query: one GL_TIME_ELAPSED
// query around each call, all read after the last (nothing waits in between); wall: the wall clock from a
// glFinish before the first call to a glFinish after the last.
template <class Work>
double seconds_per_call(const Context& ctx, Timing timing, int iterations, const std::string& what, Work&& work) {
  double seconds = 0.0;
  if (timing == Timing::query) {
    std::vector<GpuTimer> timers;
    for (int it = 0; it < iterations; ++it) timers.emplace_back(ctx);
    for (GpuTimer& t : timers) {
      t.begin();
      work();
      t.end();
    }
    for (const GpuTimer& t : timers) seconds += t.seconds();
  } else {
    ctx.finish();
    const auto start = std::chrono::steady_clock::now();
    for (int it = 0; it < iterations; ++it) work();
    ctx.finish();
    seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  }
  seconds /= iterations;
  if (!(seconds > 0.0))
    throw std::runtime_error(what + ": the " + (timing == Timing::query ? "GL_TIME_ELAPSED queries" : "wall clock") +
                             " measured " + std::to_string(seconds) + " s per call (try --timing wall)");
  return seconds;
}

// Buffer-to-buffer copy bandwidth (bytes read + written per second) between two buffers of `bytes`, 10 copies
// after a warm-up copy: glCopyNamedBufferSubData, and a compute-shader copy (Context::copy_compute).
struct Bandwidth {
  double buffer_copy = 0.0, compute_copy = 0.0;
};
Bandwidth copy_bandwidth(const Context& ctx, Timing timing, std::size_t bytes) {
  bytes = std::max<std::size_t>(bytes / 16 * 16, 16);
  std::vector<std::uint8_t> fill(std::min<std::size_t>(bytes, std::size_t{1} << 20), 1);
  Buffer a = ctx.make_buffer(bytes), b = ctx.make_buffer(bytes);
  for (std::size_t at = 0; at < bytes; at += fill.size())
    ctx.upload(a, fill.data(), std::min(fill.size(), bytes - at), at);
  ctx.copy(a, b, bytes);  // warm-up: first touch of b
  const double s = seconds_per_call(ctx, timing, 10, "the buffer copy", [&] { ctx.copy(a, b, bytes); });
  ctx.copy_compute(a, b, bytes);  // warm-up: compiles the program
  const double c = seconds_per_call(ctx, timing, 10, "the compute copy", [&] { ctx.copy_compute(a, b, bytes); });
  return {2.0 * static_cast<double>(bytes) / s, 2.0 * static_cast<double>(bytes) / c};
}

// Largest distance between instance `instance` of `gpu` (holding that one instance) and the CPU result;
// infinity when a value is not finite. Normals: largest |n_gpu - n_cpu| where the CPU normal is finite.
struct Error {
  float position = 0.0f, normal = 0.0f;
};
Error compare(const SkinnedVertices& gpu, const SkinnedOutput& cpu, bool normals) {
  Error e;
  for (std::size_t v = 0; v < cpu.px.size(); ++v) {
    const float d = std::hypot(gpu.positions[3 * v] - cpu.px[v], gpu.positions[3 * v + 1] - cpu.py[v],
                               gpu.positions[3 * v + 2] - cpu.pz[v]);
    e.position = std::isfinite(d) ? std::max(e.position, d) : INFINITY;
    if (normals && std::isfinite(cpu.nx[v] + cpu.ny[v] + cpu.nz[v])) {
      const float dn = std::hypot(gpu.normals[3 * v] - cpu.nx[v], gpu.normals[3 * v + 1] - cpu.ny[v],
                                  gpu.normals[3 * v + 2] - cpu.nz[v]);
      e.normal = std::isfinite(dn) ? std::max(e.normal, dn) : INFINITY;
    }
  }
  return e;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  if (opt.help) {
    fmt::print("{}", kUsage);
    return 0;
  }
  Context ctx;
  const std::size_t total = opt.vertices * opt.instances;
  const std::string renderer = ctx.renderer();
  fmt::print("device: {} ({}, {}), {} vertices per instance x {} instances = {} vertices, {} bones, {} iterations{}\n",
             renderer, ctx.version(), ctx.platform(), opt.vertices, opt.instances, total, opt.bones, opt.iterations,
             opt.normals ? ", with normals" : "");
  const Timing timing = opt.timing == "query" ? Timing::query
                        : opt.timing == "wall" ? Timing::wall
                        : software_renderer(renderer) ? Timing::wall
                                                      : Timing::query;
  fmt::print("timing: {}\n", timing == Timing::query
                                 ? "GPU time, one GL_TIME_ELAPSED query around each draw / dispatch / copy"
                                 : (opt.timing == "wall" ? "wall clock between glFinish calls (--timing wall)"
                                                         : "wall clock between glFinish calls: a software renderer, "
                                                           "whose GL_TIME_ELAPSED queries do not cover the work "
                                                           "(these are CPU figures, not GPU ones)"));
  const Bandwidth measured = copy_bandwidth(ctx, timing, opt.copy_mib << 20);
  const double bandwidth = measured.compute_copy;
  fmt::print("measured compute-shader copy ({} MiB, 16 B per invocation): {:.1f} GB/s (read + write): the bound\n",
             opt.copy_mib, measured.compute_copy * 1e-9);
  fmt::print("measured buffer copy (glCopyNamedBufferSubData, {} MiB): {:.1f} GB/s (read + write)\n", opt.copy_mib,
             measured.buffer_copy * 1e-9);
  // The largest buffer the compute path binds: per-instance weights (16 B per vertex) or the output positions.
  const std::size_t largest = total * (opt.inputs == "shared" ? 12 : 16);
  const std::size_t block_limit = ctx.max_storage_block_bytes();
  if (opt.path != "vertex" && largest > block_limit)
    fmt::print("note: the compute path binds buffers of up to {} MiB, above GL_MAX_SHADER_STORAGE_BLOCK_SIZE ({} MiB); "
               "the check of the last instance shows whether the driver reads and writes past it\n",
               largest >> 20, block_limit >> 20);
  fmt::print("\n");

  // The meshes (coherent: the main rows; random: the stress rows) and 16 distinct rigid palettes cycled over
  // the instances (those of cga-cuda-bench).
  std::vector<std::pair<const char*, SkinnedMesh>> meshes;
  const int bones = static_cast<int>(opt.bones);  // <= 65536 (parse); the mesh makers reject < 4
  if (opt.mesh != "random") meshes.emplace_back("coherent", make_coherent_skinned_mesh(opt.vertices, bones, 1234u, 1.0f));
  if (opt.mesh != "coherent") meshes.emplace_back("random", make_random_skinned_mesh(opt.vertices, bones, 1234u, 1.0f));
  for (const auto& [name, mesh] : meshes) fmt::print("{} mesh: {}\n", name, describe(joint_coherence(mesh)));
  fmt::print("\n");
  constexpr std::size_t kPalettes = 16;
  const RandomPalettes crowd = make_random_palettes(static_cast<int>(opt.bones), kPalettes, 500u);
  const auto& mats = crowd.matrices;
  const auto& dqs = crowd.dual_quats;
  const auto& mots = crowd.motors;
  const float scene_size = 6.0f;  // positions in [-1, 1]^3 moved by translations in [-1, 1]^3: within a 6-wide box

  std::vector<bool> layouts;  // per_instance?
  if (opt.inputs != "per-instance") layouts.push_back(false);
  if (opt.inputs != "shared") layouts.push_back(true);
  std::vector<SkinPath> paths;
  if (opt.path != "compute") paths.push_back(SkinPath::vertex_feedback);
  if (opt.path != "vertex") paths.push_back(SkinPath::compute);

  bool all_ok = true;
  fmt::print("| mesh | method | path | inputs | B/vertex | ms | G vertices/s | bound G vertices/s | fraction | max error |\n");
  fmt::print("|---|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& [mesh_name, mesh] : meshes)
  for (const bool per_instance : layouts) {
    const double bytes_per_vertex =
        static_cast<double>(skinned_vertex_bytes(opt.normals)) +
        static_cast<double>(rest_vertex_bytes(opt.normals)) / (per_instance ? 1.0 : static_cast<double>(opt.instances));
    for (SkinningMethod method : kAllSkinningMethods) {
      Skinner skinner(ctx, method);  // one at a time: a per-instance copy of the crowd is large
      if (per_instance)
        skinner.set_mesh_per_instance(mesh, opt.instances);
      else
        skinner.set_mesh(mesh);
      const std::vector<float> palettes = cycled_packed_palettes(method, mats, dqs, mots, opt.instances);
      skinner.set_palettes(palettes, opt.bones, opt.instances);

      for (SkinPath path : paths) {
        skinner.dispatch(path, opt.normals);  // warm-up: allocates the outputs, sets the program state
        ctx.finish();
        const double seconds =
            seconds_per_call(ctx, timing, opt.iterations,
                             std::string(to_string(method)) + " " + std::string(to_string(path)),
                             [&] { skinner.dispatch(path, opt.normals); });
        const double rate = static_cast<double>(total) / seconds;
        const double bound = bandwidth / bytes_per_vertex;

        // The first and the last instance against the CPU job.
        Error worst;
        for (const std::size_t inst : {std::size_t{0}, opt.instances - 1}) {
          const std::size_t p = inst % kPalettes;
          SkinnedOutput cpu;
          SkinningJob job = make_skinning_job(method, mesh, cpu);
          job.matrices = mats[p], job.dual_quats = dqs[p], job.motors = mots[p];
          if (!job.Run()) throw std::runtime_error("the CPU reference job refused its input: " + job.ValidationError());
          const Error e = compare(skinner.read_back(inst, 1), cpu, opt.normals);
          worst.position = std::max(worst.position, e.position);
          worst.normal = std::max(worst.normal, e.normal);
        }
        const bool position_ok = worst.position <= 1e-4f * scene_size;
        const bool normal_ok = !opt.normals || worst.normal <= 1e-3f;
        all_ok = all_ok && position_ok && normal_ok;
        fmt::print("| {} | {} | {} | {} | {:.1f} | {:.3f} | {:.3f} | {:.2f} | {:.0f} % | {:.2e}{}{} |\n", mesh_name, to_string(method),
                   to_string(path), per_instance ? "per instance" : "shared rest mesh",
                   bytes_per_vertex, seconds * 1e3, rate * 1e-9, bound * 1e-9, 100.0 * rate / bound, worst.position,
                   position_ok ? "" : " FAIL",
                   !opt.normals ? "" : fmt::format(" (normals {:.1e}{})", worst.normal, normal_ok ? "" : " FAIL"));
      }
    }
  }
  fmt::print(
      "\nB/vertex: bytes streamed per skinned vertex, palettes not counted. shared rest mesh: the outputs ({} B) plus "
      "the one rest mesh ({} B per vertex) read once per dispatch, i.e. / {} instances; per instance: each instance "
      "reads its own rest vertices, {} B in + {} B out. bound = compute-shader copy bandwidth / B/vertex; ms = "
      "{} of one draw / dispatch, mean of {}; max error = largest distance to the CPU "
      "SkinningJob over the first and last instance (tolerance 1e-4 x scene size {}).\n",
      skinned_vertex_bytes(opt.normals), rest_vertex_bytes(opt.normals), opt.instances, rest_vertex_bytes(opt.normals),
      skinned_vertex_bytes(opt.normals), timing == Timing::query ? "GPU time (GL_TIME_ELAPSED)" : "wall-clock time",
      opt.iterations, scene_size);
  if (!all_ok) {
    fmt::print(stderr, "cga-gl-bench: some results differ from the CPU SkinningJob by more than 1e-4 of the scene size\n");
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "cga-gl-bench: {}\n", e.what());
  return 2;
}
