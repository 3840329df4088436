// cga-demo (README command 1): the whole runtime on a real character. Loads a skinned, animated file,
// cross-fades two clips with every interpolation mode (timing one pose: sample two clips + blend + hierarchy +
// palette), skins the meshes with every method on the CPU (vertices/s, and how far the methods are apart
// relative to the character's size), twists the two-bone strip (the candy-wrapper test), and draws PNG
// pictures of both. See docs/demo.md for what each number means.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cga/gpu/context.hpp"
#include "cga/gpu/render.hpp"
#include "cga/gpu/skinning.hpp"
#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/io/loader.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "cga/testing/twist_strip.hpp"
#include "ik_demo.hpp"
#include "options.hpp"
#include "pictures.hpp"
#include "web.hpp"

using namespace cga;
using Clock = std::chrono::steady_clock;

namespace {

// Stage lines on stderr with the elapsed time, so that a slow step is never silent.
class Progress {
 public:
  void stage(const std::string& what) {
    std::fflush(stdout);  // keep the table and the stage lines in order on a terminal
    fmt::print(stderr, "[{:5.1f} s] {}\n", seconds(), what);
    std::fflush(stderr);
  }
  double seconds() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

 private:
  Clock::time_point start_ = Clock::now();
};

// What the cross-fade plays: clip a over [a0, a1] fading into clip b over [b0, b1].
struct Fade {
  const Clip* a = nullptr;
  const Clip* b = nullptr;
  float a0 = 0, a1 = 0, b0 = 0, b1 = 0;
  std::string description;
  // Times and the weight of b at step u in [0, 1].
  float time_a(float u) const { return a0 + u * (a1 - a0); }
  float time_b(float u) const { return b0 + u * (b1 - b0); }
};

// A clip that holds every joint at its rest transform (one key each), for files without animation.
Clip rest_clip(const Skeleton& sk) {
  Clip c;
  c.name = "(rest pose)";
  c.tracks.resize(sk.joint_count());
  for (int j = 0; j < sk.joint_count(); ++j) {
    const Transform& x = sk.rest_local[j];
    c.tracks[j].translations.push_back({0.0f, x.translation});
    c.tracks[j].rotations.push_back({0.0f, x.rotation, rotor_from_quat(x.rotation)});
    c.tracks[j].scales.push_back({0.0f, x.scale});
  }
  build_joint_keys(c);
  return c;
}

std::string clip_list(const Character& ch) {
  std::string s;
  for (const Clip& c : ch.clips) s += (s.empty() ? "'" : ", '") + c.name + "'";
  return s.empty() ? "none" : s;
}

Fade choose_fade(const Character& ch, const std::vector<std::string>& names, const Clip* fallback) {
  auto find = [&](const std::string& name) {
    const Clip* c = ch.find_clip(name);
    if (!c) throw LoadError(fmt::format("{}: no clip named '{}' (clips: {})", ch.path, name, clip_list(ch)));
    return c;
  };
  Fade f;
  if (names.size() == 2) {
    f.a = find(names[0]), f.b = find(names[1]);
  } else if (names.size() == 1) {
    f.a = find(names[0]);
    for (const Clip& c : ch.clips)
      if (&c != f.a) f.b = f.b ? f.b : &c;
  } else if (ch.clips.size() >= 2) {
    f.a = &ch.clips[0], f.b = &ch.clips[1];
  } else if (ch.clips.size() == 1) {
    f.a = &ch.clips[0];
  } else {
    f.a = fallback;
  }
  if (f.b && f.b != f.a) {
    f.a0 = 0, f.a1 = f.a->duration, f.b0 = 0, f.b1 = f.b->duration;
    f.description = fmt::format("clip '{}' (0..{:.3g} s) fading into clip '{}' (0..{:.3g} s)", f.a->name,
                                f.a->duration, f.b->name, f.b->duration);
  } else {
    // One clip: its first half fades into its second half.
    f.b = f.a;
    const float d = f.a->duration;
    f.a0 = 0, f.a1 = 0.5f * d, f.b0 = 0.5f * d, f.b1 = d;
    f.description = fmt::format("clip '{}': first half (0..{:.3g} s) fading into second half ({:.3g}..{:.3g} s)",
                                f.a->name, 0.5f * d, 0.5f * d, d);
  }
  return f;
}

// One mode's pose pipeline with its buffers: two samples, the cross-fade, the hierarchy, a palette per mesh.
struct PosePipeline {
  baseline::PoseMode mode;
  const Skeleton* skeleton;
  const std::vector<SkinnedMesh>* meshes;
  const std::vector<baseline::InverseBind>* inverse_binds;
  baseline::PoseBuffer a, b, blended, model;
  std::vector<MotorPalette> motor_palettes;
  std::vector<MatrixPalette> matrix_palettes;
  std::vector<DualQuatPalette> dq_palettes;

