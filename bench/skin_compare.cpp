// cga-skin-compare: cga-log (blended motor logarithms) against cga-motors (blended motors) on the CPU.
//   twist    the candy-wrapper cylinder (65 rings, radius 1, length 4) twisted by 90, 180, 270 degrees: middle
//            ring radius, enclosed volume against the rest volume, the largest gap between the two methods,
//            and how far each ring's turn is from (its weight x the angle)
//   bend     the same cylinder bent at its middle joint by 45, 90, 135 degrees: enclosed volume, gap
//   scale    the twist at 180 degrees with the child bone scaled by 2: middle ring radius, volume
//   chars    the real characters (assimp-testmodels BCN_Epileptic.X, Testwuson.X) at every key frame: the gap
//            between the methods over the character's size, the signed surface volume against the rest
//            pose's, and the time of one CPU skinning of all meshes (best of 5 runs)
// Deterministic apart from the times. --quick runs one angle and one character frame (the ctest smoke run).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/io/loader.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/testing/key_times.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

namespace {

using namespace cga;

constexpr SkinningMethod kMethods[] = {SkinningMethod::cga_motors, SkinningMethod::cga_log};

SkinnedOutput skin(SkinningMethod method, const SkinnedMesh& mesh, const MotorPalette& motors) {
  SkinnedOutput out;
  SkinningJob job = make_skinning_job(method, mesh, out);
  job.motors = motors;
  if (!job.Run()) throw std::runtime_error(fmt::format("{}: the skinning job failed on '{}'", to_string(method), mesh.name));
  return out;
}

MotorPalette motors_of(const std::vector<Transform>& xs) {
  MotorPalette p;
  for (const Transform& x : xs) p.push_back(motor_from_transform(x));
  return p;
}

glm::dvec3 at(const SkinnedOutput& o, std::size_t i) { return {o.px[i], o.py[i], o.pz[i]}; }

double max_gap(const SkinnedOutput& a, const SkinnedOutput& b) {
  double d = 0.0;
  for (std::size_t i = 0; i < a.px.size(); ++i) d = std::max(d, glm::length(at(a, i) - at(b, i)));
  return d;
}

// Volume of the cylinder side closed by a fan to each end ring's centroid (divergence theorem).
double cylinder_volume(const TwistCylinder& cyl, const SkinnedOutput& o) {
  const int segments = cyl.spec.segments, rings = cyl.spec.rings;
  auto p = [&](int r, int s) { return at(o, static_cast<std::size_t>(r * segments + (s % segments))); };
  double v = 0.0;
  auto tri = [&](const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c) { v += glm::dot(a, glm::cross(b, c)) / 6.0; };
  for (int r = 0; r + 1 < rings; ++r)
    for (int s = 0; s < segments; ++s) {
      tri(p(r, s), p(r, s + 1), p(r + 1, s + 1));
      tri(p(r, s), p(r + 1, s + 1), p(r + 1, s));
    }
  for (int end : {0, rings - 1}) {
    glm::dvec3 c(0.0);
    for (int s = 0; s < segments; ++s) c += p(end, s);
    c /= segments;
    for (int s = 0; s < segments; ++s) end == 0 ? tri(c, p(end, s + 1), p(end, s)) : tri(c, p(end, s), p(end, s + 1));
  }
  return std::abs(v);
}

// The middle ring's distance from the cylinder axis (min, max).
std::pair<double, double> middle_radius(const TwistCylinder& cyl, const SkinnedOutput& o) {
  double lo = 1e300, hi = 0.0;
  for (std::uint32_t i : cyl.middle_ring) {
    const double r = std::hypot(double(o.px[i]), double(o.py[i]));
    lo = std::min(lo, r), hi = std::max(hi, r);
  }
  return {lo, hi};
}

// How far each ring's turn about the axis is from (its weight on bone 1) x angle (taken the shorter way), the
// largest over the rings, in degrees: 0 for a twist spread evenly over the weights.
double twist_unevenness(const TwistCylinder& cyl, const SkinnedOutput& o, double angle) {
  double worst = 0.0;
  for (int r = 0; r < cyl.spec.rings; ++r) {
    const std::size_t i = static_cast<std::size_t>(r * cyl.spec.segments);  // segment 0 starts on +x
    const double turn = std::atan2(double(o.py[i]), double(o.px[i]));
    const double want = double(cyl.mesh.weights[i][1]) * std::remainder(angle, 2.0 * M_PI);
    // The shorter way is either way at 180 degrees: compare magnitudes.
    worst = std::max(worst, std::abs(std::abs(turn) - std::abs(want)));
  }
  return worst * 180.0 / M_PI;
}

// Bone 1 of the cylinder bent by `angle` about the x axis through its joint (z = length / 2).
std::vector<Transform> bend_transforms(const TwistCylinderSpec& spec, float angle) {
  Transform bone1;
  bone1.rotation = glm::angleAxis(angle, glm::vec3(1, 0, 0));
  const glm::vec3 joint(0.0f, 0.0f, 0.5f * spec.length);
  bone1.translation = joint - bone1.rotation * joint;
  return {Transform{}, bone1};
}

void twist_section(bool quick) {
  const TwistCylinder cyl = make_twist_cylinder();
  const double rest = cylinder_volume(cyl, skin(SkinningMethod::cga_motors, cyl.mesh, motors_of(twist_cylinder_skinning_transforms(cyl.spec, 0.0f))));
  std::puts("\n## Twist: the candy-wrapper cylinder (radius 1, length 4, 65 rings)\n");
  std::puts("| angle | method | middle ring radius | volume / rest | twist unevenness (deg) | gap to cga-motors / length |");
  std::puts("|---|---|---|---|---|---|");
  for (float deg : quick ? std::vector<float>{180.0f} : std::vector<float>{90.0f, 180.0f, 270.0f}) {
    const float angle = deg * static_cast<float>(M_PI) / 180.0f;
    const MotorPalette pal = motors_of(twist_cylinder_skinning_transforms(cyl.spec, angle));
    const SkinnedOutput motors = skin(SkinningMethod::cga_motors, cyl.mesh, pal);
    for (SkinningMethod m : kMethods) {
      const SkinnedOutput o = skin(m, cyl.mesh, pal);
      const auto [lo, hi] = middle_radius(cyl, o);
      std::printf("| %.0f | %s | %.4f to %.4f | %.4f | %.2f | %.2e |\n", deg, std::string(to_string(m)).c_str(), lo,
                  hi, cylinder_volume(cyl, o) / rest, twist_unevenness(cyl, o, angle),
                  max_gap(o, motors) / cyl.spec.length);
    }
  }
  std::puts("\nBoth keep the ring on its radius (a blend of rotations about one axis is a rotation). A motor");
  std::puts("blend turns a ring by the angle of its normalized blended rotor, which is not linear in the weight;");
  std::puts("the log blend turns it by exactly weight x angle. At 270 degrees both take the shorter way (-90).");

  std::puts("\n## Bend: the cylinder bent at its middle joint\n");
  std::puts("| angle | method | volume / rest | gap to cga-motors / length |");
  std::puts("|---|---|---|---|");
  for (float deg : quick ? std::vector<float>{90.0f} : std::vector<float>{45.0f, 90.0f, 135.0f}) {
    const MotorPalette pal = motors_of(bend_transforms(cyl.spec, deg * static_cast<float>(M_PI) / 180.0f));
    const SkinnedOutput motors = skin(SkinningMethod::cga_motors, cyl.mesh, pal);
    for (SkinningMethod m : kMethods) {
      const SkinnedOutput o = skin(m, cyl.mesh, pal);
      std::printf("| %.0f | %s | %.4f | %.2e |\n", deg, std::string(to_string(m)).c_str(), cylinder_volume(cyl, o) / rest,
                  max_gap(o, motors) / cyl.spec.length);
    }
  }

  std::puts("\n## Twist 180 degrees with bone 1 scaled by 2\n");
  std::puts("| method | middle ring radius | volume / rest | gap to cga-motors / length |");
  std::puts("|---|---|---|---|");
  const MotorPalette pal = motors_of(twist_cylinder_skinning_transforms(cyl.spec, static_cast<float>(M_PI), 2.0f));
  const SkinnedOutput motors = skin(SkinningMethod::cga_motors, cyl.mesh, pal);
  for (SkinningMethod m : kMethods) {
    const SkinnedOutput o = skin(m, cyl.mesh, pal);
    const auto [lo, hi] = middle_radius(cyl, o);
    std::printf("| %s | %.4f to %.4f | %.4f | %.2e |\n", std::string(to_string(m)).c_str(), lo, hi,
                cylinder_volume(cyl, o) / rest, max_gap(o, motors) / cyl.spec.length);
  }
  std::puts("\nThe middle ring (weights 1/2, 1/2) of a motor blend scales by its blended dilation; the log blend");
  std::puts("scales it by the geometric mean, sqrt(2) = 1.4142.");
}

// Signed volume of a triangle mesh (about the origin): for an open surface it depends on the origin, so only
// its ratio to the rest pose's is shown.
double signed_volume(const SkinnedMesh& mesh, const SkinnedOutput& o) {
  double v = 0.0;
  for (std::size_t t = 0; t + 2 < mesh.indices.size(); t += 3)
    v += glm::dot(at(o, mesh.indices[t]), glm::cross(at(o, mesh.indices[t + 1]), at(o, mesh.indices[t + 2]))) / 6.0;
  return v;
}

void character_section(const std::string& models, bool quick) {
  std::puts("\n## Real characters at every key frame of their first clip\n");
  std::puts("| character | frames | method | gap to cga-motors / size (max, mean) | signed volume / rest (min, max) | CPU skinning ms |");
  std::puts("|---|---|---|---|---|---|");
  for (const char* file : {"X/BCN_Epileptic.X", "X/Testwuson.X"}) {
    const Character ch = load_character(models + "/" + file);
    if (ch.clips.empty()) throw std::runtime_error(std::string(file) + ": no clip");
    const Clip& clip = ch.clips.front();
    std::vector<float> times = testing::key_times(clip);
    if (quick) times.resize(1);
    // Size: the rest pose's bounding box diagonal over all meshes.
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const SkinnedMesh& mesh : ch.meshes)
      for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
        const glm::dvec3 p(mesh.px[i], mesh.py[i], mesh.pz[i]);
        lo = glm::min(lo, p), hi = glm::max(hi, p);
      }
    const double size = glm::length(hi - lo);
    struct Stats {
      double gap_max = 0, gap_sum = 0, vol_lo = 1e300, vol_hi = -1e300, best_ms = 1e300;
    } stats[2];
    const std::size_t n = static_cast<std::size_t>(ch.skeleton.joint_count());
    for (float t : times) {
      std::vector<MotorPalette> palettes;
      for (const SkinnedMesh& mesh : ch.meshes) {
        baseline::PoseBuffer local(n), model(n);
        baseline::PaletteBuffer pal(mesh.joint_remap.size());
        if (!baseline::sample(baseline::PoseMode::paper, clip, t, local) ||
            !baseline::local_to_model(baseline::PoseMode::paper, ch.skeleton, local, model) ||
            !baseline::palette(baseline::PoseMode::paper, mesh.joint_remap, baseline::make_inverse_bind(mesh), model, pal))
          throw std::runtime_error(std::string(file) + ": the pose jobs failed");
        palettes.push_back(pal.motors);
      }
      std::vector<SkinnedOutput> motors;
      for (std::size_t k = 0; k < ch.meshes.size(); ++k) motors.push_back(skin(SkinningMethod::cga_motors, ch.meshes[k], palettes[k]));
      for (int mi = 0; mi < 2; ++mi) {
        double gap = 0.0, vol = 0.0, rest = 0.0;
        for (std::size_t k = 0; k < ch.meshes.size(); ++k) {
          const SkinnedMesh& mesh = ch.meshes[k];
          const SkinnedOutput o = skin(kMethods[mi], mesh, palettes[k]);
          gap = std::max(gap, max_gap(o, motors[k]));
          SkinnedOutput rest_pose;
          rest_pose.px = mesh.px, rest_pose.py = mesh.py, rest_pose.pz = mesh.pz;
          vol += signed_volume(mesh, o), rest += signed_volume(mesh, rest_pose);
        }
        Stats& s = stats[mi];
        s.gap_max = std::max(s.gap_max, gap / size), s.gap_sum += gap / size;
        s.vol_lo = std::min(s.vol_lo, vol / rest), s.vol_hi = std::max(s.vol_hi, vol / rest);
      }
      if (t == times.front())
        for (int mi = 0; mi < 2; ++mi)
          for (int run = 0; run < 5; ++run) {
            const auto start = std::chrono::steady_clock::now();
            for (std::size_t k = 0; k < ch.meshes.size(); ++k) skin(kMethods[mi], ch.meshes[k], palettes[k]);
            const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
            stats[mi].best_ms = std::min(stats[mi].best_ms, ms);
          }
    }
    for (int mi = 0; mi < 2; ++mi)
      std::printf("| %s | %zu | %s | %.2e, %.2e | %.4f, %.4f | %.3f |\n", file, times.size(),
                  std::string(to_string(kMethods[mi])).c_str(), stats[mi].gap_max, stats[mi].gap_sum / times.size(),
                  stats[mi].vol_lo, stats[mi].vol_hi, stats[mi].best_ms);
  }
  std::puts("\nThe times include the per-run palette preparation and the output allocation (cga-motors on its");
  std::puts("SIMD loop where the CPU has one, cga-log on the generated loop); cga-bench measures throughput.");
}

}  // namespace

int main(int argc, char** argv) {
  bool quick = false;
  std::string models = CGA_MODELS_DIR;
  for (int i = 1; i < argc; ++i) {
    const std::string_view a = argv[i];
    if (a == "--quick") quick = true;
    else if (a == "--models" && i + 1 < argc) models = argv[++i];
    else {
      std::fprintf(stderr, "usage: cga-skin-compare [--quick] [--models DIR]\n");
      return 2;
    }
  }
  try {
    std::puts("# cga-log against cga-motors (CPU)");
    twist_section(quick);
    character_section(models, quick);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cga-skin-compare: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
