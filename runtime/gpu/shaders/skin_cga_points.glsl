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
