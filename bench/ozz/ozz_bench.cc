// ozz-animation side of scripts/bench.sh --vs-ozz: SkinningJob throughput and the pose pipeline, on the same
// kind of data as cga-bench (1 M and 64 K random vertices, 64 joints, 4 influences, packed and in one 48-byte
// interleaved stride; a 54-joint humanoid).
#include <cstddef>
#include <cstring>
#include <string>

#include "common.h"
#include "ozz/animation/offline/animation_builder.h"
#include "ozz/animation/offline/raw_animation.h"
#include "ozz/animation/offline/raw_skeleton.h"
#include "ozz/animation/offline/skeleton_builder.h"
#include "ozz/animation/runtime/animation.h"
#include "ozz/animation/runtime/blending_job.h"
#include "ozz/animation/runtime/local_to_model_job.h"
#include "ozz/animation/runtime/sampling_job.h"
#include "ozz/animation/runtime/skeleton.h"
#include "ozz/base/maths/simd_math.h"
#include "ozz/base/maths/soa_transform.h"
#include "ozz/base/maths/transform.h"
#include "ozz/base/memory/unique_ptr.h"
#include "ozz/geometry/runtime/skinning_job.h"

using namespace ozz;
namespace off = ozz::animation::offline;

static const char* simd_name() {
#if defined(OZZ_SIMD_AVX2)
  return "AVX2";
#elif defined(OZZ_SIMD_AVX)
  return "AVX";
#elif defined(OZZ_SIMD_SSE4_2)
  return "SSE4.2";
#elif defined(OZZ_SIMD_SSE2)
  return "SSE2";
#else
  return "REF";
#endif
}

// ozz's column-major joint matrices of the rigid joints.
static std::vector<math::Float4x4> ozz_matrices(const std::vector<Rigid>& js) {
  std::vector<math::Float4x4> mats(js.size());
  for (std::size_t j = 0; j < js.size(); ++j) {
    float m[12];
    rigid_to_3x4(js[j], m);
    mats[j].cols[0] = math::simd_float4::Load(m[0], m[4], m[8], 0.f);
    mats[j].cols[1] = math::simd_float4::Load(m[1], m[5], m[9], 0.f);
    mats[j].cols[2] = math::simd_float4::Load(m[2], m[6], m[10], 0.f);
    mats[j].cols[3] = math::simd_float4::Load(m[3], m[7], m[11], 1.f);
  }
  return mats;
}

// Largest difference of the outputs (vertex i at out_p + i * stride_p, normals likewise when out_n is given)
// from the scalar blend of 3x4 matrices, over the first 20000 vertices.
static double max_error(const std::vector<Rigid>& js, const MeshData& md, const float* out_p, int stride_p,
                        const float* out_n, int stride_n) {
  double maxerr = 0;
  for (int i = 0; i < std::min(md.n, 20000); ++i) {
    float acc[12] = {0};
    for (int k = 0; k < 4; ++k) {
      float m[12];
      rigid_to_3x4(js[md.idx[4 * i + k]], m);
      for (int e = 0; e < 12; ++e) acc[e] += md.wgt[4 * i + k] * m[e];
    }
    const float* p = &md.pos[3 * i];
    const float* nn = &md.nrm[3 * i];
    for (int r = 0; r < 3; ++r) {
      const float o = acc[4 * r] * p[0] + acc[4 * r + 1] * p[1] + acc[4 * r + 2] * p[2] + acc[4 * r + 3];
      maxerr = std::max(maxerr, (double)std::fabs(o - out_p[stride_p * i + r]));
      if (out_n) {
        const float on = acc[4 * r] * nn[0] + acc[4 * r + 1] * nn[1] + acc[4 * r + 2] * nn[2];
        maxerr = std::max(maxerr, (double)std::fabs(on - out_n[stride_n * i + r]));
      }
    }
  }
  return maxerr;
}

