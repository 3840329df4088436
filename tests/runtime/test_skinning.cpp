// SkinningJob: method names, every Validate() failure, each method against an independent reference (GLM
// mat4 for lbs, GLM's own dual-quaternion functions for dqs), the CGA methods against the baselines on random
// palettes, dilation, and the two-bone twist cylinder (candy wrapper).
#include <catch2/catch.hpp>

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtx/norm.hpp>  // length2, which GLM's mat3x4_cast(dualquat) uses without including

#include "cga/runtime/skinning.hpp"
#include "cga/runtime/skinning_palettes.hpp"
#include "cga/testing/skinning_test_meshes.hpp"
#include "cga/testing/nan_max.hpp"

using namespace cga;

namespace {

// The motor T R D of a Transform, in the 12-blade order of types.hpp, derived by hand for the tests (not the
// generated motor_from_trs): R = w - z e12 + y e13 - x e23 for the GLM quaternion (x, y, z, w) (see
// notes/cga-facts.md: R = cos(phi/2) - sin(phi/2) (n1 e23 + n2 e31 + n3 e12)), D = 1 + d E with
// d = (1-s)/(1+s), E = einf^e0, and T R D = R + d R E - (1+d)/2 (t R) einf since einf E = einf.
Motor reference_motor(const Transform& x) {
  const glm::quat q = glm::normalize(x.rotation);
  const float r0 = q.w, r12 = -q.z, r13 = q.y, r23 = -q.x;
  const float d = (1.0f - x.scale) / (1.0f + x.scale);
  const float h = -0.5f * (1.0f + d);
  const glm::vec3 t = x.translation;
  Motor m;
  m.c[blade::s] = r0;
  m.c[blade::e12] = r12;
  m.c[blade::e13] = r13;
  m.c[blade::e23] = r23;
  m.c[blade::einf0] = d * r0;
  m.c[blade::e12inf0] = d * r12;
  m.c[blade::e13inf0] = d * r13;
  m.c[blade::e23inf0] = d * r23;
  // t R = (r0 t1 - r12 t2 - r13 t3) e1 + (r0 t2 + r12 t1 - r23 t3) e2 + (r0 t3 + r13 t1 + r23 t2) e3
  //       + (r12 t3 - r13 t2 + r23 t1) e123
  m.c[blade::e1inf] = h * (r0 * t.x - r12 * t.y - r13 * t.z);
  m.c[blade::e2inf] = h * (r0 * t.y + r12 * t.x - r23 * t.z);
  m.c[blade::e3inf] = h * (r0 * t.z + r13 * t.x + r23 * t.y);
  m.c[blade::e123inf] = h * (r12 * t.z - r13 * t.y + r23 * t.x);
  return m;
}

// p -> s R p + t through GLM's 4x4 matrices (independent of to_skinning_matrix's row-major layout).
glm::vec3 reference_transform(const Transform& x, const glm::vec3& p) {
  const glm::mat4 m = glm::translate(glm::mat4(1.0f), x.translation) * glm::mat4_cast(x.rotation) *
                      glm::scale(glm::mat4(1.0f), glm::vec3(x.scale));
  return glm::vec3(m * glm::vec4(p, 1.0f));
}

struct Palettes {
  MatrixPalette matrices;
  DualQuatPalette dual_quats;  // only when every scale is 1
  MotorPalette motors;
};

Palettes make_palettes(const std::vector<Transform>& xs) {
  Palettes p;
  bool rigid = true;
  for (const Transform& x : xs) rigid &= x.scale == 1.0f;
  for (const Transform& x : xs) {
    p.matrices.push_back(to_skinning_matrix(x));
    if (rigid) p.dual_quats.push_back(to_dual_quat(x));
    p.motors.push_back(reference_motor(x));
  }
  return p;
}

// Skins `mesh` with `method` and returns the output; fails the test if Run() refuses.
SkinnedOutput skin(SkinningMethod method, const SkinnedMesh& mesh, const Palettes& pal) {
  SkinnedOutput out;
  SkinningJob job = make_skinning_job(method, mesh, out);
  job.matrices = pal.matrices;
  job.dual_quats = pal.dual_quats;
  job.motors = pal.motors;
  INFO("method " << to_string(method) << ": " << job.ValidationError());
  REQUIRE(job.Validate());
  REQUIRE(job.Run());
  return out;
}

glm::vec3 at(const SkinnedOutput& o, std::size_t i) { return {o.px[i], o.py[i], o.pz[i]}; }
glm::vec3 normal_at(const SkinnedOutput& o, std::size_t i) { return {o.nx[i], o.ny[i], o.nz[i]}; }
glm::vec3 rest(const SkinnedMesh& m, std::size_t i) { return {m.px[i], m.py[i], m.pz[i]}; }
glm::vec3 rest_normal(const SkinnedMesh& m, std::size_t i) { return {m.nx[i], m.ny[i], m.nz[i]}; }

float max_distance(const SkinnedOutput& a, const SkinnedOutput& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.px.size(); ++i) worst = testing::nan_max(worst, glm::distance(at(a, i), at(b, i)));
  return worst;
}

