// The batch entry of a lane-wise target (Syntax::batch_*): the stream parameters of a program, the loads of
// its inputs into lanes, the kernel call's arguments and the stores of its outputs, as the function
// template's {{batch_params}}, {{batch_loads}}, {{batch_args}}, {{batch_stores}} and {{batch_names}}.
#pragma once

#include <functional>
#include <string>

#include "emit/emit.hpp"
#include "opt/program.hpp"

namespace cgagen::emit {

struct BatchParts {
  std::string params;  // one stream parameter per input, then per output, joined by ", "
  std::string loads;   // the inputs' lanes, one statement per line (indented, no trailing newline)
  std::string args;    // the kernel's arguments: the inputs' lanes, then the outputs'
  std::string stores;  // the outputs' declarations come first in loads; these store them
  std::string names;   // the stream parameters' names, joined by ", "
};

// Empty parts where the target has no batch entry (Syntax::batch_in empty). `id` spells a name of the file.
BatchParts batch_parts(const Syntax& sx, const opt::Program& program,
                       const std::function<std::string(const std::string&)>& id);

}  // namespace cgagen::emit
