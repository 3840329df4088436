// A generated library as one file of a target: the kernels printed by the target's own record and templates
// (emit::emit_functions), wrapped by templates/TARGET/library/ in the target's types and operations. A target
// has a library where that folder exists (docs/library.md lists the placeholders).
#pragma once

#include <string>
#include <vector>

#include "emit/emit.hpp"
#include "library/build.hpp"

namespace cgagen::library {

// The file text. `spec_file` is the spec's file name for the header comment. Throws std::runtime_error for a
// target without library templates (naming those that have them) or a template fault.
std::string emit_library(const Library& lib, const emit::EmitOptions& options, const std::string& spec_file);

// The targets that have library templates, in `--target list` order.
std::vector<std::string> library_targets(const std::string& template_dir);

}  // namespace cgagen::library
