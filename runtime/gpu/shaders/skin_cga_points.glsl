// cga_points: the paper's appendix A.2. An entry is a motor as the paper's mat3x4 (blade k at column k/4,
// row k%4), 3 vec4s. Each bone moves the point by its motor, X' = M X ~M divided by its weight, and the
// Euclidean points are averaged with the skin weights. The point transform of a motor is affine in the point,
// so it is the generated staged point transform on the motor's split form (G = a + b, H = a - b, U: see
// transform_point_split.clu; the blade form's weight cancels for scaled motors): transform_point_split_prepare
// (the weight-normalized 3x4 as a mat3x4), then its per-element body on the point and the normal, blended.
const int PALETTE_STRIDE = 3;

mat3x4 palette_motor(int e) {
  return mat3x4(palette_at(PALETTE_STRIDE * e), palette_at(PALETTE_STRIDE * e + 1), palette_at(PALETTE_STRIDE * e + 2));
}


void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  op = vec3(0.0);
  on = vec3(0.0);
  for (int k = 0; k < 4; ++k) {
    vec4 G, H, U;
    motor_split(palette_motor(base + j[k]), G, H, U);
    mat3x4 prepared;
    transform_point_split_prepare(G, H, U, prepared);
    vec3 tp, tn;
    transform_point_split(prepared, p.x, p.y, p.z, n.x, n.y, n.z, tp, tn);
    op += w[k] * tp;
    if (normals) on += w[k] * tn;
  }
  if (normals) on = normalize(on);
}
