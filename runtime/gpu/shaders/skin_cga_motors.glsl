// cga_motors: blend the motors, transform once. An entry is a motor as the paper's mat3x4 (blade k at
// column k/4, row k%4). The 12 coefficients are blended with the sign fix on the rotor parts (blades 1,
// e12, e13, e23 = M[0][0], M[0][1], M[0][2], M[1][0]) against the first influence; the blend moves the
// point by the weight-normalized matrix of the generated motor_split_to_matrix, computed on the blend's split
// form (G = a + b, H = a - b, U: see motor_split_to_matrix.clu; the blade form's weight cancels for scaled
// motors), so the blend needs no normalization. Normals use the same matrix's linear part.
const int PALETTE_STRIDE = 3;

mat3x4 palette_motor(int e) {
  return mat3x4(palette[PALETTE_STRIDE * e], palette[PALETTE_STRIDE * e + 1], palette[PALETTE_STRIDE * e + 2]);
}

float rotor_dot(mat3x4 a, mat3x4 b) { return dot(a[0].xyz, b[0].xyz) + a[1][0] * b[1][0]; }

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  mat3x4 M0 = palette_motor(base + j[0]);
  mat3x4 M = w[0] * M0;
  for (int k = 1; k < 4; ++k) {
    mat3x4 Mk = palette_motor(base + j[k]);
    M += (rotor_dot(M0, Mk) < 0.0 ? -w[k] : w[k]) * Mk;
  }
  // Split form of the blend (layout: skin_cga_points.glsl's motor_split).
  vec4 a = vec4(M[0].xyz, M[1][0]);
  vec4 b = vec4(M[1][3], M[2].yzw);
  vec3 c1, c2, c3, t;
  motor_split_to_matrix(a + b, a - b, vec4(M[0][3], M[1].yz, M[2][0]), c1, c2, c3, t);
  op = c1 * p.x + c2 * p.y + c3 * p.z + t;
  on = normals ? normalize(c1 * n.x + c2 * n.y + c3 * n.z) : vec3(0.0);
}
