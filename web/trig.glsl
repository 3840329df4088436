// sin and cos for the generated blends of the page's WebGL 2 shader (skin.vert.glsl maps sin and cos to these
// around the blends: GLSL ES forbids redefining a built-in). Why not the built-ins: GLSL ES and Vulkan allow
// sin and cos an absolute error of 2^-11 on [-pi, pi], and SwiftShader (the browser's software GPU) uses it;
// a blend that takes sin of an angle and divides by a small one (cga-log's closed-form exp) then misses the
// CPU's vertices by ~2e-4 of the size, over the page's 1e-4 bound. These err by less than 1e-7 (float32
// against double on [-10, 10]): Cody-Waite reduction by pi/2 (exact for |x| < 2^9 pi/2, far above a blend's
// half-angles), then the Taylor polynomials on [-pi/4, pi/4] (truncation below 1e-11). trig.wgsl is the same
// for WebGPU.
int cga_quadrant(float x, out float r) {
  float k = floor(x * 0.63661977236758134 + 0.5);
  r = ((x - k * 1.5703125) - k * 4.8375129699707031e-4) - k * 7.5497899548918822e-8;
  return int(k) & 3;
}
float cga_sin_poly(float r) {
  float r2 = r * r;
  return r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0 +
                                                                                   r2 * (-1.0 / 39916800.0)))));
}
float cga_cos_poly(float r) {
  float r2 = r * r;
  return 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0 +
                                                                        r2 * (-1.0 / 3628800.0 + r2 / 479001600.0)))));
}
float cga_sin(float x) {
  float r;
  int q = cga_quadrant(x, r);
  float v = (q & 1) == 0 ? cga_sin_poly(r) : cga_cos_poly(r);
  return q >= 2 ? -v : v;
}
float cga_cos(float x) {
  float r;
  int q = cga_quadrant(x, r);
  float v = (q & 1) == 0 ? cga_cos_poly(r) : cga_sin_poly(r);
  return (q == 1 || q == 2) ? -v : v;
}
