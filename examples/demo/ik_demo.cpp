// The demo's IK scenes (see ik_demo.hpp): sample, hierarchy, TwoBoneIKJob on the right arm or ChainIKJob on
// the spine and the right arm, corrections applied to the local pose, hierarchy again, the hand's distance to
// the target, and a picture of the character before and after, skinned with cga-motors.
#include "ik_demo.hpp"

#include <cmath>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "cga/runtime/ik.hpp"
#include "cga/runtime/ik_chain.hpp"
#include "cga/runtime/jobs.hpp"
#include "cga/runtime/motor.hpp"
#include "cga/runtime/skinning.hpp"
#include "cga/gpu/label.hpp"
#include "raster.hpp"

namespace demo {

using namespace cga;

namespace {

void require(bool ok, const char* what) {
  if (!ok) throw std::runtime_error(fmt::format("IK demo: {} refused its input", what));
}

glm::vec3 position(const Motor& m) { return motor_transform_point(m, glm::vec3(0.0f)); }

// Every mesh of the character skinned (cga-motors) with the model pose, appended into one point cloud per
// mesh (positions of mesh m in px[m], ...).
struct Skin {
  std::vector<std::vector<float>> px, py, pz;
};

Skin skin(const Character& ch, const std::vector<Motor>& model) {
  Skin out;
  for (const SkinnedMesh& mesh : ch.meshes) {
    const std::vector<Motor> inverse_bind = make_inverse_bind_motors(mesh);
    std::vector<Motor> palette(mesh.joint_remap.size());
    require(SkinningPaletteJob{mesh.joint_remap, inverse_bind, model, palette}.Run(), "SkinningPaletteJob");
    const std::size_t n = mesh.vertex_count();
    out.px.emplace_back(n), out.py.emplace_back(n), out.pz.emplace_back(n);
    SkinningJob job;
    job.method = SkinningMethod::cga_motors;
    job.in_px = mesh.px, job.in_py = mesh.py, job.in_pz = mesh.pz;
    job.joints = mesh.joints, job.weights = mesh.weights;
    job.motors = palette;
    job.out_px = out.px.back(), job.out_py = out.py.back(), job.out_pz = out.pz.back();
    require(job.Run(), "SkinningJob");
  }
  return out;
}

// A small octahedron around c (8 triangles) as a target marker.
void draw_marker(Image& img, const View& view, glm::vec3 c, float r) {
  const std::vector<float> px = {c.x + r, c.x - r, c.x, c.x, c.x, c.x}, py = {c.y, c.y, c.y + r, c.y - r, c.y, c.y},
                           pz = {c.z, c.z, c.z, c.z, c.z + r, c.z - r};
  const std::vector<std::uint32_t> tri = {0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 2, 0, 5, 1, 2, 5, 3, 1, 5, 0, 3, 5};
  draw_triangles(img, view, px, py, pz, tri, glm::vec3(0.9f, 0.1f, 0.1f));
}

// Two panels, same view: before (grey) and after (colour), the target in red in both; written to path.
void draw_before_after(const Character& ch, const std::vector<Motor>& model_before, const std::vector<Motor>& model,
                       glm::vec3 target, float marker, const std::string& path, const std::string (&caption)[2]) {
  const Skin before = skin(ch, model_before), after = skin(ch, model);
  const int w = 480, h = 640;
  Image img(2 * w, h);
  std::vector<float> ax, ay, az;
  for (const Skin* k : {&before, &after})
    for (std::size_t i = 0; i < k->px.size(); ++i)
      ax.insert(ax.end(), k->px[i].begin(), k->px[i].end()), ay.insert(ay.end(), k->py[i].begin(), k->py[i].end()),
          az.insert(az.end(), k->pz[i].begin(), k->pz[i].end());
  ax.push_back(target.x), ay.push_back(target.y), az.push_back(target.z);
  for (int panel = 0; panel < 2; ++panel) {
    View view = frame_points(ax, ay, az, panel * w, 0, w, h);
    const Skin& k = panel == 0 ? before : after;
    for (std::size_t i = 0; i < ch.meshes.size(); ++i)
      draw_triangles(img, view, k.px[i], k.py[i], k.pz[i], ch.meshes[i].indices,
                     panel == 0 ? glm::vec3(0.6f) : glm::vec3(0.35f, 0.6f, 0.9f));
    draw_marker(img, view, target, marker);
  }
  cga::gpu::write_png(cga::gpu::with_caption(to_rgba(img), caption), path);
}

}  // namespace

std::string ik_hand_reach(const Character& ch, const std::string& out_dir) {
  const Skeleton& sk = ch.skeleton;
  const int js = sk.find("B_UpperArm_Right"), jm = sk.find("B_ForeArm_Right"), je = sk.find("B_Hand_Right");
  const int jc = sk.find("B_Clavicle_Right"), jp = sk.find("B_Root_Pelvis_T"), jn = sk.find("B_Neck");
  if (js < 0 || jm < 0 || je < 0 || jc < 0 || jp < 0 || jn < 0 || ch.clips.empty() ||
      sk.parents[jm] != js || sk.parents[je] != jm) {
    fmt::print("IK: this character has no B_UpperArm_Right -> B_ForeArm_Right -> B_Hand_Right arm; skipped\n\n");
    return "";
  }
  const std::size_t n = static_cast<std::size_t>(sk.joint_count());
  std::vector<Motor> local(n), model(n);
  const Clip& clip = ch.clips[0];
  require(SamplingJob{&clip, 0.5f * clip.duration, Interpolation::nlerp, local}.Run(), "SamplingJob");
  require(LocalToModelJob{&sk, local, model}.Run(), "LocalToModelJob");
  const std::vector<Motor> model_before = model;

  // The target: 85 % of the arm's length from the shoulder, up (pelvis -> neck) and out to the side
  // (clavicle -> shoulder), so the raised hand is plainly visible; the elbow keeps bending the way it does.
  const glm::vec3 s = position(model[js]), m = position(model[jm]), e = position(model[je]);
  const float arm = glm::length(m - s) + glm::length(e - m);
  const glm::vec3 up = glm::normalize(position(model[jn]) - position(model[jp]));
  const glm::vec3 side = glm::normalize(s - position(model[jc]));
  const glm::vec3 target = s + 0.85f * arm * glm::normalize(up + 0.6f * side);
  const glm::vec3 pole = -up;  // elbow down, as a raised arm bends

  Motor c_start, c_mid;
  bool reached = false;
  TwoBoneIKJob ik;
  ik.start_joint = &model[js], ik.mid_joint = &model[jm], ik.end_joint = &model[je];
  ik.target = target, ik.pole_vector = pole;
  ik.start_joint_correction = &c_start, ik.mid_joint_correction = &c_mid, ik.reached = &reached;
  require(ik.Run(), "TwoBoneIKJob");
  apply_ik_correction(local[js], c_start);
  apply_ik_correction(local[jm], c_mid);
  require(LocalToModelJob{&sk, local, model}.Run(), "LocalToModelJob");

  const float miss = glm::length(position(model[je]) - target) / arm;
  const float moved = glm::length(position(model[js]) - s) / arm;
  fmt::print("IK: right hand reaches the target (TwoBoneIKJob, clip '{}' at t = {:.3g} s): distance {:.3g} of the "
             "arm length, shoulder moved {:.3g}, reached flag {}\n",
             clip.name, 0.5f * clip.duration, miss, moved, reached ? "yes" : "no");
  if (!(miss <= 1e-4f) || !(moved <= 1e-4f) || !reached)
    throw std::runtime_error(fmt::format("IK demo: the hand misses the target by {:.3g} of the arm length", miss));
  if (out_dir.empty()) {
    fmt::print("\n");
    return "";
  }

  const std::string path = out_dir + "/ik-hand-reach.png";
  const std::string caption[] = {
      "two-bone IK, right arm (cga-motors)",
      fmt::format("CPU: skinned by the CPU SkinningJob, drawn by the demo's rasterizer. Clip '{}' at {:.3g} s; "
                  "left: before the solve (grey), right: after (blue); the target in red",
                  clip.name, 0.5f * clip.duration)};
  draw_before_after(ch, model_before, model, target, 0.04f * arm, path, caption);
  fmt::print("  ik-hand-reach.png: before (grey) and after (blue) the solve, target in red (inside the reaching hand on the right): {}\n\n", path);
  return path;
}

std::string ik_chain_reach(const Character& ch, const std::string& out_dir) {
  const Skeleton& sk = ch.skeleton;
  // The chain: B_Spine1 up to the right hand, as the skeleton links them.
  const char* names[] = {"B_Spine1", "B_Spine2", "B_Spine3", "B_Spine4", "B_Clavicle_Right", "B_UpperArm_Right",
                         "B_ForeArm_Right", "B_Hand_Right"};
  std::vector<int> chain;
  for (const char* name : names) chain.push_back(sk.find(name));
  const int knee = sk.find("B_Knee_Right"), neck = sk.find("B_Neck"), jaw = sk.find("B_Jaw"),
            pelvis = sk.find("B_Root_Pelvis_T");
  bool linked = knee >= 0 && neck >= 0 && jaw >= 0 && pelvis >= 0 && !ch.clips.empty();
  for (std::size_t i = 0; i < chain.size() && linked; ++i)
    linked = chain[i] >= 0 && (i == 0 || sk.parents[chain[i]] == chain[i - 1]);
  if (!linked) {
    fmt::print("IK chain: this character has no B_Spine1 ... B_Hand_Right chain (or no B_Knee_Right, B_Neck, B_Jaw, "
               "B_Root_Pelvis_T); skipped\n\n");
    return "";
  }
  const std::size_t n = static_cast<std::size_t>(sk.joint_count());
  std::vector<Motor> local(n), model(n);
  const Clip& clip = ch.clips[0];
  require(SamplingJob{&clip, 0.5f * clip.duration, Interpolation::nlerp, local}.Run(), "SamplingJob");
  require(LocalToModelJob{&sk, local, model}.Run(), "LocalToModelJob");
  const std::vector<Motor> model_before = model;

  // The target: low in front of the right knee, as if to pick something up, which the arm alone cannot
  // reach: the spine has to bend forward. Forward is where the jaw is from the neck, across the up axis.
  std::vector<Motor> joints;
  for (int j : chain) joints.push_back(model[j]);
  float length = 0.0f;
  for (std::size_t i = 1; i < chain.size(); ++i) length += glm::length(position(joints[i]) - position(joints[i - 1]));
  const glm::vec3 up = glm::normalize(position(model[neck]) - position(model[pelvis]));
  const glm::vec3 ahead = position(model[jaw]) - position(model[neck]);
  const glm::vec3 forward = glm::normalize(ahead - glm::dot(ahead, up) * up);
  const glm::vec3 target = position(model[knee]) + 0.35f * length * forward;

  std::vector<Motor> corrections(chain.size());
  bool reached = false;
  int iterations = 0;
  ChainIKJob ik;
  ik.joints = joints, ik.target = target, ik.corrections = corrections;
  ik.reached = &reached, ik.iterations = &iterations;
  require(ik.Run(), "ChainIKJob");
  for (std::size_t i = 0; i < chain.size(); ++i) apply_ik_correction(local[chain[i]], corrections[i]);
  require(LocalToModelJob{&sk, local, model}.Run(), "LocalToModelJob");

  const glm::vec3 hand = position(model[chain.back()]);
  const float miss = glm::length(hand - target) / length;
  fmt::print("IK chain: spine and right hand reach low in front of the right knee (ChainIKJob, {} free joints, clip '{}' at t = {:.3g} "
             "s): distance {:.3g} of the chain length after {} iterations, reached flag {}\n",
             chain.size(), clip.name, 0.5f * clip.duration, miss, iterations, reached ? "yes" : "no");
  if (!(miss <= 1e-4f) || !reached)
    throw std::runtime_error(fmt::format("IK demo: the chain's hand misses its target by {:.3g} of its length", miss));
  if (out_dir.empty()) {
    fmt::print("\n");
    return "";
  }
  const std::string path = out_dir + "/ik-chain-reach.png";
  const std::string caption[] = {
      fmt::format("chain IK, spine and right arm ({} joints, cga-motors)", chain.size()),
      fmt::format("CPU: skinned by the CPU SkinningJob, drawn by the demo's rasterizer. Clip '{}' at {:.3g} s; "
                  "left: before the solve (grey), right: after (blue); the target (low, in front of the right knee) in red",
                  clip.name, 0.5f * clip.duration)};
  draw_before_after(ch, model_before, model, target, 0.03f * length, path, caption);
  fmt::print("  ik-chain-reach.png: before (grey) and after (blue) the solve, target in red (at the reaching hand): {}\n\n",
             path);
  return path;
}

}  // namespace demo