// ---------------------------------------------------------------- skinning
static void bench_skinning(int n, const char* tag) {
  const int kJoints = 64;
  auto js = make_joints(kJoints);
  const std::vector<math::Float4x4> mats = ozz_matrices(js);
  MeshData md = make_mesh(n, kJoints);
  std::vector<float> outp(3 * n), outn(3 * n);

  for (int pn = 0; pn < 2; ++pn) {
    geometry::SkinningJob job;
    job.vertex_count = n;
    job.influences_count = 4;
    job.joint_matrices = make_span(mats);
    job.joint_indices = make_span(md.idx);
    job.joint_indices_stride = 4 * sizeof(uint16_t);
    job.joint_weights = make_span(md.wgt);
    job.joint_weights_stride = 4 * sizeof(float);  // ozz reads 3, rebuilds 4th
    job.in_positions = make_span(md.pos);
    job.in_positions_stride = 3 * sizeof(float);
    job.out_positions = make_span(outp);
    job.out_positions_stride = 3 * sizeof(float);
    if (pn) {
      job.in_normals = make_span(md.nrm);
      job.in_normals_stride = 3 * sizeof(float);
      job.out_normals = make_span(outn);
      job.out_normals_stride = 3 * sizeof(float);
    }
    if (!job.Run()) { std::printf("skinning job failed\n"); std::exit(1); }
    // correctness vs scalar reference on a subset
    const double maxerr = max_error(js, md, outp.data(), 3, pn ? outn.data() : nullptr, 3);
    Stats s = time_it([&] { job.Run(); clobber(); });
    std::printf("ozz SkinningJob %-2s %s n=%d inf=4: %.1f Mvert/s (median; min-max %.1f-%.1f) %.2f ns/vert maxerr=%.2g\n",
                pn ? "PN" : "P", tag, n, n / s.med / 1e6, n / s.mx / 1e6, n / s.mn / 1e6,
                s.med / n * 1e9, maxerr);
  }
}

// The same mesh as engines store it: position, normal and skin data in one 48-byte stride (as cga-bench's
// skinning/interleaved1M); outputs x y z nx ny nz interleaved (24 bytes).
struct EngineVertex {
  float p[3], n[3], w[4];
  uint16_t j[4];
};
static_assert(sizeof(EngineVertex) == 48, "48-byte vertex");

static void bench_skinning_interleaved(int n, const char* tag) {
  const int kJoints = 64;
  auto js = make_joints(kJoints);
  const std::vector<math::Float4x4> mats = ozz_matrices(js);
  MeshData md = make_mesh(n, kJoints);
  std::vector<EngineVertex> in(n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 4; ++k) {
      if (k < 3) in[i].p[k] = md.pos[3 * i + k], in[i].n[k] = md.nrm[3 * i + k];
      in[i].w[k] = md.wgt[4 * i + k], in[i].j[k] = md.idx[4 * i + k];
    }
  std::vector<float> out(6 * n);
  const std::size_t bytes = sizeof(EngineVertex) * n;
  const char* base = reinterpret_cast<const char*>(in.data());
  const auto floats_from = [&](std::size_t offset) {
    return span<const float>(reinterpret_cast<const float*>(base + offset), (bytes - offset) / sizeof(float));
  };
  for (int pn = 0; pn < 2; ++pn) {
    geometry::SkinningJob job;
    job.vertex_count = n;
    job.influences_count = 4;
    job.joint_matrices = make_span(mats);
    job.joint_indices = span<const uint16_t>(reinterpret_cast<const uint16_t*>(base + offsetof(EngineVertex, j)),
                                             (bytes - offsetof(EngineVertex, j)) / sizeof(uint16_t));
    job.joint_indices_stride = sizeof(EngineVertex);
    job.joint_weights = floats_from(offsetof(EngineVertex, w));
    job.joint_weights_stride = sizeof(EngineVertex);
    job.in_positions = floats_from(offsetof(EngineVertex, p));
    job.in_positions_stride = sizeof(EngineVertex);
    job.out_positions = make_span(out);
    job.out_positions_stride = 6 * sizeof(float);
    if (pn) {
      job.in_normals = floats_from(offsetof(EngineVertex, n));
      job.in_normals_stride = sizeof(EngineVertex);
      job.out_normals = span<float>(out.data() + 3, out.size() - 3);
      job.out_normals_stride = 6 * sizeof(float);
    }
    if (!job.Run()) { std::printf("interleaved skinning job failed\n"); std::exit(1); }
    const double maxerr = max_error(js, md, out.data(), 6, pn ? out.data() + 3 : nullptr, 6);
    Stats s = time_it([&] { job.Run(); clobber(); });
    std::printf("ozz SkinningJob %-2s %s n=%d inf=4: %.1f Mvert/s (median; min-max %.1f-%.1f) %.2f ns/vert maxerr=%.2g\n",
                pn ? "PN" : "P", tag, n, n / s.med / 1e6, n / s.mx / 1e6, n / s.mn / 1e6,
                s.med / n * 1e9, maxerr);
  }
}

// ---------------------------------------------------------------- pose pipeline
static const int kNumJoints = 54;