float max_normal_distance(const SkinnedOutput& a, const SkinnedOutput& b) {
  float worst = 0.0f;
  for (std::size_t i = 0; i < a.nx.size(); ++i)
    worst = testing::nan_max(worst, glm::distance(normal_at(a, i), normal_at(b, i)));
  return worst;
}

// A valid small job on the random mesh for the validation tests to break one field at a time.
struct ValidFixture {
  SkinnedMesh mesh = make_random_skinned_mesh(100, 8, 7);
  Palettes pal = make_palettes(make_random_transforms(8, 8));
  SkinnedOutput out;
  SkinningJob job(SkinningMethod method) {
    SkinningJob j = make_skinning_job(method, mesh, out);
    j.matrices = pal.matrices;
    j.dual_quats = pal.dual_quats;
    j.motors = pal.motors;
    return j;
  }
};

void require_invalid(const SkinningJob& job, const std::string& reason_part) {
  INFO("expected a failure mentioning '" << reason_part << "', got '" << job.ValidationError() << "'");
  CHECK_FALSE(job.Validate());
  CHECK(job.ValidationError().find(reason_part) != std::string::npos);
  CHECK_FALSE(job.Run());
}

}  // namespace

TEST_CASE("skinning method names round-trip and bad names are rejected", "[skinning]") {
  for (SkinningMethod m : kAllSkinningMethods) CHECK(parse_skinning_method(to_string(m)) == m);
  CHECK(parse_skinning_method("cga_points") == SkinningMethod::cga_points);
  CHECK(to_string(SkinningMethod::cga_motors) == "cga-motors");
  CHECK_THROWS_AS(parse_skinning_method("cga"), std::invalid_argument);
  CHECK_THROWS_WITH(parse_skinning_method("quat"), Catch::Contains("lbs"));
}

TEST_CASE("the reference motor matches the CGA facts on simple cases", "[skinning]") {
  // Pure translation: T = 1 - 1/2 t einf; rotation by pi/2 about z: R = cos(pi/4) - sin(pi/4) e12.
  const Motor t = reference_motor(Transform{glm::vec3(2, 4, 6)});
  CHECK(t.c[blade::e1inf] == Approx(-1.0f));
  CHECK(t.c[blade::e2inf] == Approx(-2.0f));
  CHECK(t.c[blade::e3inf] == Approx(-3.0f));
  Transform r;
  r.rotation = glm::angleAxis(std::numbers::pi_v<float> / 2, glm::vec3(0, 0, 1));
  const Motor rz = reference_motor(r);
  CHECK(rz.c[blade::s] == Approx(std::sqrt(0.5f)));
  CHECK(rz.c[blade::e12] == Approx(-std::sqrt(0.5f)));
  Transform s;
  s.scale = 3.0f;  // d = (1 - 3) / (1 + 3)
  CHECK(reference_motor(s).c[blade::einf0] == Approx(-0.5f));
}

TEST_CASE("a valid job validates and an empty job is valid", "[skinning]") {
  ValidFixture f;
  for (SkinningMethod m : {SkinningMethod::lbs, SkinningMethod::dqs}) {
    const SkinningJob job = f.job(m);
    CHECK(job.ValidationError().empty());
    CHECK(job.Validate());
    CHECK(job.Run());
  }
  SkinningJob empty;
  CHECK(empty.Validate());
  CHECK(empty.Run());
}

