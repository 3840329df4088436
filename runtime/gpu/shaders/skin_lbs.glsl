// lbs: linear blend skinning. An entry is a row-major 3x4 matrix (cga::MatrixPalette): 3 vec4 rows,
// p' = (dot(row0, (p,1)), dot(row1, (p,1)), dot(row2, (p,1))). The rows are blended, then applied once.
const int PALETTE_STRIDE = 3;

mat3x4 palette_rows(int e) {
  return mat3x4(palette_at(PALETTE_STRIDE * e), palette_at(PALETTE_STRIDE * e + 1), palette_at(PALETTE_STRIDE * e + 2));
}

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  mat3x4 m = w[0] * palette_rows(base + j[0]) + w[1] * palette_rows(base + j[1]) +
             w[2] * palette_rows(base + j[2]) + w[3] * palette_rows(base + j[3]);
  vec4 h = vec4(p, 1.0);
  op = vec3(dot(m[0], h), dot(m[1], h), dot(m[2], h));
  on = normals ? normalize(vec3(dot(m[0].xyz, n), dot(m[1].xyz, n), dot(m[2].xyz, n))) : vec3(0.0);
}
