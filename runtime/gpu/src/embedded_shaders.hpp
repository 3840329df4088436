// The GLSL programs assembled at build time (cmake/assemble_shaders.cmake writes their definition).
#pragma once

#include <string_view>
#include <vector>

namespace cga::gpu::detail {

struct EmbeddedShader {
  std::string_view name;  // "skin_cga_motors.vert", "render.frag", ...
  std::string_view path;  // the assembled file in the build tree (what glslangValidator checked)
  std::string_view text;
};

const std::vector<EmbeddedShader>& embedded_shaders();

}  // namespace cga::gpu::detail