TEST_CASE("Validate rejects every malformed job", "[skinning]") {
  ValidFixture f;
  const SkinningJob good = f.job(SkinningMethod::lbs);
  std::vector<float> short_buffer(99, 0.0f);
  std::vector<float> long_buffer(100, 0.0f);

  SECTION("input positions of different sizes") {
    SkinningJob j = good;
    j.in_py = short_buffer;
    require_invalid(j, "input positions");
  }
  SECTION("output positions too small") {
    SkinningJob j = good;
    j.out_pz = std::span<float>(short_buffer);
    require_invalid(j, "output positions");
  }
  SECTION("joints and weights counts") {
    SkinningJob j = good;
    j.joints = j.joints.first(50);
    require_invalid(j, "joint quadruples");
    j = good;
    j.weights = j.weights.first(50);
    require_invalid(j, "weight quadruples");
  }
  SECTION("normals: partial input, missing output, output without input") {
    SkinningJob j = good;
    j.in_nz = {};
    require_invalid(j, "input normals");
    j = good;
    j.out_ny = std::span<float>(short_buffer);
    require_invalid(j, "output normals");
    j = good;
    j.in_nx = j.in_ny = j.in_nz = {};
    require_invalid(j, "output normals given without input normals");
  }
  SECTION("a joint index outside the palette") {
    SkinnedMesh mesh = f.mesh;
    mesh.joints[42][2] = 8;  // the palette has 8 entries
    SkinningJob j = good;
    j.joints = mesh.joints;
    require_invalid(j, "vertex 42 influence 2: joint 8");
    // Even a slot with weight 0 must index the palette: Run() reads it.
    mesh = f.mesh;
    mesh.joints[3] = {0, 1, 2, 65535};
    mesh.weights[3] = {0.5f, 0.25f, 0.25f, 0.0f};
    j.joints = mesh.joints;
    j.weights = mesh.weights;
    require_invalid(j, "joint 65535");
  }
  SECTION("the palette of the chosen method is missing") {
    SkinningJob j = good;
    j.matrices = {};
    require_invalid(j, "outside the lbs palette of 0 entries");
    j = f.job(SkinningMethod::dqs);
    j.dual_quats = std::span<const glm::dualquat>(f.pal.dual_quats).first(3);
    require_invalid(j, "dqs palette of 3 entries");
  }
  SECTION("non-finite weights") {
    SkinnedMesh mesh = f.mesh;
    mesh.weights[99][1] = std::numeric_limits<float>::quiet_NaN();
    SkinningJob j = good;
    j.weights = mesh.weights;
    require_invalid(j, "vertex 99 influence 1: weight nan");
    mesh = f.mesh;
    mesh.weights[0][0] = std::numeric_limits<float>::infinity();
    j.weights = mesh.weights;
    require_invalid(j, "not finite");
  }
  SECTION("palettes larger than a run converts") {
    const std::vector<glm::dualquat> huge(kMaxConvertedPalette + 1, glm::dualquat(glm::quat(1, 0, 0, 0)));
    SkinningJob j = f.job(SkinningMethod::dqs);
    j.dual_quats = huge;
    require_invalid(j, "at most 1024");
  }
  (void)long_buffer;
}

TEST_CASE("lbs equals the weighted sum of GLM 4x4 transforms", "[skinning]") {
  const SkinnedMesh mesh = make_random_skinned_mesh(1000, 16, 11);
  const std::vector<Transform> xs = make_random_transforms(16, 12, 2.0f, 0.5f);
  const SkinnedOutput out = skin(SkinningMethod::lbs, mesh, make_palettes(xs));
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    glm::vec3 expected(0.0f);
    for (int k = 0; k < 4; ++k) expected += mesh.weights[i][k] * reference_transform(xs[mesh.joints[i][k]], rest(mesh, i));
    REQUIRE(glm::distance(at(out, i), expected) < 1e-5f * 4.0f);
    REQUIRE(glm::length(normal_at(out, i)) == Approx(1.0f).margin(1e-5));
  }
}

