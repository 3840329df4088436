// cga-accuracy FILE.bvh [--k K]... : how well each interpolation mode rebuilds motion capture.
// Keeps every k-th frame of the file's first clip as keys (and the last frame, so the whole clip is covered),
// samples the dropped frames with each mode and baseline, and compares the model-space joint positions with
// the file's own frames. Prints mean and max joint-position error in the file's units, per mode and k.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cga/baselines/pose_jobs.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/io/loader.hpp"

using namespace cga;

namespace {

// Model-space joint positions of `clip` at time t in `mode`.
void joint_positions(const Skeleton& sk, const Clip& clip, float t, baseline::PoseMode mode, baseline::PoseBuffer& local,
                     baseline::PoseBuffer& model, std::vector<glm::vec3>& out) {
  if (!baseline::sample(mode, clip, t, local) || !baseline::local_to_model(mode, sk, local, model))
    throw std::runtime_error("sampling or hierarchy job rejected its input");
  out.resize(sk.joint_count());
  for (int j = 0; j < sk.joint_count(); ++j) out[j] = baseline::joint_position(mode, model, j);
}

// The clip keeping only the keys at `kept` frame times (joints with a single key keep it).
Clip decimate(const Clip& clip, const std::vector<float>& kept) {
  Clip out;
  out.name = clip.name;
  out.duration = clip.duration;
  out.ticks_per_second = clip.ticks_per_second;
  out.tracks.resize(clip.keys.size());
  for (std::size_t j = 0; j < clip.keys.size(); ++j) {
    const JointKeys& k = clip.keys[j];
    JointTrack& tr = out.tracks[j];
    for (std::size_t i = 0; i < k.size(); ++i) {
      if (k.size() > 1 && !std::binary_search(kept.begin(), kept.end(), k.times[i])) continue;
      const Transform& x = k.transforms[i];
      tr.translations.push_back({k.times[i], x.translation});
      tr.rotations.push_back({k.times[i], x.rotation, rotor_from_quat(x.rotation)});
      tr.scales.push_back({k.times[i], x.scale});
    }
  }
  build_joint_keys(out);
  return out;
}

int usage() {
  std::fprintf(stderr, "usage: cga-accuracy FILE.bvh [--k K]...   (default: --k 4 --k 8 --k 16)\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  std::string path;
  std::vector<int> ks;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--k" || a == "-k") {
      if (i + 1 >= argc) return usage();
      char* end = nullptr;
      const long k = std::strtol(argv[++i], &end, 10);
      if (!end || *end || k < 2 || k > 1000000) {
        std::fprintf(stderr, "cga-accuracy: --k needs an integer >= 2, got '%s'\n", argv[i]);
        return 2;
      }
      ks.push_back(int(k));
    } else if (a == "--help" || a == "-h") {
      usage();
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "cga-accuracy: unknown option '%s'\n", a.c_str());
      return usage();
    } else if (path.empty()) {
      path = a;
    } else {
      return usage();
    }
  }
  if (path.empty()) return usage();
  if (ks.empty()) ks = {4, 8, 16};

  try {
    LoadOptions opt;
    opt.meshes = false;
    const Character ch = load_character(path, opt);
    if (ch.clips.empty()) throw LoadError(path + ": no animation in the file");
    const Clip& clip = ch.clips[0];
    // The frames: the key times of the joint with the most keys (a BVH samples every channel every frame).
    std::size_t busiest = 0;
    for (std::size_t j = 0; j < clip.keys.size(); ++j)
      if (clip.keys[j].size() > clip.keys[busiest].size()) busiest = j;
    const std::vector<float>& frames = clip.keys[busiest].times;
    if (frames.size() < 3) throw LoadError(path + ": fewer than 3 frames, nothing to interpolate");
    for (const std::string& w : ch.warnings) fmt::print(stderr, "warning: {}\n", w);

    const Skeleton& sk = ch.skeleton;
    baseline::PoseBuffer local(sk.joint_count()), model(sk.joint_count());
    std::vector<std::vector<glm::vec3>> truth(frames.size());
    for (std::size_t f = 0; f < frames.size(); ++f)
      joint_positions(sk, clip, frames[f], baseline::PoseMode::glm_matrix, local, model, truth[f]);
    float extent = 0.0f;
    for (const auto& pose : truth)
      for (const glm::vec3& p : pose) extent = std::max(extent, glm::length(p - truth[0][0]));

    fmt::print("{}: clip '{}', {} joints, {} frames, {:.4g} s; joints reach {:.4g} units from the root\n", path,
               clip.name, sk.joint_count(), frames.size(), clip.duration, extent);
    fmt::print("error of the rebuilt frames in file units (mean / max over dropped frames x joints)\n\n");
    fmt::print("{:>4}  {:<13} {:>12} {:>12}\n", "k", "mode", "mean", "max");
    std::vector<glm::vec3> got;
    for (int k : ks) {
      if (std::size_t(k) >= frames.size()) {
        fmt::print("{:>4}  (skipped: the clip has only {} frames)\n", k, frames.size());
        continue;
      }
      std::vector<float> kept;
      for (std::size_t f = 0; f < frames.size(); f += k) kept.push_back(frames[f]);
      if (kept.back() != frames.back()) kept.push_back(frames.back());
      const Clip reduced = decimate(clip, kept);
      for (baseline::PoseMode mode : baseline::kAllPoseModes) {
        double sum = 0.0, worst = 0.0;
        std::size_t count = 0;
        for (std::size_t f = 0; f < frames.size(); ++f) {
          if (std::binary_search(kept.begin(), kept.end(), frames[f])) continue;
          joint_positions(sk, reduced, frames[f], mode, local, model, got);
          for (int j = 0; j < sk.joint_count(); ++j) {
            const double e = glm::length(got[j] - truth[f][j]);
            sum += e;
            worst = std::max(worst, e);
            ++count;
          }
        }
        fmt::print("{:>4}  {:<13} {:>12.5g} {:>12.5g}\n", k, to_string(mode), count ? sum / count : 0.0, worst);
      }
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cga-accuracy: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