  PosePipeline(baseline::PoseMode m, const Skeleton& sk, const std::vector<SkinnedMesh>& ms,
               const std::vector<baseline::InverseBind>& ib)
      : mode(m), skeleton(&sk), meshes(&ms), inverse_binds(&ib), a(sk.joint_count()), b(sk.joint_count()),
        blended(sk.joint_count()), model(sk.joint_count()) {
    for (const SkinnedMesh& mesh : ms) {
      motor_palettes.emplace_back(mesh.joint_remap.size());
      matrix_palettes.emplace_back(mesh.joint_remap.size());
      dq_palettes.emplace_back(mesh.joint_remap.size());
    }
  }

  // The model pose and the palettes at fade step u (weight u on clip b), by the jobs of the mode's
  // representation: the runtime's motor jobs, or the GLM baselines (cga/baselines/pose_jobs.hpp).
  void run(const Fade& f, float u) {
    using namespace baseline;
    const float ta = f.time_a(u), tb = f.time_b(u);
    bool ok = true;
    if (mode == PoseMode::glm_matrix) {
      const TransformLayer layers[2] = {{1.0f - u, a.transforms}, {u, b.transforms}};
      ok = TransformSamplingJob{f.a, ta, a.transforms}.Run() && TransformSamplingJob{f.b, tb, b.transforms}.Run() &&
           TransformBlendingJob{layers, blended.transforms}.Run() &&
           MatrixLocalToModelJob{skeleton, blended.transforms, model.matrices}.Run();
      for (std::size_t m = 0; ok && m < meshes->size(); ++m)
        ok = MatrixPaletteJob{(*meshes)[m].joint_remap, (*inverse_binds)[m].matrices, model.matrices,
                              matrix_palettes[m]}.Run();
    } else if (mode == PoseMode::glm_dualquat) {
      const DualQuatLayer layers[2] = {{1.0f - u, a.dual_quats, a.scales}, {u, b.dual_quats, b.scales}};
      ok = DualQuatSamplingJob{f.a, ta, a.dual_quats, a.scales}.Run() &&
           DualQuatSamplingJob{f.b, tb, b.dual_quats, b.scales}.Run() &&
           DualQuatBlendingJob{layers, blended.dual_quats, blended.scales}.Run() &&
           DualQuatLocalToModelJob{skeleton, blended.dual_quats, blended.scales, model.dual_quats, model.scales}.Run();
      for (std::size_t m = 0; ok && m < meshes->size(); ++m)
        ok = DualQuatPaletteJob{(*meshes)[m].joint_remap, (*inverse_binds)[m].dual_quats, model.dual_quats,
                                model.scales, dq_palettes[m]}.Run();
    } else {
      const Interpolation motor_mode = to_interpolation(mode);
      const BlendLayer layers[2] = {{1.0f - u, a.motors}, {u, b.motors}};
      ok = SamplingJob{f.a, ta, motor_mode, a.motors}.Run() && SamplingJob{f.b, tb, motor_mode, b.motors}.Run() &&
           BlendingJob{motor_mode, layers, blended.motors}.Run() && LocalToModelJob{skeleton, blended.motors, model.motors}.Run();
      for (std::size_t m = 0; ok && m < meshes->size(); ++m)
        ok = SkinningPaletteJob{(*meshes)[m].joint_remap, (*inverse_binds)[m].motors, model.motors,
                                motor_palettes[m]}.Run();
    }
    if (!ok)
      throw std::runtime_error(fmt::format("the {} pose pipeline refused its input (clips '{}' at {} s, '{}' at {} s)",
                                           to_string(mode), f.a->name, ta, f.b->name, tb));
  }

