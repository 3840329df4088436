// cga-draw-bench: the draw path. N characters (one coherent skinned mesh, make_coherent_skinned_mesh, 64
// bones, a palette each cycled from 16 random rigid poses) drawn with the skinning vertex shader into an
// offscreen framebuffer, one instanced depth-tested draw per frame (cga::gpu::CrowdDraw), per method: ms per
// frame (clear + draw) and skinned vertices per second. Timing: GL_TIME_ELAPSED per frame, or on Mesa's
// software renderers the wall clock between glFinish calls (their queries do not cover the work). Check:
// the first min(N, 16) characters drawn the same way and skinned on the CPU (SkinningJob, render_meshes,
// same camera) must give the same picture: at most 1 % of the covered pixels may differ by more than 24/255
// in a channel. Exit status 1 when a picture differs, 2 on an error.
//
//   cga-draw-bench [--vertices N] [--characters C] [--bones B] [--frames K] [--width W] [--height H]
//                  [--method METHOD|all] [--timing auto|query|wall] [--pictures DIR]
// (METHOD: a name of the method table, runtime/skinning_methods.txt; --help lists them.)
#include <fmt/core.h>

#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "cga/gpu/context.hpp"
#include "cga/gpu/draw.hpp"
#include "cga/runtime/packed_palette.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/crowd_meshes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

using namespace cga;
using namespace cga::gpu;

namespace {

struct Options {
  std::size_t vertices = 16384, characters = 1024, bones = 64;
  int frames = 10, width = 1920, height = 1080;
  std::string method = "all", timing = "auto", pictures;
};

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + std::string(a));
      return argv[++i];
    };
    auto number = [&](long long lo, long long hi) {
      const std::string text = value();
      std::size_t used = 0;
      long long v = 0;
      try {
        v = std::stoll(text, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used != text.size() || v < lo || v > hi)
        throw std::invalid_argument(std::string(a) + " needs an integer in [" + std::to_string(lo) + ", " +
                                    std::to_string(hi) + "], not '" + text + "'");
      return v;
    };
    if (a == "--vertices") o.vertices = static_cast<std::size_t>(number(16, 1 << 24));
    else if (a == "--characters") o.characters = static_cast<std::size_t>(number(1, 1 << 20));
    else if (a == "--bones") o.bones = static_cast<std::size_t>(number(4, 1024));
    else if (a == "--frames") o.frames = static_cast<int>(number(1, 1 << 20));
    else if (a == "--width") o.width = static_cast<int>(number(1, 8192));
    else if (a == "--height") o.height = static_cast<int>(number(1, 8192));
    else if (a == "--method") o.method = value();
    else if (a == "--timing") o.timing = value();
    else if (a == "--pictures") o.pictures = value();
    else if (a == "--help" || a == "-h") {
      // The methods from the table, so that the help lists every one there is.
      std::string methods;
      for (const SkinningMethodInfo& m : kSkinningMethods) methods += std::string(m.name) + "|";
      fmt::print("usage: cga-draw-bench [--vertices N] [--characters C] [--bones B] [--frames K] [--width W] "
                 "[--height H]\n                      [--method {}all] "
                 "[--timing auto|query|wall] [--pictures DIR]\n", methods);
      std::exit(0);
    } else {
      throw std::invalid_argument("unknown option " + std::string(a) + " (see --help)");
    }
  }
  if (o.timing != "auto" && o.timing != "query" && o.timing != "wall")
    throw std::invalid_argument("--timing must be auto, query or wall");
  bool known = o.method == "all";
  std::string names;
  for (SkinningMethod m : kAllSkinningMethods) {
    known = known || o.method == to_string(m);
    names += std::string(to_string(m)) + ", ";
  }
  if (!known) throw std::invalid_argument("--method must be " + names + "or all");
  return o;
}

CrowdGrid grid_of(std::size_t characters) {
  CrowdGrid g;
  g.characters = characters;
  g.columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(characters) * 16.0 / 9.0)));
  return g;
}

}  // namespace