static std::vector<int> humanoid_parents() {
  std::vector<int> p = {-1, 0, 1, 2, 3, 4, 5, 6};  // root pelvis spine1-3 neck head jaw
  for (int s = 0; s < 2; ++s) { p.push_back(1); int b = (int)p.size() - 1; for (int k = 0; k < 3; ++k) p.push_back(b + k); }  // legs
  int hands[2];
  for (int s = 0; s < 2; ++s) { p.push_back(4); int b = (int)p.size() - 1; for (int k = 0; k < 3; ++k) p.push_back(b + k); hands[s] = (int)p.size() - 1; }
  for (int s = 0; s < 2; ++s)
    for (int f = 0; f < 5; ++f) { p.push_back(hands[s]); int b = (int)p.size() - 1; p.push_back(b); p.push_back(b + 1); }
  return p;
}

static math::Quaternion rand_quat(std::mt19937& rng, float spread) {
  std::normal_distribution<float> nd(0.f, 1.f);
  float x = nd(rng) * spread, y = nd(rng) * spread, z = nd(rng) * spread, w = 1.f;
  float l = std::sqrt(x * x + y * y + z * z + w * w);
  return math::Quaternion(x / l, y / l, z / l, w / l);
}

static off::RawSkeleton::Joint build_joint(int i, const std::vector<int>& par, std::mt19937& rng) {
  off::RawSkeleton::Joint j;
  j.name = "j" + std::to_string(i);
  std::uniform_real_distribution<float> ud(0.05f, 0.3f);
  j.transform.translation = math::Float3(0.f, i ? ud(rng) : 0.f, 0.f);
  j.transform.rotation = rand_quat(rng, 0.3f);
  j.transform.scale = math::Float3::one();
  for (int c = 0; c < (int)par.size(); ++c)
    if (par[c] == i) j.children.push_back(build_joint(c, par, rng));
  return j;
}

static unique_ptr<animation::Animation> build_anim(int tracks, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> ud(-0.5f, 0.5f);
  off::RawAnimation raw;
  raw.duration = 1.f;
  raw.tracks.resize(tracks);
  const int kKeys = 30;
  for (auto& tr : raw.tracks) {
    for (int k = 0; k < kKeys; ++k) {
      float t = raw.duration * k / (kKeys - 1);
      tr.translations.push_back({t, math::Float3(ud(rng), ud(rng), ud(rng))});
      tr.rotations.push_back({t, rand_quat(rng, 1.0f)});
    }
  }
  if (!raw.Validate()) { std::printf("raw anim invalid\n"); std::exit(1); }
  off::AnimationBuilder builder;
  return builder(raw);
}

