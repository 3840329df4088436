// The page's WebGPU shaders (WGSL), after cgagen's generated transform_point_split (WGSL target: array
// values in, pointers to arrays out), which assemble_page.cmake put in front of this file. The same maths
// as skin.vert.glsl (see there and runtime/gpu/shaders/skin_*.glsl); the palette is a storage buffer of
// vec4s, 5 per entry (motor blades 0-11 in Gaalop order, then the rigid part's dual quaternion), and the
// rest mesh a storage buffer of 14 floats per vertex (position, normal, 4 palette indices, 4 weights), read
// by vertex_index (drawIndexed passes the index). cs_skin writes the skinned positions for the self-test.

struct Uniforms {
  view_proj: mat4x4<f32>,
  color: vec4<f32>,
  light: vec4<f32>,
  method: i32,
  heat: i32,
  heat_a: i32,
  heat_b: i32,
  heat_scale: f32,
  vertex_count: u32,
  pad0: u32,
  pad1: u32,
}

@group(0) @binding(0) var<uniform> uni: Uniforms;
@group(0) @binding(1) var<storage, read> palette: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> verts: array<f32>;
@group(0) @binding(3) var<storage, read_write> skinned: array<f32>;

struct Split {
  G: vec4<f32>,
  H: vec4<f32>,
  U: vec4<f32>,
}

struct Affine {
  c1: vec3<f32>,
  c2: vec3<f32>,
  c3: vec3<f32>,
  t: vec3<f32>,
}

fn motor_split(e: i32) -> Split {
  let m0 = palette[5 * e];
  let m1 = palette[5 * e + 1];
  let m2 = palette[5 * e + 2];
  let a = vec4<f32>(m0.xyz, m1.x);
  let b = vec4<f32>(m1.w, m2.yzw);
  return Split(a + b, a - b, vec4<f32>(m0.w, m1.yz, m2.x));
}

// The generated prepare of the staged point transform (transform_point_split.clu, G H U uniform) takes and
// returns f32 arrays; its 12 prepared values are the weight-normalized 3x4 matrix, row r as (translation,
// x, y, z) (slots p.e<r>[1] p.e<r>[x] p.e<r>[y] p.e<r>[z]).
fn split_to_matrix(s: Split) -> Affine {
  var m: array<f32, 12>;
  transform_point_split_prepare(array<f32, 4>(s.G.x, s.G.y, s.G.z, s.G.w), array<f32, 4>(s.H.x, s.H.y, s.H.z, s.H.w),
                                array<f32, 4>(s.U.x, s.U.y, s.U.z, s.U.w), &m);
  return Affine(vec3<f32>(m[1], m[5], m[9]), vec3<f32>(m[2], m[6], m[10]), vec3<f32>(m[3], m[7], m[11]),
                vec3<f32>(m[0], m[4], m[8]));
}

struct Skinned {
  p: vec3<f32>,
  n: vec3<f32>,
}