int main(int argc, char** argv) try {
  const Options opt = parse(argc, argv);
  Context ctx;
  const std::string renderer = ctx.renderer();
  const bool software = renderer.find("llvmpipe") != std::string::npos || renderer.find("softpipe") != std::string::npos;
  const bool query = opt.timing == "query" || (opt.timing == "auto" && !software);
  const SkinnedMesh mesh = make_coherent_skinned_mesh(opt.vertices, static_cast<int>(opt.bones), 1234u, 1.0f);
  fmt::print("device: {} ({}, {}), {} characters x {} vertices ({} triangles) = {} vertices per frame, {} bones, "
             "{}x{} RGBA8 + depth 24, {} frames\n",
             renderer, ctx.version(), ctx.platform(), opt.characters, mesh.vertex_count(), mesh.indices.size() / 3,
             opt.characters * mesh.vertex_count(), opt.bones, opt.width, opt.height, opt.frames);
  fmt::print("timing: {}\n", query ? "GPU time, one GL_TIME_ELAPSED query around each frame (clear + draw)"
                                   : "wall clock between glFinish calls (a software renderer: CPU figures)");
  fmt::print("mesh: {}\n\n", describe(joint_coherence(mesh)));

  constexpr std::size_t kPoses = 16;
  const RandomPalettes poses = make_random_palettes(static_cast<int>(opt.bones), kPoses, 500u);
  const std::size_t checked = std::min<std::size_t>(opt.characters, 16);
  bool all_ok = true;
  fmt::print("| method | characters | vertices/frame | ms/frame | G vertices/s | picture vs CPU skinning |\n");
  fmt::print("|---|---|---|---|---|---|\n");
  for (SkinningMethod method : kAllSkinningMethods) {
    if (opt.method != "all" && opt.method != to_string(method)) continue;
    double seconds = 0.0;
    {
      CrowdDraw crowd(ctx, method, mesh, grid_of(opt.characters), opt.width, opt.height);
      crowd.set_palettes(cycled_packed_palettes(method, poses.matrices, poses.dual_quats, poses.motors, opt.characters),
                         opt.bones);
      crowd.draw();  // warm-up: program state, first touch of the buffers
      ctx.finish();
      if (query) {
        std::vector<GpuTimer> timers;
        for (int f = 0; f < opt.frames; ++f) timers.emplace_back(ctx);
        for (GpuTimer& t : timers) t.begin(), crowd.draw(), t.end();
        for (const GpuTimer& t : timers) seconds += t.seconds();
      } else {
        const auto start = std::chrono::steady_clock::now();
        for (int f = 0; f < opt.frames; ++f) crowd.draw();
        ctx.finish();
        seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      }
      seconds /= opt.frames;
      if (!opt.pictures.empty())
        write_png(crowd.read_picture(), opt.pictures + "/draw-" + std::string(to_string(method)) + ".png");
    }
    // The check: a few characters, GPU-skinned while drawing vs CPU-skinned, same camera and picture size.
    const CrowdGrid small = grid_of(checked);
    CrowdDraw check(ctx, method, mesh, small, 384, 256);
    check.set_palettes(cycled_packed_palettes(method, poses.matrices, poses.dual_quats, poses.motors, checked),
                       opt.bones);
    check.draw();
    const Image gpu = check.read_picture();
    std::vector<CharacterPalette> palettes;
    for (std::size_t i = 0; i < checked; ++i)
      palettes.push_back({poses.matrices[i % kPoses], poses.dual_quats[i % kPoses], poses.motors[i % kPoses]});
    const Image cpu = reference_picture(ctx, method, mesh, small, palettes, 384, 256);
    const double differ = picture_difference(gpu, cpu);
    const bool ok = differ <= 0.01 && gpu.count_pixels_unlike(kClearColour) > 0;
    all_ok = all_ok && ok;
    const double vertices = static_cast<double>(opt.characters * mesh.vertex_count());
    fmt::print("| {} | {} | {} | {:.3f} | {:.3f} | {:.2f} % of {} px differ{} |\n", to_string(method), opt.characters,
               opt.characters * mesh.vertex_count(), seconds * 1e3, vertices / seconds * 1e-9, 100.0 * differ,
               gpu.count_pixels_unlike(kClearColour), ok ? "" : " FAIL");
  }
  fmt::print("\nms/frame: clear + one instanced draw of every character, mean of {}; G vertices/s: skinned vertices "
             "(characters x mesh vertices) per second; check: the first {} characters at 384x256 against the same "
             "characters skinned by the CPU SkinningJob (pixels off by > 24/255, at most 1 %).\n",
             opt.frames, checked);
  if (!all_ok) {
    fmt::print(stderr, "cga-draw-bench: a picture differs from the CPU-skinned one\n");
    return 1;
  }
  return 0;
} catch (const std::exception& e) {
  fmt::print(stderr, "cga-draw-bench: {}\n", e.what());
  return 2;
}
