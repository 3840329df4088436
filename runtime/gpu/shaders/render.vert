// Draws already-skinned vertices (the transform-feedback output: position, normal interleaved) with a
// view-projection matrix; passes the view-space normal on for Lambert shading.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;

uniform mat4 u_view_projection;
uniform mat3 u_view_rotation;

out vec3 view_normal;

void main() {
  gl_Position = u_view_projection * vec4(in_position, 1.0);
  view_normal = u_view_rotation * in_normal;
}
