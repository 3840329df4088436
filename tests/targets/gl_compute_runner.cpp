// gl_compute_runner GLSL [NIN NOUT IN OUT]: runs a GLSL 4.50 compute shader (spirv-cross's translation of the
// HLSL wrapper targets_check writes) in the headless GL 4.5 context of cga::gpu (Mesa llvmpipe in CI): SSBO 0
// holds the float input rows, SSBO 1 receives the output rows, one work group per row. Prints the renderer.
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#define GL_GLEXT_PROTOTYPES 1
#include <GL/glcorearb.h>

#include "cga/gpu/context.hpp"

int main(int argc, char** argv) {
  if (argc != 6) {
    std::fprintf(stderr, "usage: gl_compute_runner GLSL NIN NOUT IN OUT\n");
    return 2;
  }
  try {
    std::ifstream f(argv[1]);
    std::stringstream ss;
    ss << f.rdbuf();
    size_t nin = std::strtoul(argv[2], nullptr, 10), nout = std::strtoul(argv[3], nullptr, 10);
    std::vector<float> in;
    std::ifstream fin(argv[4]);
    double v;
    while (fin >> v) in.push_back(static_cast<float>(v));
    size_t rows = in.size() / nin;
    cga::gpu::Context ctx;
    std::printf("%s, %s\n", ctx.renderer().c_str(), ctx.version().c_str());
    cga::gpu::ShaderSource src{GL_COMPUTE_SHADER, argv[1], ss.str()};
    cga::gpu::Object prog = ctx.make_program(std::span<const cga::gpu::ShaderSource>(&src, 1));
    cga::gpu::Buffer bin = ctx.make_buffer(std::span<const float>(in));
    std::vector<float> zeros(rows * nout, 0.0f);
    cga::gpu::Buffer bout = ctx.make_buffer(std::span<const float>(zeros));
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 0, bin.get());
    glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, bout.get());
    ctx.dispatch(prog.get(), static_cast<unsigned>(rows));
    ctx.check("dispatch");
    std::vector<float> out = ctx.read_all<float>(bout);
    std::ofstream fo(argv[5]);
    char buf[64];
    for (size_t i = 0; i < out.size(); ++i) {
      std::snprintf(buf, sizeof buf, "%.17g", static_cast<double>(out[i]));
      fo << buf << ((i + 1) % nout ? " " : "\n");
    }
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gl_compute_runner: %s\n", e.what());
    return 1;
  }
}
