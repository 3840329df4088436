// sin and cos for the generated blends of the page's WebGPU module: module-scope functions named sin and cos
// shadow WGSL's built-ins for the whole module (only the generated blends call them). Why not the built-ins:
// WGSL and Vulkan allow sin and cos an absolute error of 2^-11 on [-pi, pi], and SwiftShader (the browser's
// software GPU) uses it; a blend that takes sin of an angle and divides by a small one (cga-log's closed-form
// exp) then misses the CPU's vertices by ~2e-4 of the size, over the page's 1e-4 bound. These err by less
// than 1e-7 (float32 against double on [-10, 10]): Cody-Waite reduction by pi/2 (exact for |x| < 2^9 pi/2,
// far above a blend's half-angles), then the Taylor polynomials on [-pi/4, pi/4] (truncation below 1e-11).
// trig.glsl is the same for WebGL 2.
fn cga_reduce(x: f32) -> vec2<f32> {  // (r, quadrant 0..3) with x = r + quadrant pi/2 (mod 2 pi)
  let k = floor(x * 0.63661977236758134 + 0.5);
  let r = ((x - k * 1.5703125) - k * 4.8375129699707031e-4) - k * 7.5497899548918822e-8;
  return vec2<f32>(r, f32(i32(k) & 3));
}

fn cga_sin_poly(r: f32) -> f32 {
  let r2 = r * r;
  return r + r * r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 + r2 * (1.0 / 362880.0 +
                                                                                   r2 * (-1.0 / 39916800.0)))));
}

fn cga_cos_poly(r: f32) -> f32 {
  let r2 = r * r;
  return 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0 +
                                                                        r2 * (-1.0 / 3628800.0 + r2 / 479001600.0)))));
}

fn sin(x: f32) -> f32 {
  let rq = cga_reduce(x);
  let q = i32(rq.y);
  let v = select(cga_cos_poly(rq.x), cga_sin_poly(rq.x), (q & 1) == 0);
  return select(v, -v, q >= 2);
}

fn cos(x: f32) -> f32 {
  let rq = cga_reduce(x);
  let q = i32(rq.y);
  let v = select(cga_sin_poly(rq.x), cga_cos_poly(rq.x), (q & 1) == 0);
  return select(v, -v, q == 1 || q == 2);
}
