// Scaled rigs: on rigs whose joints carry scales 100 and 0.01 (centimetre exports), every CPU skinning
// method stays within 1e-5 of the character's size of a double-precision reference of the same method
// (scaled_rig.hpp). The motors are composed and turned into matrices in split form for this: in blade form
// cga-points is 4e-4 and cga-motors 1e-5..4e-4 of the size away on these rigs (the blade form's weight
// a^2 + b^2 + 2ab and its products cancel at scale 100).
#include <catch2/catch.hpp>

#include <cstdio>
#include <string>

#include "scaled_rig.hpp"
#include "cga/io/loader.hpp"
#include "cga/testing/key_times.hpp"

using namespace cga;

namespace {

constexpr double kTolerance = 1e-5;  // of the character's size

// Max distance / size over the clip's key times between each method's CPU job and its double reference.
double worst_deviation(const Character& ch, SkinningMethod method, Interpolation motor_mode, bool use_simd) {
  const double size = character_size(ch);
  const Clip& clip = ch.clips.at(0);
  const std::vector<float> times = cga::testing::key_times(clip);
  double worst = 0.0;
  for (float t : times)
    for (std::size_t m = 0; m < ch.meshes.size(); ++m) {
      const SkinnedMesh& mesh = ch.meshes[m];
      const test::Palettes pal = test::job_palettes(ch, m, clip, t, test::pipeline_mode(method, motor_mode));
      SkinnedOutput out;
      out.resize_for(mesh);
      SkinningJob job = make_skinning_job(method, mesh, out);
      job.matrices = pal.matrices, job.dual_quats = pal.dual_quats, job.motors = pal.motors;
      job.use_simd = use_simd;
      REQUIRE(job.Run());
      const auto ref = test::double_palette(ch, mesh, clip, t);
      REQUIRE(ref.size() == mesh.joint_remap.size());
      for (std::size_t v = 0; v < mesh.vertex_count(); ++v) {
        const glm::dvec3 r = test::double_skin(method, ref, mesh, v);
        worst = std::max(worst, glm::length(glm::dvec3(out.px[v], out.py[v], out.pz[v]) - r));
      }
    }
  return worst / size;
}

void check_every_method(const Character& ch) {
  for (SkinningMethod method : kAllSkinningMethods)
    for (Interpolation mode : {Interpolation::paper, Interpolation::nlerp})
      for (bool simd : {true, false}) {
        if (method != SkinningMethod::cga_points && method != SkinningMethod::cga_motors &&
            mode != Interpolation::paper)
          continue;
        const double d = worst_deviation(ch, method, mode, simd);
        std::printf("%s: %-10s %-5s %-8s %.3g of the size\n", ch.path.c_str(), std::string(to_string(method)).c_str(),
                    std::string(to_string(mode)).c_str(), simd ? "simd" : "portable", d);
        INFO(ch.path << ": " << to_string(method) << " (" << to_string(mode) << (simd ? ", simd" : ", portable")
                     << ") is " << d << " of the size from the double reference");
        CHECK(d < kTolerance);
      }
}

}  // namespace

TEST_CASE("a rig with joint scales 100 and 0.01: every CPU method within 1e-5 of the size of double precision") {
  const Character ch = test::make_centimetre_rig();
  // The rig is what it claims: the armature scales by 100, the hips by 0.01, the rest is rigid.
  REQUIRE(ch.skeleton.rest_local[0].scale == 100.0f);
  REQUIRE(ch.skeleton.rest_local[1].scale == 0.01f);
  check_every_method(ch);
}

TEST_CASE("huesitos.fbx (armature scale 100 in the file): every CPU method within 1e-5 of the size") {
  const Character ch = load_character(std::string(CGA_MODELS_DIR) + "/FBX/huesitos.fbx");
  REQUIRE(ch.skeleton.rest_local[0].scale == Approx(100.0f));
  check_every_method(ch);
}
