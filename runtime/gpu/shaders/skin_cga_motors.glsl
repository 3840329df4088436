// cga_motors: blend the motors, transform once. An entry is a motor as the paper's mat3x4 (blade k at
// column k/4, row k%4). The motors are blended with the sign fix on the rotor parts (blades 1, e12, e13,
// e23, times 1 + k) against the first influence, in split form (G = a + b, H = a - b, U: see
// transform_point_split.clu; the blade form's weight cancels for scaled motors). The blend goes through the
// generated staged point transform: transform_point_split_prepare (the blend's weight-normalized 3x4 as a
// mat3x4, so the blend needs no normalization), then its per-element body on the point and the normal.
const int PALETTE_STRIDE = 3;

mat3x4 palette_motor(int e) {
  return mat3x4(palette_at(PALETTE_STRIDE * e), palette_at(PALETTE_STRIDE * e + 1), palette_at(PALETTE_STRIDE * e + 2));
}


// The blend is taken in split form (linear, so the same blend): a sum of the blade forms of scaled motors
// would round a and b at their size, which is up to s times that of G = a + b. The sign fix reads G (the
// rotor part times 1 + k > 0).
void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  vec4 G0, H0, U0;
  motor_split(palette_motor(base + j[0]), G0, H0, U0);
  vec4 G = w[0] * G0, H = w[0] * H0, U = w[0] * U0;
  for (int k = 1; k < 4; ++k) {
    vec4 Gk, Hk, Uk;
    motor_split(palette_motor(base + j[k]), Gk, Hk, Uk);
    float wk = cga_signed_weight(w[k], dot(G0, Gk));
    G += wk * Gk;
    H += wk * Hk;
    U += wk * Uk;
  }
  mat3x4 prepared;
  transform_point_split_prepare(G, H, U, prepared);
  vec3 tn;
  transform_point_split(prepared, p.x, p.y, p.z, n.x, n.y, n.z, op, tn);
  on = normals ? normalize(tn) : vec3(0.0);
}
