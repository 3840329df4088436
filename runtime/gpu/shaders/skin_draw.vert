// Skinning while drawing (the paper's real path): the vertex shader skins one mesh vertex of character
// gl_InstanceID with its palette (entries [gl_InstanceID * u_bone_count, ...)), moves the character to its
// place on a grid (u_columns per row, u_spacing apart in x and y) and projects it; render.frag shades it.
// Nothing is captured or written back: the skinned vertex exists only on its way to the rasterizer.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in ivec4 in_joints;
layout(location = 3) in vec4 in_weights;

uniform int u_bone_count;
uniform int u_columns;
uniform float u_spacing;
uniform mat4 u_view_projection;
uniform mat3 u_view_rotation;

out vec3 view_normal;

void main() {
  vec3 p, n;
  skin(gl_InstanceID * u_bone_count, in_joints, in_weights, in_position, in_normal, true, p, n);
  vec3 offset = u_spacing * vec3(float(gl_InstanceID % u_columns), float(gl_InstanceID / u_columns), 0.0);
  gl_Position = u_view_projection * vec4(p + offset, 1.0);
  view_normal = u_view_rotation * n;
}
