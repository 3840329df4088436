// The page's WebGPU shaders (WGSL). The skinning is not written here: assemble_page.cmake appends the
// methods' generated blends (cgagen's WGSL of runtime/scripts/skin/*.clu) and the glue
// runtime/cmake/SkinningMethods.cmake writes from the method table: skin(method, entries, ...) runs the
// method of that code (its row in the table) on the palette. The palette is a storage buffer of vec4s that
// holds, for the current pose, every method's prepared palette (cga::append_packed_palette) in table order,
// uni.entries entries each; the rest mesh is a storage buffer of 14 floats per vertex (position, normal,
// 4 palette indices, 4 weights), read by vertex_index (drawIndexed passes the index). cs_skin writes the
// skinned positions for the self-test.

struct Uniforms {
  view_proj: mat4x4<f32>,
  color: vec4<f32>,
  light: vec4<f32>,
  method: i32,  // the method's code: its row in the table
  heat: i32,
  heat_a: i32,
  heat_b: i32,
  heat_scale: f32,
  vertex_count: u32,
  entries: i32,  // palette entries of one method
  pad1: u32,
}

@group(0) @binding(0) var<uniform> uni: Uniforms;
@group(0) @binding(1) var<storage, read> palette: array<vec4<f32>>;
@group(0) @binding(2) var<storage, read> verts: array<f32>;
@group(0) @binding(3) var<storage, read_write> skinned: array<f32>;

fn palette_at(i: i32) -> vec4<f32> {
  return palette[i];
}

struct Skinned {
  p: vec3<f32>,
  n: vec3<f32>,
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
  var p: vec3<f32>;
  var n: vec3<f32>;
  skin(method, uni.entries, vec4<i32>(i32(r[6]), i32(r[7]), i32(r[8]), i32(r[9])),
       vec4<f32>(r[10], r[11], r[12], r[13]), vec3<f32>(r[0], r[1], r[2]), vec3<f32>(r[3], r[4], r[5]), &p, &n);
  return Skinned(p, n);
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
