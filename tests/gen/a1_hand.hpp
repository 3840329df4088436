// The best hand-written per-bone code we could write for the paper's A.1 (tests/gen/scripts/paper_a1.clu),
// to measure the staged prepare against (the prepare is held within 1.2x of the best hand-written per-bone
// code; docs/generator.md). Hand-written per-bone code for the paper's A.1 (two motors T R D from
// translation, axis, angle, scale; the rigid parts and the dilations blended linearly; the 3x4 matrix and
// weight of the point transform).
// Input order: the script's 17 key parameters. Output: the 13 values of the staged prepare, in its slot
// order: row r (r = e1, e2, e3) as (translation, x, y, z), then the weight.
#pragma once

namespace cga_test {

// Derivation: the rotor of each motor is the 4th-order exponential of a Euclidean bivector B with B^2 = -q,
// so it is (1 - q/2 + q^2/24) + B (1 - q/6) (no powers of B); T R = R - 1/2 (t R) einf. The blend is
// a + c (rotor and einf parts, each linear in alpha) times 1 + k E with k the blended dilation. In the split
// form (runtime/scripts/transform_point_split.clu) G = (1+k) a and H = (1-k) a, so every G_i H_j of the
// linear part is (1-k^2) a_i a_j: the rotation matrix of the unnormalized quaternion a times 1-k^2 (10
// products), the translation (1+k)^2 times the 12 products of t R with a, the weight (1+k)^2 |a|^2.
// Signs (e13 = -(sb vy)) as the script's dual gives them, checked against the staged prepare.
template <class T>
void a1_hand(const T in[17], T out[13]) {
  T a[2][4], tr[2][4], k[2];
  for (int i = 0; i < 2; ++i) {
    const T* m = in + 8 * i;  // transX transY transZ axisX axisY axisZ angle d
    const T vx = m[3], vy = m[4], vz = m[5], angle = m[6], d = m[7];
    // B = -(angle/2) *(v^e0^einf): a Euclidean bivector, B^2 = -q, q = angle^2 |v|^2 / 4; the 4th-order
    // exponential is (1 - q/2 + q^2/24) + B (1 - q/6).
    const T q = angle * angle * (vx * vx + vy * vy + vz * vz);  // 4 q
    const T r0 = T(1) - q * T(0.125) + q * q * T(1.0 / 384);
    const T sb = angle * (T(-0.5) + q * T(1.0 / 48));       // -(angle/2)(1 - q/6)
    a[i][0] = r0;
    a[i][1] = sb * vz;     // e12
    a[i][2] = -(sb * vy);  // e13
    a[i][3] = sb * vx;     // e23
    // t R (vector + e123 part); the translator's -1/2 t einf and the sandwich's factor 2 cancel below.
    const T t1 = m[0], t2 = m[1], t3 = m[2];
    tr[i][0] = t1 * a[i][0] - t2 * a[i][1] - t3 * a[i][2];
    tr[i][1] = t2 * a[i][0] + t1 * a[i][1] - t3 * a[i][3];
    tr[i][2] = t3 * a[i][0] + t1 * a[i][2] + t2 * a[i][3];
    tr[i][3] = t1 * a[i][3] - t2 * a[i][2] + t3 * a[i][1];
    k[i] = (T(1) - d) / (T(1) + d);
  }
  const T alpha = in[16];
  T A[4], C[4];
  for (int j = 0; j < 4; ++j) A[j] = a[0][j] + alpha * (a[1][j] - a[0][j]), C[j] = tr[0][j] + alpha * (tr[1][j] - tr[0][j]);
  const T kk = k[0] + alpha * (k[1] - k[0]);
  const T f1 = T(1) - kk * kk, p = T(1) + kk, f2 = p * p;  // (1+k)(1-k), (1+k)^2
  // G = (1+k) A, H = (1-k) A (split form): the linear part is (1-k^2) times the rotation matrix of A times
  // |A|^2, the translation (1+k)^2 times the products of t R with A, the weight (1+k)^2 |A|^2.
  T fa[4], fa2[4];
  for (int j = 0; j < 4; ++j) fa[j] = f1 * A[j], fa2[j] = fa[j] + fa[j];
  const T s0 = A[0] * fa[0], s1 = A[1] * fa[1], s2 = A[2] * fa[2], s3 = A[3] * fa[3];
  const T p01 = A[0] * fa2[1], p02 = A[0] * fa2[2], p03 = A[0] * fa2[3];
  const T p12 = A[1] * fa2[2], p13 = A[1] * fa2[3], p23 = A[2] * fa2[3];
  T g[4];
  for (int j = 0; j < 4; ++j) g[j] = f2 * A[j];
  out[0] = C[0] * g[0] + C[1] * g[1] + C[2] * g[2] + C[3] * g[3];
  out[1] = s0 + s3 - s1 - s2;
  out[2] = p01 - p23;
  out[3] = p13 + p02;
  out[4] = C[1] * g[0] + C[2] * g[3] - C[0] * g[1] - C[3] * g[2];
  out[5] = -(p01 + p23);
  out[6] = s0 + s2 - s1 - s3;
  out[7] = p03 - p12;
  out[8] = C[2] * g[0] + C[3] * g[1] - C[0] * g[2] - C[1] * g[3];
  out[9] = p13 - p02;
  out[10] = -(p12 + p03);
  out[11] = s0 + s1 - s2 - s3;
  out[12] = (A[0] * A[0] + A[1] * A[1] + A[2] * A[2] + A[3] * A[3]) * f2;
}

}  // namespace cga_test
