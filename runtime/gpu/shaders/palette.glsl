// The skinning palettes of all instances, one after the other (instance i's entry k is entry
// i * u_bone_count + k). An entry is PALETTE_STRIDE vec4s; the method file says how it reads one, through
// palette_at (vec4 i of the buffer). palette_compute.glsl replaces this part in the compute shader.
layout(std430, binding = 0) readonly buffer Palette { vec4 palette[]; };

vec4 palette_at(int i) { return palette[i]; }
