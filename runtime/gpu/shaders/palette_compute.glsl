// The palette part of the compute shader: the palettes as in palette.glsl, and the work group's instance's
// palette staged in shared memory in 8 copies, copy c of vec4 u at shared_palette[8 u + c]: copy c lives in
// bank group c (16 B) only and invocation l reads copy l % 8, so the 8 invocations of a quarter warp read 8
// different bank groups whatever their joints (the layout of runtime/cuda, see docs/gpu.md). When the
// palette does not fit (bones x PALETTE_STRIDE x 8 > SHARED_PALETTE_VEC4) palette_at reads the buffer.
layout(std430, binding = 0) readonly buffer Palette { vec4 palette[]; };

const int SHARED_PALETTE_VEC4 = 1536;  // 24 KiB: 64 bones of 3 vec4s in 8 copies
shared vec4 shared_palette[SHARED_PALETTE_VEC4];
bool palette_staged = false;
int palette_first = 0;  // the buffer index of the staged instance's vec4 0

vec4 palette_at(int i) {
  return palette_staged ? shared_palette[((i - palette_first) << 3) + int(gl_LocalInvocationIndex & 7u)]
                        : palette[i];
}