  glm::vec3 joint_position(int j) const {
    switch (mode) {
      case baseline::PoseMode::glm_matrix: return glm::vec3(model.matrices[j][3]);
      case baseline::PoseMode::glm_dualquat: return baseline::dual_quat_translation(model.dual_quats[j]);
      default: return motor_transform_point(model.motors[j], glm::vec3(0.0f));
    }
  }
};

// Every method's palette for one mesh, all from the same motor palette, so that method deviations measure the
// skinning methods and not the interpolation: lbs/cga-points get the motor's point-transform matrix, dqs the
// rigid part of its transform (a dual quaternion has no scale: `scaled` counts the entries that lose one).
struct MethodPalettes {
  MotorPalette motors;
  MatrixPalette matrices;
  DualQuatPalette dual_quats;
  int scaled = 0;
};

MethodPalettes palettes_from_motors(const MotorPalette& motors) {
  MethodPalettes p;
  p.motors = motors;
  for (const Motor& m : motors) {
    p.matrices.push_back(motor_matrix(m));
    Transform x = motor_to_transform(m);
    if (std::abs(x.scale - 1.0f) > 1e-4f) ++p.scaled;
    x.scale = 1.0f;
    p.dual_quats.push_back(to_dual_quat(x));
  }
  return p;
}

SkinningJob job_for(SkinningMethod method, const SkinnedMesh& mesh, const MethodPalettes& pal, SkinnedOutput& out) {
  SkinningJob job = make_skinning_job(method, mesh, out);
  job.motors = pal.motors, job.matrices = pal.matrices, job.dual_quats = pal.dual_quats;
  return job;
}

void run_job(const SkinningJob& job, const std::string& what) {
  if (!job.Run()) throw std::runtime_error(fmt::format("skinning {} failed: {}", what, job.ValidationError()));
}

float max_distance(const SkinnedOutput& x, const SkinnedOutput& y) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < x.px.size(); ++i)
    worst = std::max(worst, glm::length(glm::vec3(x.px[i] - y.px[i], x.py[i] - y.py[i], x.pz[i] - y.pz[i])));
  return worst;
}

// Repeats `body` (one batch of work) until at least `min_seconds` have passed; returns seconds per batch.
template <class F>
double time_batches(F&& body, double min_seconds) {
  body();  // warm caches and branch predictors
  int batches = 0;
  const auto start = Clock::now();
  double elapsed = 0.0;
  do {
    body();
    ++batches;
    elapsed = std::chrono::duration<double>(Clock::now() - start).count();
  } while (elapsed < min_seconds);
  return elapsed / batches;
}

// All skinned vertices of all meshes of one method, concatenated (for framing and drawing).
struct PosedCharacter {
  std::vector<SkinnedOutput> meshes;
};

