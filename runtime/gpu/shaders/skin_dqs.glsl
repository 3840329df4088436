// dqs: dual-quaternion skinning (Kavan et al.). An entry is 2 vec4s: real (x, y, z, w), dual (x, y, z, w)
// (cga::pack_dual_quats). Blend with the antipodality fix against the first influence, normalize, apply.
const int PALETTE_STRIDE = 2;

void skin(int base, ivec4 j, vec4 w, vec3 p, vec3 n, bool normals, out vec3 op, out vec3 on) {
  vec4 r0 = palette_at(PALETTE_STRIDE * (base + j[0]));
  vec4 r = w[0] * r0;
  vec4 d = w[0] * palette_at(PALETTE_STRIDE * (base + j[0]) + 1);
  for (int k = 1; k < 4; ++k) {
    vec4 rk = palette_at(PALETTE_STRIDE * (base + j[k]));
    float wk = dot(r0, rk) < 0.0 ? -w[k] : w[k];
    r += wk * rk;
    d += wk * palette_at(PALETTE_STRIDE * (base + j[k]) + 1);
  }
  float inv = 1.0 / dot(r, r);
  // Unnormalized blend b = (r, d): p' = (rotate(r) p) / |r|^2 + 2 (r_w d_v - d_w r_v + r_v x d_v) / |r|^2.
  vec3 rotated = (r.w * r.w - dot(r.xyz, r.xyz)) * p + 2.0 * dot(r.xyz, p) * r.xyz + 2.0 * r.w * cross(r.xyz, p);
  vec3 t = 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz));
  op = (rotated + t) * inv;
  if (normals) {
    vec3 rn = (r.w * r.w - dot(r.xyz, r.xyz)) * n + 2.0 * dot(r.xyz, n) * r.xyz + 2.0 * r.w * cross(r.xyz, n);
    on = normalize(rn);
  } else {
    on = vec3(0.0);
  }
}
