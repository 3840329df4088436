// The picture of the candy-wrapper test on the GL backend (tests/gpu and the demo; needs cga::gpu).
#pragma once

#include <span>
#include <vector>

#include <glm/glm.hpp>

#include "cga/gpu/render.hpp"
#include "cga/testing/skinning_test_meshes.hpp"

namespace cga::gpu {

// The two-bone twist cylinder (cga::make_twist_cylinder) with joint 1 twisted by `angle` radians, skinned
// on the GPU by each of `methods` (default every method, in the table's order), side by side, each panel
// labelled with its method.
// At 180 degrees lbs and cga-points collapse to a "candy wrapper" in the middle, dqs, cga-motors and cga-log
// do not.
// The one camera of every twist-strip panel, on the GPU and in the demo's CPU pictures: the rest cylinder's
// box, seen from the side and a little above, axis up.
inline Camera twist_strip_camera(const TwistCylinderSpec& spec) {
  Camera camera;
  camera.fit_axes = false;
  camera.up = {0.0f, 0.0f, 1.0f};
  camera.direction = glm::normalize(glm::vec3(-1.0f, -0.35f, -0.25f));
  camera.fit_box = false;
  camera.box_min = {-spec.radius, -spec.radius, 0.0f};
  camera.box_max = {spec.radius, spec.radius, spec.length};
  return camera;
}

inline Image render_twist_strip(const Context& context, float angle = 3.14159265f, int panel_width = 256,
                                int height = 384, std::span<const SkinningMethod> methods = kAllSkinningMethods) {
  const TwistCylinder cylinder = make_twist_cylinder();
  const std::vector<Transform> bones = twist_cylinder_skinning_transforms(cylinder.spec, angle);
  return render_method_strip(context, cylinder.mesh, bones, twist_strip_camera(cylinder.spec), panel_width, height,
                             methods);
}

}  // namespace cga::gpu
