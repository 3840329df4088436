// Emitters: Program -> C++ header, GLSL functions or CUDA header, through the text templates in templates/
// (files a user can edit; placeholders are {{name}}). See docs/generator.md for the generated interface.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

#include "opt/program.hpp"

namespace cgagen::emit {

enum class Target { Cpp, Glsl, Cuda };
const std::vector<std::pair<std::string, Target>>& targets();  // every target by its --target name, in order
Target parse_target(const std::string& text);  // a name from targets(); throws std::invalid_argument
std::string file_extension(Target t);          // ".hpp" | ".glsl" | ".cuh"

// How a GLSL parameter is passed: as a float array (default) or packed in a vector/matrix type.
enum class Pack { Array, Mat3x4, Vec4, Vec3, Float };
Pack parse_pack(const std::string& text);  // "mat3x4" | "vec4" | "vec3" | "float"

struct EmitOptions {
  Target target = Target::Cpp;
  std::string template_dir;      // empty: the built-in CGAGEN_TEMPLATE_DIR
  std::string script_name;       // for the header comment (a file name, not a path, to stay reproducible)
  std::map<std::string, Pack> pack;  // GLSL only: input or output name -> packing
  std::string return_output;     // GLSL only: this output is the return value
};

// The whole file text. Throws std::runtime_error on a missing template or a bad pack/return option.
std::string emit(const opt::Program& program, const EmitOptions& options);

// Replaces each {{key}} with values[key]; throws std::runtime_error (naming the template) for a
// placeholder without a value or an unterminated one.
std::string fill_template(const std::string& text, const std::map<std::string, std::string>& values,
                          const std::string& template_name);

// Numeric literal of an exact rational in the target's syntax ("0.5", "0.5f", "(1.0 / 3.0)").
std::string literal(const GiNaC::numeric& value, Target target, bool single_precision);

// BINDIR/../share/cgagen/templates next to the running executable (an installed cgagen, prefix relocatable),
// else the source tree's templates/ (CGAGEN_TEMPLATE_DIR, a cgagen run from its build tree).
std::string default_template_dir();

}  // namespace cgagen::emit
