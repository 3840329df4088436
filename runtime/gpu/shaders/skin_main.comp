// Crowd-skinning compute shader: work group (x, i) skins vertices of the rest mesh for instance i with
// instance i's palette. Layout per vertex: position 3 floats in, joints as ushort4 (read as
// a uvec2), weights vec4, position 3 floats out; normals (3 floats in and out) only when u_normals.
// Instance i's outputs are vertices [i * u_vertex_count, (i + 1) * u_vertex_count). With
// u_per_instance_inputs the inputs hold one copy of the rest mesh per instance, laid out the same way, and
// instance i reads its own copy; otherwise every instance reads the one rest mesh.
// Work group (x, i): 256 invocations skin vertices [1024 x, 1024 (x + 1)) of instance i, 4 each, 256 apart
// (each pass coalesced), after staging instance i's palette in shared memory (palette_compute.glsl): one
// staging per 1024 vertices.
layout(local_size_x = 256) in;
const uint VERTICES_PER_INVOCATION = 4u;

layout(std430, binding = 1) readonly buffer InPositions { float in_positions[]; };
layout(std430, binding = 2) readonly buffer InNormals { float in_normals[]; };
layout(std430, binding = 3) readonly buffer InJoints { uvec2 in_joints[]; };
layout(std430, binding = 4) readonly buffer InWeights { vec4 in_weights[]; };
layout(std430, binding = 5) writeonly buffer OutPositions { float out_positions[]; };
layout(std430, binding = 6) writeonly buffer OutNormals { float out_normals[]; };

uniform uint u_vertex_count;
uniform int u_bone_count;
uniform bool u_normals;
uniform bool u_per_instance_inputs;

void main() {
  uint instance = gl_WorkGroupID.y;
  int vec4s = u_bone_count * PALETTE_STRIDE;
  palette_first = int(instance) * vec4s;
  // Uniform across the work group (a uniform), so barrier() stays in uniform control flow.
  if (vec4s * 8 <= SHARED_PALETTE_VEC4) {
    for (int s = int(gl_LocalInvocationIndex); s < vec4s * 8; s += 256) shared_palette[s] = palette[palette_first + (s >> 3)];
    barrier();
    palette_staged = true;
  }
  for (uint k = 0u; k < VERTICES_PER_INVOCATION; ++k) {
    uint v = gl_WorkGroupID.x * 256u * VERTICES_PER_INVOCATION + k * 256u + gl_LocalInvocationIndex;
    if (v >= u_vertex_count) break;
    uint out_v = instance * u_vertex_count + v;
    uint in_v = u_per_instance_inputs ? out_v : v;
    uvec2 jp = in_joints[in_v];
    ivec4 j = ivec4(jp.x & 0xffffu, jp.x >> 16, jp.y & 0xffffu, jp.y >> 16);
    vec3 p = vec3(in_positions[3u * in_v], in_positions[3u * in_v + 1u], in_positions[3u * in_v + 2u]);
    vec3 n = u_normals ? vec3(in_normals[3u * in_v], in_normals[3u * in_v + 1u], in_normals[3u * in_v + 2u])
                       : vec3(0.0);
    vec3 op, on;
    skin(int(instance) * u_bone_count, j, in_weights[in_v], p, n, u_normals, op, on);
    uint o = 3u * out_v;
    out_positions[o] = op.x;
    out_positions[o + 1u] = op.y;
    out_positions[o + 2u] = op.z;
    if (u_normals) {
      out_normals[o] = on.x;
      out_normals[o + 1u] = on.y;
      out_normals[o + 2u] = on.z;
    }
  }
}