fn skin(method: i32, j: vec4<i32>, w: vec4<f32>, p: vec3<f32>, n: vec3<f32>) -> Skinned {
  if (method == 0 || method == 2) {
    var s1 = vec3<f32>(0.0);
    var s2 = vec3<f32>(0.0);
    var s3 = vec3<f32>(0.0);
    var st = vec3<f32>(0.0);
    var op = vec3<f32>(0.0);
    for (var k = 0; k < 4; k++) {
      let m = split_to_matrix(motor_split(j[k]));
      if (method == 0) {
        s1 += w[k] * m.c1; s2 += w[k] * m.c2; s3 += w[k] * m.c3; st += w[k] * m.t;
      } else {
        op += w[k] * (m.c1 * p.x + m.c2 * p.y + m.c3 * p.z + m.t);
        s1 += w[k] * m.c1; s2 += w[k] * m.c2; s3 += w[k] * m.c3;
      }
    }
    if (method == 0) {
      op = s1 * p.x + s2 * p.y + s3 * p.z + st;
    }
    return Skinned(op, s1 * n.x + s2 * n.y + s3 * n.z);
  }
  if (method == 1) {
    let r0 = palette[5 * j[0] + 3];
    var r = w[0] * r0;
    var d = w[0] * palette[5 * j[0] + 4];
    for (var k = 1; k < 4; k++) {
      let rk = palette[5 * j[k] + 3];
      let wk = select(w[k], -w[k], dot(r0, rk) < 0.0);
      r += wk * rk;
      d += wk * palette[5 * j[k] + 4];
    }
    let inv = 1.0 / dot(r, r);
    let rotated = (r.w * r.w - dot(r.xyz, r.xyz)) * p + 2.0 * dot(r.xyz, p) * r.xyz + 2.0 * r.w * cross(r.xyz, p);
    let t = 2.0 * (r.w * d.xyz - d.w * r.xyz + cross(r.xyz, d.xyz));
    let rn = (r.w * r.w - dot(r.xyz, r.xyz)) * n + 2.0 * dot(r.xyz, n) * r.xyz + 2.0 * r.w * cross(r.xyz, n);
    return Skinned((rotated + t) * inv, rn);
  }
  let s0 = motor_split(j[0]);
  var G = w[0] * s0.G;
  var H = w[0] * s0.H;
  var U = w[0] * s0.U;
  for (var k = 1; k < 4; k++) {
    let sk = motor_split(j[k]);
    let wk = select(w[k], -w[k], dot(s0.G, sk.G) < 0.0);
    G += wk * sk.G;
    H += wk * sk.H;
    U += wk * sk.U;
  }
  let m = split_to_matrix(Split(G, H, U));
  return Skinned(m.c1 * p.x + m.c2 * p.y + m.c3 * p.z + m.t, m.c1 * n.x + m.c2 * n.y + m.c3 * n.z);
}

fn rest_vertex(v: u32) -> array<f32, 14> {
  var r: array<f32, 14>;
  for (var k = 0u; k < 14u; k++) {
    r[k] = verts[14u * v + k];
  }
  return r;
}

fn skin_vertex(method: i32, v: u32) -> Skinned {
  let r = rest_vertex(v);
  return skin(method, vec4<i32>(i32(r[6]), i32(r[7]), i32(r[8]), i32(r[9])), vec4<f32>(r[10], r[11], r[12], r[13]),
              vec3<f32>(r[0], r[1], r[2]), vec3<f32>(r[3], r[4], r[5]));
}

fn heat_color(x0: f32) -> vec3<f32> {  // 0 blue, 0.5 green, 1 red
  let x = clamp(x0, 0.0, 1.0);
  if (x < 0.5) {
    return mix(vec3<f32>(0.15, 0.25, 0.9), vec3<f32>(0.2, 0.85, 0.3), 2.0 * x);
  }
  return mix(vec3<f32>(0.2, 0.85, 0.3), vec3<f32>(0.95, 0.2, 0.15), 2.0 * x - 1.0);
}

struct VsOut {
  @builtin(position) position: vec4<f32>,
  @location(0) normal: vec3<f32>,
  @location(1) color: vec3<f32>,
}

@vertex
fn vs_main(@builtin(vertex_index) v: u32) -> VsOut {
  let s = skin_vertex(uni.method, v);
  var color = uni.color.xyz;
  if (uni.heat == 1) {
    let a = skin_vertex(uni.heat_a, v);
    let b = skin_vertex(uni.heat_b, v);
    color = heat_color(length(a.p - b.p) / uni.heat_scale);
  }
  return VsOut(uni.view_proj * vec4<f32>(s.p, 1.0), s.n, color);
}

@fragment
fn fs_main(f: VsOut) -> @location(0) vec4<f32> {
  let len = length(f.normal);
  let n = select(vec3<f32>(0.0, 0.0, 1.0), f.normal / len, len > 1e-12);
  let d = abs(dot(n, uni.light.xyz));
  return vec4<f32>(f.color * (0.35 + 0.65 * d), 1.0);
}

@compute @workgroup_size(64)
fn cs_skin(@builtin(global_invocation_id) id: vec3<u32>) {
  if (id.x >= uni.vertex_count) {
    return;
  }
  let s = skin_vertex(uni.method, id.x);
  skinned[3u * id.x] = s.p.x;
  skinned[3u * id.x + 1u] = s.p.y;
  skinned[3u * id.x + 2u] = s.p.z;
}
