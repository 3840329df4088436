// cga_motors: blend the motors, transform once. An entry is a motor as the paper's mat3x4 (blade k at
// column k/4, row k%4). The 12 coefficients are blended with the sign fix on the rotor parts (blades 1,
// e12, e13, e23 = M[0][0], M[0][1], M[0][2], M[1][0]) against the first influence; the blend moves the
// point with the generated transform_point and the result is divided by its weight (the e0 coefficient),
// so the blend needs no normalization. Normals use the linear part of the generated motor_to_matrix.
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
  vec4 P = transform_point(M, p.x, p.y, p.z);
  op = P.xyz / P.w;
  if (normals) {
    vec3 c1, c2, c3, t;
    motor_to_matrix(M, c1, c2, c3, t);
    on = normalize(c1 * n.x + c2 * n.y + c3 * n.z);
  } else {
    on = vec3(0.0);
  }
}
