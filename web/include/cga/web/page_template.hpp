// The web page template that web/assemble_page.cmake builds from page.html, app.js, the page's shaders and
// cgagen's generated WGSL / GLSL ES kernels; cga-demo --web replaces /*@CGA_DATA@*/ with the data.
#pragma once

#include <string>

namespace cga::web {

std::string page_template();

}  // namespace cga::web
