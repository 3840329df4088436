// Skinning vertex shader (paper appendix A.2 generalized to the four methods): one mesh vertex per
// invocation, instance gl_InstanceID reads palette entries [gl_InstanceID * u_bone_count, ...). The skinned
// position and normal are captured by transform feedback (interleaved: skinned_position, skinned_normal)
// and also drive gl_Position, so the same shader can feed a rasterizer. With u_per_instance_inputs the draw
// is not instanced: the vertex arrays hold one copy of the rest mesh per instance, one after the other, and
// vertex gl_VertexID belongs to instance gl_VertexID / u_vertex_count.
layout(location = 0) in vec3 in_position;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in ivec4 in_joints;
layout(location = 3) in vec4 in_weights;

uniform int u_bone_count;
uniform bool u_normals;
uniform int u_vertex_count;
uniform bool u_per_instance_inputs;

out vec3 skinned_position;
out vec3 skinned_normal;

void main() {
  int instance = u_per_instance_inputs ? gl_VertexID / u_vertex_count : gl_InstanceID;
  skin(instance * u_bone_count, in_joints, in_weights, in_position, in_normal, u_normals,
       skinned_position, skinned_normal);
  gl_Position = vec4(skinned_position, 1.0);
}