static void bench_pose() {
  auto par = humanoid_parents();
  if ((int)par.size() != kNumJoints) { std::printf("bad joint count %zu\n", par.size()); std::exit(1); }
  std::mt19937 rng(7);
  off::RawSkeleton raw_skel;
  raw_skel.roots.push_back(build_joint(0, par, rng));
  if (!raw_skel.Validate() || raw_skel.num_joints() != kNumJoints) { std::printf("bad skel\n"); std::exit(1); }
  off::SkeletonBuilder sb;
  unique_ptr<animation::Skeleton> skel = sb(raw_skel);
  auto a0 = build_anim(skel->num_joints(), 11);
  auto a1 = build_anim(skel->num_joints(), 22);
  const int nsoa = skel->num_soa_joints(), nj = skel->num_joints();

  animation::SamplingJob::Context ctx0(nj), ctx1(nj);
  std::vector<math::SoaTransform> l0(nsoa), l1(nsoa), lb(nsoa);
  std::vector<math::Float4x4> models(nj), invbind(nj), skin(nj);

  // inverse bind matrices from rest pose
  {
    animation::LocalToModelJob l2m;
    l2m.skeleton = skel.get();
    l2m.input = skel->joint_rest_poses();
    l2m.output = make_span(models);
    l2m.Run();
    for (int i = 0; i < nj; ++i) invbind[i] = math::Invert(models[i]);
  }

  const float dt = 1.f / 60.f;
  long frame = 0;
  auto next_ratio = [&] { float t = std::fmod(frame++ * dt, a0->duration()); return t / a0->duration(); };
  std::vector<float> rnd_ratios(4096);
  { std::uniform_real_distribution<float> u(0.f, 1.f); for (auto& r : rnd_ratios) r = u(rng); }

  animation::SamplingJob s0; s0.animation = a0.get(); s0.context = &ctx0; s0.output = make_span(l0);
  animation::SamplingJob s1; s1.animation = a1.get(); s1.context = &ctx1; s1.output = make_span(l1);
  animation::BlendingJob::Layer layers[2];
  layers[0].transform = make_span(l0); layers[0].weight = 0.3f;
  layers[1].transform = make_span(l1); layers[1].weight = 0.7f;
  animation::BlendingJob bj; bj.layers = layers; bj.rest_pose = skel->joint_rest_poses(); bj.output = make_span(lb);
  animation::LocalToModelJob l2m; l2m.skeleton = skel.get(); l2m.input = make_span(lb); l2m.output = make_span(models);
  auto mulbind = [&] { for (int i = 0; i < nj; ++i) skin[i] = models[i] * invbind[i]; };

  auto ok = [](bool b) { if (!b) { std::printf("job failed\n"); std::exit(1); } };
  auto report = [&](const char* name, const Stats& s) {
    std::printf("ozz pose %-42s joints=%d: %8.1f ns/pose (median; min-max %.1f-%.1f)\n", name, nj, s.med * 1e9, s.mn * 1e9, s.mx * 1e9);
  };

  report("sample x1 (playback dt=1/60, loop)", time_it([&] { s0.ratio = next_ratio(); ok(s0.Run()); clobber(); }));
  {
    size_t k = 0;
    report("sample x1 (random t each pose)", time_it([&] { s0.ratio = rnd_ratios[k++ & 4095]; ok(s0.Run()); clobber(); }));
  }
  report("sample x2 + blend(0.3/0.7)", time_it([&] {
           float r = next_ratio(); s0.ratio = r; s1.ratio = r; ok(s0.Run()); ok(s1.Run()); ok(bj.Run()); clobber(); }));
  report("full: sample x2+blend+L2M+invbind", time_it([&] {
           float r = next_ratio(); s0.ratio = r; s1.ratio = r; ok(s0.Run()); ok(s1.Run()); ok(bj.Run()); ok(l2m.Run()); mulbind(); clobber(); }));
  report("  part: blend only", time_it([&] { ok(bj.Run()); clobber(); }));
  report("  part: LocalToModel only", time_it([&] { ok(l2m.Run()); clobber(); }));
  report("  part: x invbind (54 4x4 mul) only", time_it([&] { mulbind(); clobber(); }));
  // sanity 1: rest pose -> skinning matrices must be identity
  {
    animation::LocalToModelJob r; r.skeleton = skel.get(); r.input = skel->joint_rest_poses(); r.output = make_span(models);
    ok(r.Run()); mulbind();
    double e = 0;
    for (int i = 0; i < nj; ++i)
      for (int c = 0; c < 4; ++c) { float f[4]; math::StorePtrU(skin[i].cols[c], f); for (int k = 0; k < 4; ++k) e = std::max(e, (double)std::fabs(f[k] - (c == k ? 1.f : 0.f))); }
    std::printf("ozz pose check: rest-pose skinning matrices vs identity maxerr=%.2g\n", e);
  }
  // sanity 2: deterministic checksum of the full pipeline at ratio 0.5 (fresh contexts)
  {
    ctx0.Invalidate(); ctx1.Invalidate(); s0.ratio = s1.ratio = 0.5f;
    ok(s0.Run()); ok(s1.Run()); ok(bj.Run()); ok(l2m.Run()); mulbind();
    double chk = 0;
    for (int i = 0; i < nj; ++i) { float f[4]; math::StorePtrU(skin[i].cols[3], f); chk += f[0] + f[1] + f[2]; }
    std::printf("ozz pose checksum@0.5 %.5f (anim: 30 T + 30 R keys/track, %zu bytes/anim)\n", chk, a0->size());
  }
}

// ozz_bench [skin | pose | 1M | 64K | interleaved]: everything, or one part (scripts/bench-vs-ozz.sh runs each
// case right next to cga-bench's same case).
int main(int argc, char** argv) {
  std::printf("ozz SIMD path: %s\n", simd_name());
  const std::string part = argc > 1 ? argv[1] : "";
  const auto want = [&](const char* name, bool in_skin) {
    return part.empty() || part == name || (in_skin && part == "skin");
  };
  if (want("1M", true)) bench_skinning(1000000, "1M ");
  if (want("64K", true)) bench_skinning(65536, "64K");
  if (want("interleaved", true)) bench_skinning_interleaved(1000000, "1M interleaved");
  if (want("pose", false)) bench_pose();
  return 0;
}
