// cgagen --gpc: Gaalop precompiler (GPC) blocks in a C, C++ or CUDA source (docs/gpc.md).
//
// rewrite() copies the source and replaces each `#pragma gpc begin ... #pragma gpc end` block:
//   - `NAME = mv_from_array(ARRAY, BLADE, ...);` before `#pragma clucalc begin` declares the script input NAME
//     with those blades, read from ARRAY[0], ARRAY[1], ...;
//   - the script between `#pragma clucalc begin` and `#pragma clucalc end` goes through the pipeline
//     (front -> expand -> opt) and is printed as statements (emit/statements.hpp) that declare its outputs;
//   - in the C text after it, to_array(X), ARRAY = mv_to_array(X, BLADE...); and mv_get_bladecoeff(X, BLADE)
//     of an output X become expressions and statements over the declared output.
// `#line` directives map the result to the original file. Faults are front::CompileError located in the
// original source (the script's own errors included), never an exit.
#pragma once

#include <string>
#include <vector>

#include "emit/emit.hpp"
#include "front/diagnostics.hpp"
#include "opt/program.hpp"

namespace cgagen::gpc {

struct Options {
  opt::Level level = opt::Level::O2;
  emit::Target target = emit::Target::Cpp;  // cpp, cuda or opencl (emit::statement_targets())
  std::string type = "float";               // the number type of outputs and temporaries
  std::string line_path;                    // the file name `#line` gives; empty: the SourceFile's path
};

struct Result {
  std::string text;                       // the rewritten source
  std::vector<front::Warning> warnings;   // the scripts' warnings, located in the original source
};

// Uses the thread's current algebra (algebra::use). Throws front::CompileError.
Result rewrite(const front::SourceFile& file, const Options& options);

}  // namespace cgagen::gpc
