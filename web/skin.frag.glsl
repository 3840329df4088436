// The page's WebGL 2 fragment shader: two-sided Lambert shading of the skinned normal.
precision highp float;
in vec3 v_position;
in vec3 v_normal;
in vec3 v_color;
out vec4 frag;
uniform vec3 u_light;
void main() {
  float len = length(v_normal);
  vec3 n = len > 1e-12 ? v_normal / len : vec3(0.0, 0.0, 1.0);
  float d = abs(dot(n, u_light));
  frag = vec4(v_color * (0.35 + 0.65 * d), 1.0);
}
