// cga_motors: blend the motors, transform once. An entry is a motor as the paper's mat3x4 (blade k at
// column k/4, row k%4). The motors are blended with the sign fix on the rotor parts (blades 1, e12, e13,
// e23, times 1 + k) against the first influence, in split form (G = a + b, H = a - b, U: see
// motor_split_to_matrix.clu; the blade form's weight cancels for scaled motors); the blend moves the point by
// the weight-normalized matrix of the generated motor_split_to_matrix, so it needs no normalization. Normals
// use the same matrix's linear part.
const int PALETTE_STRIDE = 3;

mat3x4 palette_motor(int e) {
  return mat3x4(palette[PALETTE_STRIDE * e], palette[PALETTE_STRIDE * e + 1], palette[PALETTE_STRIDE * e + 2]);
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
  vec3 c1, c2, c3, t;
  motor_split_to_matrix(G, H, U, c1, c2, c3, t);
  op = c1 * p.x + c2 * p.y + c3 * p.z + t;
  on = normals ? normalize(c1 * n.x + c2 * n.y + c3 * n.z) : vec3(0.0);
}