TEST_CASE("dqs equals GLM's dual-quaternion blend and is rigid for single-bone vertices", "[skinning]") {
  const SkinnedMesh mesh = make_random_skinned_mesh(1000, 16, 21);
  const std::vector<Transform> xs = make_random_transforms(16, 22, 2.0f);
  Palettes pal = make_palettes(xs);
  // Negate half the palette: a dual quaternion and its negation are the same transform, so the
  // antipodality fix must make the result independent of these signs.
  for (std::size_t k = 0; k < pal.dual_quats.size(); k += 2) pal.dual_quats[k] = -pal.dual_quats[k];
  const SkinnedOutput out = skin(SkinningMethod::dqs, mesh, pal);
  std::size_t single_bone = 0;
  for (std::size_t i = 0; i < mesh.vertex_count(); ++i) {
    const auto& j = mesh.joints[i];
    const auto& w = mesh.weights[i];
    glm::dualquat blend = pal.dual_quats[j[0]] * w[0];
    for (int k = 1; k < 4; ++k) {
      const glm::dualquat& q = pal.dual_quats[j[k]];
      blend = blend + q * (glm::dot(pal.dual_quats[j[0]].real, q.real) < 0 ? -w[k] : w[k]);
    }
    const glm::mat3x4 m = glm::mat3x4_cast(glm::normalize(blend));  // GLM's own conversion
    const glm::vec3 expected = transform_point(m, rest(mesh, i));
    REQUIRE(glm::distance(at(out, i), expected) < 1e-5f * 4.0f);
    REQUIRE(glm::length(normal_at(out, i)) == Approx(1.0f).margin(1e-5));
    if (w[0] == 1.0f) {
      ++single_bone;
      REQUIRE(glm::distance(at(out, i), reference_transform(xs[j[0]], rest(mesh, i))) < 1e-5f * 4.0f);
      REQUIRE(glm::distance(normal_at(out, i), xs[j[0]].rotation * rest_normal(mesh, i)) < 1e-5f);
    }
  }
  CHECK(single_bone > 0);  // the rigidity checks above ran
}

TEST_CASE("cga-points equals lbs and cga-motors equals dqs on random rigid palettes", "[skinning][cga]") {
  const float size = 3.0f;  // positions in [-1, 1]^3 moved by up to 2: the character's extent
  for (std::uint32_t seed = 1; seed <= 5; ++seed) {
    const SkinnedMesh mesh = make_random_skinned_mesh(2000, 32, 100 + seed);
    const Palettes pal = make_palettes(make_random_transforms(32, 200 + seed, 2.0f));
    const SkinnedOutput lbs = skin(SkinningMethod::lbs, mesh, pal);
    const SkinnedOutput points = skin(SkinningMethod::cga_points, mesh, pal);
    const SkinnedOutput dqs = skin(SkinningMethod::dqs, mesh, pal);
    const SkinnedOutput motors = skin(SkinningMethod::cga_motors, mesh, pal);
    CHECK(max_distance(points, lbs) < 1e-5f * size);
    CHECK(max_normal_distance(points, lbs) < 1e-5f);
    CHECK(max_distance(motors, dqs) < 1e-5f * size);
    CHECK(max_normal_distance(motors, dqs) < 1e-5f);
    // The two families really differ on this data (else the comparisons above prove little).
    CHECK(max_distance(lbs, dqs) > 1e-2f);
  }
}

TEST_CASE("cga-points equals lbs with scaled bones", "[skinning][cga]") {
  const SkinnedMesh mesh = make_random_skinned_mesh(2000, 32, 300);
  const Palettes pal = make_palettes(make_random_transforms(32, 301, 2.0f, 0.7f));
  CHECK(max_distance(skin(SkinningMethod::cga_points, mesh, pal), skin(SkinningMethod::lbs, mesh, pal)) <
        1e-5f * 6.0f);
}