// Deviation between methods, each through its own pipeline (lbs <- GLM matrices, dqs <- GLM dual quaternions,
// cga-points / cga-motors <- generated motor kernels), at key frames of the first clip, where every mode
// reproduces the keys: what differs is only the representation and the skinning method.
void key_frame_deviations(const Character& ch, const Fade& fade, const std::vector<SkinningMethod>& methods,
                          const std::vector<baseline::InverseBind>& inverse_binds, float size) {
  const Clip& clip = *fade.a;
  std::vector<float> times;
  for (const JointKeys& k : clip.keys)
    if (k.size() > times.size()) times = k.times;
  if (times.size() > 12) {  // at most 12 key frames, spread over the clip
    std::vector<float> some;
    for (int i = 0; i < 12; ++i) some.push_back(times[i * (times.size() - 1) / 11]);
    times = some;
  }
  PosePipeline mat(baseline::PoseMode::glm_matrix, ch.skeleton, ch.meshes, inverse_binds);
  PosePipeline dq(baseline::PoseMode::glm_dualquat, ch.skeleton, ch.meshes, inverse_binds);
  PosePipeline mot(baseline::PoseMode::nlerp, ch.skeleton, ch.meshes, inverse_binds);
  // worst[a][b]: the largest distance between methods[a] and methods[b] (b < a) over the key frames.
  std::vector<std::vector<float>> worst(methods.size(), std::vector<float>(methods.size(), 0.0f));
  for (float t : times) {
    Fade at = fade;
    at.b = at.a, at.a0 = at.a1 = at.b0 = at.b1 = t;
    mat.run(at, 0.0f), dq.run(at, 0.0f), mot.run(at, 0.0f);
    for (std::size_t m = 0; m < ch.meshes.size(); ++m) {
      MethodPalettes pal;
      pal.matrices = mat.matrix_palettes[m], pal.dual_quats = dq.dq_palettes[m];
      pal.motors = mot.motor_palettes[m];
      std::vector<SkinnedOutput> out(methods.size());
      for (std::size_t k = 0; k < methods.size(); ++k)
        run_job(job_for(methods[k], ch.meshes[m], pal, out[k]), std::string(to_string(methods[k])));
      for (std::size_t a = 0; a < methods.size(); ++a)
        for (std::size_t b = 0; b < a; ++b) worst[a][b] = std::max(worst[a][b], max_distance(out[a], out[b]));
    }
  }
  fmt::print("  max vertex distance / size over {} key frames of '{}', each method through its own pipeline:\n",
             times.size(), clip.name);
  const bool approximated = std::any_of(ch.warnings.begin(), ch.warnings.end(), [](const std::string& w) {
    return w.find("not a similarity") != std::string::npos || w.find("non-uniform") != std::string::npos;
  });
  if (approximated)
    fmt::print("    (the loader approximated non-similarity transforms for motors and dual quaternions, see the "
               "warnings; lbs uses the file's exact matrices, so the cga methods differ from it here)\n");
  // cga-points is lbs in other maths (rounding only), cga-motors is dqs for rigid bones (docs/skinning.md).
  fmt::print("    {:<11}", "");
  for (std::size_t b = 0; b + 1 < methods.size(); ++b) fmt::print(" {:<11}", to_string(methods[b]));
  fmt::print("\n");
  for (std::size_t a = 1; a < methods.size(); ++a) {
    fmt::print("    {:<11}", to_string(methods[a]));
    for (std::size_t b = 0; b < a; ++b) fmt::print(" {:<11.3g}", worst[a][b] / size);
    fmt::print("\n");
  }
}

