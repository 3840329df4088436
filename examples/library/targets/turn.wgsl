// The generated pga3 library in WGSL (cgagen --library --target wgsl): a WebGPU compute shader turning a point
// about the x axis. The module's code is pga3.wgsl, then this (WGSL has no #include). WGSL has no overloading:
// the operand types are part of each function's name. The entry point is the one tests/targets' browser
// harness runs (cgagen_main, buffers 0 and 1); it writes 1.0 when the turned point is where trigonometry puts it.
fn turn(p: pga3_point, angle: f32) -> pga3_point {
  let axis = pga3_line(array<f32, 6>(0.0, 0.0, 0.0, 1.0, 0.0, 0.0));  // e2^e3: the x axis
  let m = pga3_exp_line(pga3_scale_line(0.5 * angle, axis));           // a motor
  return pga3_sandwich_motor_point(m, p);                              // m p ~m
}

@group(0) @binding(0) var<storage, read> cgagen_in: array<f32>;
@group(0) @binding(1) var<storage, read_write> cgagen_out: array<f32>;

@compute @workgroup_size(64)
fn cgagen_main(@builtin(global_invocation_id) id: vec3<u32>) {
  if (id.x >= 1u) { return; }
  let angle = cgagen_in[0];
  let q = turn(pga3_point(array<f32, 4>(-1.0, 2.0, -3.0, 1.0)), angle);  // (1, 2, 3)
  let got = vec3<f32>(-q.v[0], q.v[1], -q.v[2]) / q.v[3];
  let c = cos(angle);
  let s = sin(angle);
  let want = vec3<f32>(1.0, 2.0 * c + 3.0 * s, 3.0 * c - 2.0 * s);       // from z towards y, as main.cpp
  // WGSL's sin and cos promise only 2^-11 absolute, and SwiftShader's use that room (exp's motor and `want`
  // both call them): tests/targets' bound for them, 4 * 2^-11.
  cgagen_out[0] = select(0.0, 1.0, all(abs(got - want) < vec3<f32>(4.0 * exp2(-11.0))));
}
