// cga_points: the paper's appendix A.2. An entry is a motor as the paper's mat3x4 (blade k at column k/4,
// row k%4), 3 vec4s. Each bone moves the point with the generated transform_point (X' = M X ~M, returned
// as (e1, e2, e3, e0) coefficients); each result is divided by its weight (the e0 coefficient) and the
// Euclidean points are averaged with the skin weights. Normals use the linear part of the generated
// motor_to_matrix of each bone, blended the same way.
const int PALETTE_STRIDE = 3;

mat3x4 palette_motor(int e) {
  return mat3x4(palette[PALETTE_STRIDE * e], palette[PALETTE_STRIDE * e + 1], palette[PALETTE_STRIDE * e + 2]);
}

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  op = vec3(0.0);
  on = vec3(0.0);
  for (int k = 0; k < 4; ++k) {
    mat3x4 M = palette_motor(base + j[k]);
    vec4 P = transform_point(M, p.x, p.y, p.z);
    op += w[k] * (P.xyz / P.w);
    if (normals) {
      vec3 c1, c2, c3, t;
      motor_to_matrix(M, c1, c2, c3, t);
      on += w[k] * (c1 * n.x + c2 * n.y + c3 * n.z);
    }
  }
  if (normals) on = normalize(on);
}