int run(const demo::Options& opt) {
  Progress progress;
  const std::vector<baseline::PoseMode>& modes = opt.modes;
  const std::vector<SkinningMethod>& methods = opt.methods;

  progress.stage("loading " + opt.model);
  const Character ch = load_character(opt.model);
  const Skeleton& sk = ch.skeleton;
  if (sk.joint_count() == 0) throw LoadError(opt.model + ": no skeleton");
  std::size_t vertices = 0;
  for (const SkinnedMesh& m : ch.meshes) vertices += m.vertex_count();
  const float size = character_size(ch);
  if (!(size > 0.0f) || !std::isfinite(size))
    throw LoadError(fmt::format("{}: the character has no extent (size {})", opt.model, size));
  fmt::print("model     {}\n", opt.model);
  fmt::print("skeleton  {} joints; {} skinned meshes, {} vertices; clips: {}; size {:.4g} units\n", sk.joint_count(),
             ch.meshes.size(), vertices, clip_list(ch), size);
  for (std::size_t i = 0; i < ch.warnings.size() && i < 3; ++i) fmt::print("warning   {}\n", ch.warnings[i]);
  if (ch.warnings.size() > 3) fmt::print("warning   ... and {} more loader warnings\n", ch.warnings.size() - 3);

  const Clip rest = rest_clip(sk);
  if (ch.clips.empty()) fmt::print("note      the file has no animation; the demo poses the rest pose\n");
  const Fade fade = choose_fade(ch, opt.clips, &rest);
  fmt::print("fade      {}\n\n", fade.description);

  std::vector<baseline::InverseBind> inverse_binds;
  for (const SkinnedMesh& m : ch.meshes) inverse_binds.push_back(baseline::make_inverse_bind(m));

  // ---- poses: time per pose and joint deviation from the GLM matrix baseline, per mode
  progress.stage(fmt::format("posing {} frames of the cross-fade in {} modes", opt.frames, modes.size()));
  const int frames = opt.frames;
  auto step = [&](int f) { return float(f) / float(frames - 1); };
  std::vector<std::vector<glm::vec3>> baseline(frames, std::vector<glm::vec3>(sk.joint_count()));
  {
    PosePipeline ref(baseline::PoseMode::glm_matrix, sk, ch.meshes, inverse_binds);
    for (int f = 0; f < frames; ++f) {
      ref.run(fade, step(f));
      for (int j = 0; j < sk.joint_count(); ++j) baseline[f][j] = ref.joint_position(j);
    }
  }
  fmt::print("pose: sample 2 clips + cross-fade + hierarchy ({} joints) + palettes ({} meshes), one core\n",
             sk.joint_count(), ch.meshes.size());
  fmt::print("  {:<13} {:>10}   {}\n", "mode", "us/pose", "max joint distance to glm-matrix / size");
  for (baseline::PoseMode mode : modes) {
    PosePipeline p(mode, sk, ch.meshes, inverse_binds);
    float worst = 0.0f;
    for (int f = 0; f < frames; ++f) {
      p.run(fade, step(f));
      for (int j = 0; j < sk.joint_count(); ++j) worst = std::max(worst, glm::length(p.joint_position(j) - baseline[f][j]));
    }
    const double per_batch = time_batches([&] { for (int f = 0; f < frames; ++f) p.run(fade, step(f)); }, 0.05);
    fmt::print("  {:<13} {:>10.2f}   {:.3g}\n", to_string(mode), 1e6 * per_batch / frames, worst / size);
  }
  fmt::print("\n");

  // ---- skinning: every method on the same pose (middle of the fade), speed and deviations
  std::map<SkinningMethod, PosedCharacter> posed;
  std::vector<MethodPalettes> palettes;  // the mid-fade pose's, per mesh (the GL path skins it again below)
  if (ch.meshes.empty()) {
    fmt::print("skinning: the file has no skinned mesh, nothing to skin\n\n");
  } else {
    const baseline::PoseMode pose_mode = baseline::PoseMode::screw;
    progress.stage(fmt::format("skinning {} vertices with {} methods", vertices, methods.size()));
    PosePipeline p(pose_mode, sk, ch.meshes, inverse_binds);
    int scaled = 0;
    p.run(fade, 0.5f);
    for (const MotorPalette& mp : p.motor_palettes) palettes.push_back(palettes_from_motors(mp));
    for (const MethodPalettes& mp : palettes) scaled += mp.scaled;
    const bool normals = std::any_of(ch.meshes.begin(), ch.meshes.end(), [](const SkinnedMesh& m) { return m.has_normals(); });
    fmt::print("skinning: {} vertices{}, pose = middle of the fade ({}), one core\n", vertices,
               normals ? " with normals" : "", to_string(pose_mode));
    fmt::print("  {:<11} {:>12}\n", "method", "Mvertices/s");
    for (SkinningMethod method : methods) {
      PosedCharacter& pc = posed[method];
      pc.meshes.resize(ch.meshes.size());
      std::vector<SkinningJob> jobs;
      for (std::size_t m = 0; m < ch.meshes.size(); ++m)
        jobs.push_back(job_for(method, ch.meshes[m], palettes[m], pc.meshes[m]));
      const std::string name(to_string(method));
      const double seconds = time_batches([&] { for (const SkinningJob& j : jobs) run_job(j, name); }, 0.1);
      fmt::print("  {:<11} {:>12.1f}\n", name, 1e-6 * double(vertices) / seconds);
    }
    fmt::print("\n");
    key_frame_deviations(ch, fade, methods, inverse_binds, size);
    // On the blended pose itself: how much each method changes the skin against the first (not an error;
    // lbs loses volume).
    for (std::size_t k = 1; k < methods.size(); ++k) {
      float worst = 0.0f;
      for (std::size_t m = 0; m < ch.meshes.size(); ++m)
        worst = std::max(worst, max_distance(posed[methods[k]].meshes[m], posed[methods[0]].meshes[m]));
      fmt::print("  mid-fade pose: {} vs {} {:.3g} of the size\n", to_string(methods[k]), to_string(methods[0]),
                 worst / size);
    }
    if (scaled)
      fmt::print("  note: {} palette entries carry a scale; dqs skins their rigid part only\n", scaled);
    fmt::print("\n");
  }

  // ---- the twist strip: joint 1 turned 180 degrees, the middle cross-section's radius per method
  const TwistCylinder cyl = make_twist_cylinder();
  const std::vector<Transform> twist = twist_cylinder_skinning_transforms(cyl.spec, std::numbers::pi_v<float>);
  MethodPalettes twist_pal;
  for (const Transform& x : twist) {
    twist_pal.matrices.push_back(to_skinning_matrix(x));
    twist_pal.dual_quats.push_back(to_dual_quat(x));
    twist_pal.motors.push_back(motor_from_transform(x));
  }
  std::map<SkinningMethod, SkinnedOutput> twisted;
  fmt::print("twist strip: joint 1 of a two-bone cylinder turned 180 degrees (candy-wrapper test)\n");
  fmt::print("  {:<11} {:>28}\n", "method", "middle ring radius / rest");
  for (SkinningMethod method : methods) {
    SkinnedOutput& out = twisted[method];
    run_job(job_for(method, cyl.mesh, twist_pal, out), std::string(to_string(method)) + " (twist strip)");
    double radius = 0.0;
    for (std::uint32_t v : cyl.middle_ring) radius += std::hypot(out.px[v], out.py[v]);
    radius /= double(cyl.middle_ring.size());
    fmt::print("  {:<11} {:>28.3f}\n", to_string(method), radius / cyl.spec.radius);
  }
  fmt::print("\n");

  // ---- pictures (pictures.cpp): the mid-fade pose and the strip, here from the CPU jobs, below from the GL path
  demo::PictureSet pictures;
  pictures.character = &ch;
  pictures.pose = fmt::format("pose: the middle of the fade (screw mode, weight 0.5): clip '{}' at {:.3g} s, clip '{}' at {:.3g} s",
                              fade.a->name, fade.time_a(0.5f), fade.b->name, fade.time_b(0.5f));
  for (const auto& [method, pc] : posed) pictures.cpu[method] = pc.meshes;
  pictures.gpu_palette = [&](SkinningMethod method, std::size_t m) {
    std::vector<float> packed;
    gpu::append_palette(method, palettes[m].matrices, palettes[m].dual_quats, palettes[m].motors, packed);
    return packed;
  };
  pictures.cylinder = &cyl, pictures.twist_angle = std::numbers::pi_v<float>, pictures.twisted = twisted;
  if (opt.pictures) {
    progress.stage("drawing pictures into " + opt.out_dir);
    std::error_code ec;
    std::filesystem::create_directories(opt.out_dir, ec);
    if (ec) throw std::runtime_error(fmt::format("cannot create folder {}: {}", opt.out_dir, ec.message()));
    fmt::print("pictures (CPU rasterizer):");
    for (const std::string& w : demo::write_cpu_pictures(pictures, opt.out_dir)) fmt::print(" {}", w);
    fmt::print("\n");
  }
  // ---- IK: the right hand reaches a target, then the spine and the arm reach the left knee (ik_demo.cpp)
  demo::ik_hand_reach(ch, opt.pictures ? opt.out_dir : std::string());
  demo::ik_chain_reach(ch, opt.pictures ? opt.out_dir : std::string());
  // ---- the web page (--web DIR): the runtime's palettes for every motor mode on a grid of clip times and
  // fade weights, skinned in the browser (web.cpp, docs/web.md)
  if (!opt.web_dir.empty() && ch.meshes.empty()) {
    fmt::print("web page  skipped: the file has no skinned mesh to show\n\n");
  } else if (!opt.web_dir.empty()) {
    progress.stage("writing the web page into " + opt.web_dir);
    demo::WebInput web;
    web.character = &ch, web.model = std::filesystem::path(opt.model).filename().string(), web.size = size;
    web.fade_description = fade.description;
    web.time_label = [&](float u) {
      return fmt::format("a {:.2f} s, b {:.2f} s", fade.time_a(u), fade.time_b(u));
    };
    web.modes = {Interpolation::paper, Interpolation::nlerp, Interpolation::screw};
    std::map<Interpolation, PosePipeline> pipelines;
    for (Interpolation m : web.modes) pipelines.emplace(m, PosePipeline(baseline::to_pose_mode(m), sk, ch.meshes, inverse_binds));
    web.pose = [&](Interpolation m, float u, float w) {
      // The clip times of step u held fixed, so that the fade's step w only sets the weight.
      Fade at = fade;
      at.a0 = at.a1 = fade.time_a(u), at.b0 = at.b1 = fade.time_b(u);
      PosePipeline& p = pipelines.at(m);
      p.run(at, w);
      return p.motor_palettes;
    };
    fmt::print("web page  {}\n  open it in a browser (file:// is fine; WebGPU, else WebGL 2); add #selftest to check it\n\n",
               demo::write_web_page(web, opt.web_dir));
  }

  // ---- the GPU path: the mid-fade pose skinned again by the GLSL shaders built from the generated kernels
  // (vertex shader + transform feedback, and compute), checked against the CPU jobs; then the pictures,
  // drawn by OpenGL (headless EGL: llvmpipe without a GPU).
  progress.stage("GPU: skinning and drawing with OpenGL");
  try {
    const gpu::Context context;
    fmt::print("GPU       {} ({}, {})\n", context.renderer(), context.version(), context.platform());
    if (!posed.empty()) {
      fmt::print("GPU skinning of the mid-fade pose: max vertex distance to the CPU job / size (ms to upload, skin\n"
                 "and read back every mesh; on llvmpipe the GPU is the CPU: a correctness check, not a speed figure)\n");
      fmt::print("  {:<11} {:>26} {:>26}\n", "method", to_string(gpu::SkinPath::vertex_feedback),
                 to_string(gpu::SkinPath::compute));
      for (const auto& [method, pc] : posed) {
        std::string cells;
        for (const gpu::SkinPath path : {gpu::SkinPath::vertex_feedback, gpu::SkinPath::compute}) {
          gpu::Skinner skinner(context, method);
          float worst = 0.0f;
          const auto start = std::chrono::steady_clock::now();
          for (std::size_t m = 0; m < ch.meshes.size(); ++m) {
            const MethodPalettes& pal = palettes[m];
            std::vector<float> packed;
            gpu::append_palette(method, pal.matrices, pal.dual_quats, pal.motors, packed);
            skinner.set_mesh(ch.meshes[m]);
            const gpu::SkinnedVertices got =
                skinner.run(path, packed, packed.size() / gpu::palette_floats(method), 1, false);
            const SkinnedOutput& cpu = pc.meshes[m];
            for (std::size_t v = 0; v < cpu.px.size(); ++v)
              worst = std::max(worst, glm::length(glm::vec3(got.positions[3 * v] - cpu.px[v],
                                                            got.positions[3 * v + 1] - cpu.py[v],
                                                            got.positions[3 * v + 2] - cpu.pz[v])));
          }
          const double ms = 1e3 * std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
          cells += fmt::format(" {:>26}", fmt::format("{:.2g} ({:.1f} ms)", worst / size, ms));
        }
        fmt::print("  {:<11}{}\n", to_string(method), cells);
      }
    }
    if (opt.pictures && !ch.meshes.empty()) {
      const std::vector<std::string> paths = demo::write_gpu_pictures(context, pictures, opt.out_dir);
      fmt::print("pictures (GPU, the same pose and framing as the CPU's): {}\n", fmt::join(paths, " "));
    }
  } catch (const gpu::Unavailable& e) {
    fmt::print("GPU       no OpenGL 4.5 context, GPU path skipped: {}\n", e.what());
  }
  progress.stage("done");
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string default_model = CGA_DEMO_DEFAULT_MODEL;
  demo::Options opt;
  try {
    opt = demo::parse_options(argc, argv, default_model);
  } catch (const demo::UsageError& e) {
    std::fprintf(stderr, "cga-demo: %s\nrun 'cga-demo --help' for the options\n", e.what());
    return 2;
  }
  if (opt.help) {
    std::fputs(demo::usage_text(default_model).c_str(), stdout);
    return 0;
  }
  try {
    return run(opt);
  } catch (const std::exception& e) {
    std::fflush(stdout);
    std::fprintf(stderr, "cga-demo: error: %s\n", e.what());
    return 1;
  }
}