TEST_CASE("cga-motors scales single-bone vertices exactly (dilation 1.7 on one bone)", "[skinning][cga]") {
  const TwistCylinder cyl = make_twist_cylinder();
  const std::vector<Transform> xs = twist_cylinder_skinning_transforms(cyl.spec, 0.6f, 1.7f);
  const Palettes pal = make_palettes(xs);
  const SkinnedOutput out = skin(SkinningMethod::cga_motors, cyl.mesh, pal);
  REQUIRE(!cyl.bone1_only.empty());
  for (std::uint32_t i : cyl.bone1_only) {
    const glm::vec3 expected = reference_transform(xs[1], rest(cyl.mesh, i));
    REQUIRE(glm::distance(at(out, i), expected) < 1e-5f * cyl.spec.length);
    // Scaled about the joint: the radius grows by exactly 1.7.
    REQUIRE(std::hypot(out.px[i], out.py[i]) == Approx(1.7f * cyl.spec.radius).epsilon(1e-5));
    REQUIRE(glm::distance(normal_at(out, i), xs[1].rotation * rest_normal(cyl.mesh, i)) < 1e-5f);
  }
  for (std::uint32_t i : cyl.bone0_only) REQUIRE(glm::distance(at(out, i), rest(cyl.mesh, i)) < 1e-6f);
}

namespace {

// Smallest and largest distance from the axis of the middle ring's skinned vertices.
std::pair<float, float> middle_radius(const TwistCylinder& cyl, const SkinnedOutput& out) {
  float lo = std::numeric_limits<float>::max(), hi = 0.0f;
  for (std::uint32_t i : cyl.middle_ring) {
    const float r = std::hypot(out.px[i], out.py[i]);
    lo = testing::nan_min(lo, r);
    hi = testing::nan_max(hi, r);
  }
  return {lo, hi};
}

}  // namespace

TEST_CASE("twist cylinder: the linear methods collapse at 180 degrees, motor/dual-quaternion blending does not",
          "[skinning]") {
  const TwistCylinder cyl = make_twist_cylinder();
  REQUIRE(cyl.middle_ring.size() == static_cast<std::size_t>(cyl.spec.segments));
  const Palettes pal = make_palettes(twist_cylinder_skinning_transforms(cyl.spec, std::numbers::pi_v<float>));

  const auto [lbs_lo, lbs_hi] = middle_radius(cyl, skin(SkinningMethod::lbs, cyl.mesh, pal));
  // README's figures (0.000 and 1.000 of the radius, three decimals): within 5e-4 of them.
  CHECK(lbs_hi < 5e-4f * cyl.spec.radius);  // half of p plus half of -p: the axis
  const auto [dqs_lo, dqs_hi] = middle_radius(cyl, skin(SkinningMethod::dqs, cyl.mesh, pal));
  CHECK(dqs_lo > 0.9995f * cyl.spec.radius);
  CHECK(dqs_hi < 1.0005f * cyl.spec.radius);

  const auto [pts_lo, pts_hi] = middle_radius(cyl, skin(SkinningMethod::cga_points, cyl.mesh, pal));
  CHECK(pts_hi < 5e-4f * cyl.spec.radius);
  const auto [mot_lo, mot_hi] = middle_radius(cyl, skin(SkinningMethod::cga_motors, cyl.mesh, pal));
  CHECK(mot_lo > 0.9995f * cyl.spec.radius);
  CHECK(mot_hi < 1.0005f * cyl.spec.radius);
}

TEST_CASE("the twist cylinder's weights and rings", "[skinning]") {
  const TwistCylinder cyl = make_twist_cylinder({.radius = 0.5f, .length = 2.0f, .segments = 8, .rings = 10});
  CHECK(cyl.spec.rings == 11);
  CHECK(cyl.mesh.vertex_count() == 88);
  CHECK(cyl.mesh.indices.size() == 10u * 8u * 6u);
  for (std::size_t i = 0; i < cyl.mesh.vertex_count(); ++i) {
    CHECK(cyl.mesh.weights[i][0] + cyl.mesh.weights[i][1] == Approx(1.0f));
    CHECK(std::hypot(cyl.mesh.px[i], cyl.mesh.py[i]) == Approx(0.5f));
  }
  for (std::uint32_t i : cyl.middle_ring) CHECK(cyl.mesh.weights[i][1] == 0.5f);
  CHECK_THROWS_AS(make_twist_cylinder({.radius = 0.0f}), std::invalid_argument);
}
