// cga_points: the paper's appendix A.2. An entry is a motor as the paper's mat3x4 (blade k at column k/4,
// row k%4), 3 vec4s. Each bone moves the point by its motor, X' = M X ~M divided by its weight, and the
// Euclidean points are averaged with the skin weights. The point transform of a motor is affine in the point,
// so it is computed as the generated motor_split_to_matrix of the motor's split form (G = a + b, H = a - b,
// U: see motor_split_to_matrix.clu; the blade form's weight cancels for scaled motors). Normals use the
// same matrix's linear part, blended the same way.
const int PALETTE_STRIDE = 3;

mat3x4 palette_motor(int e) {
  return mat3x4(palette[PALETTE_STRIDE * e], palette[PALETTE_STRIDE * e + 1], palette[PALETTE_STRIDE * e + 2]);
}

// Split form of a motor in the mat3x4 layout: a = (M[0][0], M[0][1], M[0][2], M[1][0]) (1 e12 e13 e23),
// b = (M[1][3], M[2][1], M[2][2], M[2][3]) (einf^e0 and e12, e13, e23 times it), U = (M[0][3], M[1][1],
// M[1][2], M[2][0]) (e1inf e2inf e3inf e123inf).
void motor_split(mat3x4 M, out vec4 G, out vec4 H, out vec4 U) {
  vec4 a = vec4(M[0].xyz, M[1][0]);
  vec4 b = vec4(M[1][3], M[2].yzw);
  G = a + b;
  H = a - b;
  U = vec4(M[0][3], M[1].yz, M[2][0]);
}

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  op = vec3(0.0);
  on = vec3(0.0);
  for (int k = 0; k < 4; ++k) {
    vec4 G, H, U;
    motor_split(palette_motor(base + j[k]), G, H, U);
    vec3 c1, c2, c3, t;
    motor_split_to_matrix(G, H, U, c1, c2, c3, t);
    op += w[k] * (c1 * p.x + c2 * p.y + c3 * p.z + t);
    if (normals) on += w[k] * (c1 * n.x + c2 * n.y + c3 * n.z);
  }
  if (normals) on = normalize(on);
}
