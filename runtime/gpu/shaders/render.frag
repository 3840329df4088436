// Two-sided Lambert shading with a headlight plus a little ambient, in one base colour.
in vec3 view_normal;

uniform vec3 u_color;

layout(location = 0) out vec4 frag_color;

void main() {
  vec3 n = normalize(view_normal);
  // The light sits at the eye, slightly above: view space looks down -z.
  vec3 to_light = normalize(vec3(0.3, 0.5, 1.0));
  float lambert = abs(dot(n, to_light));
  frag_color = vec4(u_color * (0.2 + 0.8 * lambert), 1.0);
}
