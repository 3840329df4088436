// The page's WebGL 2 vertex shader (GLSL ES 3.00; app.js puts "#version 300 es" in front). The skinning is
// not written here: assemble_page.cmake replaces the SKINNING marker below with the methods' generated
// blends (cgagen's GLSL ES of runtime/scripts/skin/*.clu) and the glue runtime/cmake/SkinningMethods.cmake
// writes from the method table: skin(method, entries, ...) runs the method of that code (its row in the
// table) on the palette. The palette (u_palette, RGBA32F, 1024 texels wide) holds, for the current pose,
// every method's prepared palette (cga::append_packed_palette) in table order, u_entries entries each.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D u_palette;
uniform int u_entries;    // palette entries of one method
uniform mat4 u_view_proj;
uniform int u_method;     // the method's code: its row in the table
uniform int u_heat;       // 1: colour by the distance between methods u_heat_a and u_heat_b
uniform int u_heat_a;
uniform int u_heat_b;
uniform float u_heat_scale;  // the distance that is full red
uniform vec3 u_color;

in vec3 a_position;
in vec3 a_normal;
in vec4 a_joints;
in vec4 a_weights;

out vec3 v_position;  // captured by transform feedback in the self-test
out vec3 v_normal;
out vec3 v_color;

vec4 palette_at(int i) { return texelFetch(u_palette, ivec2(i & 1023, i >> 10), 0); }

// The generated blends' sin and cos are trig.glsl's cga_sin and cga_cos (see there why).
/*@TRIG@*/
#define sin cga_sin
#define cos cga_cos
/*@SKINNING@*/
#undef sin
#undef cos

vec3 heat_color(float x) {  // 0 blue, 0.5 green, 1 red
  x = clamp(x, 0.0, 1.0);
  return x < 0.5 ? mix(vec3(0.15, 0.25, 0.9), vec3(0.2, 0.85, 0.3), 2.0 * x)
                 : mix(vec3(0.2, 0.85, 0.3), vec3(0.95, 0.2, 0.15), 2.0 * x - 1.0);
}

void main() {
  ivec4 j = ivec4(a_joints);
  vec3 p, n;
  skin(u_method, u_entries, j, a_weights, a_position, a_normal, p, n);
  v_position = p;
  v_normal = n;
  v_color = u_color;
  if (u_heat == 1) {
    vec3 pa, pb, na, nb;
    skin(u_heat_a, u_entries, j, a_weights, a_position, a_normal, pa, na);
    skin(u_heat_b, u_entries, j, a_weights, a_position, a_normal, pb, nb);
    v_color = heat_color(length(pa - pb) / u_heat_scale);
  }
  gl_Position = u_view_proj * vec4(p, 1.0);
}
