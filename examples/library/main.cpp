// cga-library-example: the generated 3D PGA library (libraries/pga3.gal) on the CPU and in a GL compute
// shader. A motor m = exp(angle/2 * axis) turns points about the x axis; the C++ library applies it with
// pga3::sandwich, the shader with pga3_sandwich from pga3.glsl, and both are checked against plain
// trigonometry. Exit status 0 when every point agrees within 1e-5, 1 otherwise (2: no GL context).
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include "cga/gpu/context.hpp"
#include "pga3.hpp"  // generated: namespace pga3

namespace {

// A point's blades (pga3.gal): e0^e2^e3 e0^e1^e3 e0^e1^e2 e1^e2^e3. The Euclidean point (x, y, z) is
// x e032 + y e013 + z e021 + e123, so e0^e2^e3 = -x, e0^e1^e3 = y, e0^e1^e2 = -z and the weight e1^e2^e3 = 1.
pga3::point make_point(float x, float y, float z) { return pga3::point{{-x, y, -z, 1.0f}}; }
void euclidean(const float v[4], float out[3]) {
  out[0] = -v[0] / v[3];
  out[1] = v[1] / v[3];
  out[2] = -v[2] / v[3];
}

const char* kShader = R"(
layout(local_size_x = 1) in;
layout(std430, binding = 0) readonly buffer In { float xin[]; };
layout(std430, binding = 1) writeonly buffer Out { float xout[]; };
uniform float angle;
void main() {
  uint i = gl_WorkGroupID.x;
  pga3_line axis = pga3_line(float[6](0.0, 0.0, 0.0, 1.0, 0.0, 0.0));  // e2^e3: the x axis
  pga3_motor m = pga3_exp(pga3_scale(0.5 * angle, axis));
  pga3_point p = pga3_point(float[4](xin[4u * i], xin[4u * i + 1u], xin[4u * i + 2u], xin[4u * i + 3u]));
  pga3_point q = pga3_sandwich(m, p);
  for (int k = 0; k < 4; ++k) xout[4u * i + uint(k)] = q.v[k];
}
)";

}  // namespace

int main() {
  const float angle = 0.7f;
  const pga3::line axis{{0, 0, 0, 1, 0, 0}};  // e2^e3: the x axis
  const pga3::motor m = pga3::exp(0.5f * angle * axis);
  std::vector<float> points;
  for (int i = 0; i < 64; ++i) {
    const pga3::point p = make_point(std::sin(0.3f * i), 0.1f * i - 3.0f, std::cos(0.7f * i));
    points.insert(points.end(), p.v, p.v + 4);
  }
  // Plain trigonometry: m p ~m with m = exp(angle/2 e2^e3) turns by `angle` about x, from z towards y
  // (clockwise seen from +x).
  auto expected = [&](const float* p, float out[3]) {
    float e[3];
    euclidean(p, e);
    const float c = std::cos(angle), s = std::sin(angle);
    out[0] = e[0];
    out[1] = c * e[1] + s * e[2];
    out[2] = c * e[2] - s * e[1];
  };
  double worst_cpu = 0, worst_gpu = 0;
  std::vector<float> want(points.size() / 4 * 3);
  for (size_t i = 0; i < points.size() / 4; ++i) {
    const pga3::point p{{points[4 * i], points[4 * i + 1], points[4 * i + 2], points[4 * i + 3]}};
    const pga3::point q = pga3::sandwich(m, p);
    float got[3];
    euclidean(q.v, got);
    expected(p.v, &want[3 * i]);
    for (int k = 0; k < 3; ++k) worst_cpu = std::fmax(worst_cpu, std::fabs(got[k] - want[3 * i + k]));
  }
  try {
    cga::gpu::Context ctx;
    std::ifstream f(PGA3_GLSL);
    std::stringstream library;
    library << f.rdbuf();
    const cga::gpu::ShaderSource src{GL_COMPUTE_SHADER, "pga3 example", "#version 450\n" + library.str() + kShader};
    cga::gpu::Object prog = ctx.make_program(std::span<const cga::gpu::ShaderSource>(&src, 1));
    cga::gpu::Buffer in = ctx.make_buffer(std::span<const float>(points));
    cga::gpu::Buffer out = ctx.make_buffer(points.size() * sizeof(float));
    glUseProgram(prog.get());
    glUniform1f(glGetUniformLocation(prog.get(), "angle"), angle);
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, in.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, out.get());
    ctx.dispatch(prog.get(), static_cast<unsigned>(points.size() / 4));
    ctx.check("dispatch");
    const std::vector<float> q = ctx.read_all<float>(out);
    for (size_t i = 0; i < points.size() / 4; ++i) {
      float got[3];
      euclidean(&q[4 * i], got);
      for (int k = 0; k < 3; ++k) worst_gpu = std::fmax(worst_gpu, std::fabs(got[k] - want[3 * i + k]));
    }
    std::printf("pga3 library: 64 points turned about x; C++ off by %.3g, GLSL (%s) off by %.3g\n", worst_cpu,
                ctx.renderer().c_str(), worst_gpu);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "cga-library-example: %s\n", e.what());
    return 2;
  }
  return worst_cpu < 1e-5 && worst_gpu < 1e-5 ? 0 : 1;
}
