// The page's WebGL 2 vertex shader (GLSL ES 3.00), after "#version 300 es" and cgagen's generated
// transform_point_split_prepare (GLSL ES target, array interface), which assemble_page.cmake put in front of it.
// One palette entry = 5 texels of u_palette (RGBA32F, 1024 wide): the motor's 12 blades (Gaalop order,
// the paper's mat3x4) and the dual quaternion of its rigid part (real xyzw, dual xyzw). The skin() functions
// follow runtime/gpu/shaders/skin_*.glsl: lbs blends the per-bone matrices (from the generated kernel),
// dqs blends dual quaternions, cga-points averages the motor-moved points (generated kernel per bone),
// cga-motors blends the motors in split form with the sign fix and calls the generated kernel once.
precision highp float;
precision highp int;
precision highp sampler2D;

uniform sampler2D u_palette;
uniform mat4 u_view_proj;
uniform int u_method;     // 0 lbs, 1 dqs, 2 cga-points, 3 cga-motors
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

vec4 texel(int i) { return texelFetch(u_palette, ivec2(i & 1023, i >> 10), 0); }

// The split form of entry e's motor (see transform_point_split.clu): a = (1 e12 e13 e23) = blades 0 1 2 4,
// b = the same times einf^e0 = blades 7 9 10 11, U = blades 3 5 6 8; G = a + b, H = a - b.
void motor_split(int e, out vec4 G, out vec4 H, out vec4 U) {
  vec4 m0 = texel(5 * e), m1 = texel(5 * e + 1), m2 = texel(5 * e + 2);
  vec4 a = vec4(m0.xyz, m1.x);
  vec4 b = vec4(m1.w, m2.yzw);
  G = a + b;
  H = a - b;
  U = vec4(m0.w, m1.yz, m2.x);
}

// The generated prepare of the staged point transform (transform_point_split.clu, G H U uniform) takes and
// returns float arrays; its 12 prepared values are the weight-normalized 3x4 matrix, row r as (translation,
// x, y, z) (slots p.e<r>[1] p.e<r>[x] p.e<r>[y] p.e<r>[z]), read here as the columns c1 c2 c3 and t.
void split_to_matrix(vec4 G, vec4 H, vec4 U, out vec3 c1, out vec3 c2, out vec3 c3, out vec3 t) {
  float g[4] = float[4](G.x, G.y, G.z, G.w);
  float h[4] = float[4](H.x, H.y, H.z, H.w);
  float u[4] = float[4](U.x, U.y, U.z, U.w);
  float m[12];
  transform_point_split_prepare(g, h, u, m);
  c1 = vec3(m[1], m[5], m[9]);
  c2 = vec3(m[2], m[6], m[10]);
  c3 = vec3(m[3], m[7], m[11]);
  t = vec3(m[0], m[4], m[8]);
}

void bone_matrix(int e, out vec3 c1, out vec3 c2, out vec3 c3, out vec3 t) {
  vec4 G, H, U;
  motor_split(e, G, H, U);
  split_to_matrix(G, H, U, c1, c2, c3, t);
}

void skin(int method, ivec4 j, vec4 w, vec3 p, vec3 n, out vec3 op, out vec3 on) {
  if (method == 0 || method == 2) {
    // lbs: blend the matrices, apply once. cga-points: apply each, blend the points. The same sums in
    // exact arithmetic; both kept apart as on the CPU.
    vec3 s1 = vec3(0.0), s2 = vec3(0.0), s3 = vec3(0.0), st = vec3(0.0);
    op = vec3(0.0);
    for (int k = 0; k < 4; ++k) {
      vec3 c1, c2, c3, t;
      bone_matrix(j[k], c1, c2, c3, t);
      if (method == 0) {
        s1 += w[k] * c1; s2 += w[k] * c2; s3 += w[k] * c3; st += w[k] * t;
      } else {
        op += w[k] * (c1 * p.x + c2 * p.y + c3 * p.z + t);
        s1 += w[k] * c1; s2 += w[k] * c2; s3 += w[k] * c3;
      }
    }
    if (method == 0) op = s1 * p.x + s2 * p.y + s3 * p.z + st;
    on = s1 * n.x + s2 * n.y + s3 * n.z;
  } else if (method == 1) {
    vec4 r0 = texel(5 * j[0] + 3);
    vec4 r = w[0] * r0;
    vec4 d = w[0] * texel(5 * j[0] + 4);
    for (int k = 1; k < 4; ++k) {
      vec4 rk = texel(5 * j[k] + 3);
      float wk = dot(r0, rk) < 0.0 ? -w[k] : w[k];
      r += wk * rk;
      d += wk * texel(5 * j[k] + 4);
    }
    float inv = 1.0 / dot(r, r);
    vec3 rotated = (r.w * r.w - dot(r.xyz, r.xyz)) * p + 2.0 * dot(r.xyz, p) * r.xyz + 2.0 * r.w * cross(r.xyz, p);
    vec3 t = 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz));
    op = (rotated + t) * inv;
    on = (r.w * r.w - dot(r.xyz, r.xyz)) * n + 2.0 * dot(r.xyz, n) * r.xyz + 2.0 * r.w * cross(r.xyz, n);
  } else {
    // cga-motors: blend in split form with the rotor sign fix against the first influence (G's sign).
    vec4 G0, H0, U0;
    motor_split(j[0], G0, H0, U0);
    vec4 G = w[0] * G0, H = w[0] * H0, U = w[0] * U0;
    for (int k = 1; k < 4; ++k) {
      vec4 Gk, Hk, Uk;
      motor_split(j[k], Gk, Hk, Uk);
      float wk = dot(G0, Gk) < 0.0 ? -w[k] : w[k];
      G += wk * Gk;
      H += wk * Hk;
      U += wk * Uk;
    }
    vec3 c1, c2, c3, t;
    split_to_matrix(G, H, U, c1, c2, c3, t);
    op = c1 * p.x + c2 * p.y + c3 * p.z + t;
    on = c1 * n.x + c2 * n.y + c3 * n.z;
  }
}

vec3 heat_color(float x) {  // 0 blue, 0.5 green, 1 red
  x = clamp(x, 0.0, 1.0);
  return x < 0.5 ? mix(vec3(0.15, 0.25, 0.9), vec3(0.2, 0.85, 0.3), 2.0 * x)
                 : mix(vec3(0.2, 0.85, 0.3), vec3(0.95, 0.2, 0.15), 2.0 * x - 1.0);
}

void main() {
  ivec4 j = ivec4(a_joints);
  vec3 p, n;
  skin(u_method, j, a_weights, a_position, a_normal, p, n);
  v_position = p;
  v_normal = n;
  v_color = u_color;
  if (u_heat == 1) {
    vec3 pa, pb, na, nb;
    skin(u_heat_a, j, a_weights, a_position, a_normal, pa, na);
    skin(u_heat_b, j, a_weights, a_position, a_normal, pb, nb);
    v_color = heat_color(length(pa - pb) / u_heat_scale);
  }
  gl_Position = u_view_proj * vec4(p, 1.0);
}
