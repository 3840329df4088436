// Crowd-skinning compute shader: invocation (v, i) skins vertex v of the shared rest mesh for instance i
// with instance i's palette. Layout per vertex: position 3 floats in, joints as ushort4 (read as
// a uvec2), weights vec4, position 3 floats out; normals (3 floats in and out) only when u_normals.
// Instance i's outputs are vertices [i * u_vertex_count, (i + 1) * u_vertex_count). With
// u_per_instance_inputs the inputs hold one copy of the rest mesh per instance, laid out the same way, and
// instance i reads its own copy; otherwise every instance reads the one rest mesh.
layout(local_size_x = 128) in;

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
  uint v = gl_GlobalInvocationID.x;
  if (v >= u_vertex_count) return;
  uint instance = gl_GlobalInvocationID.y;
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
