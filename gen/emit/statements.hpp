// The statement emitter: a Program as statements to paste into a function body of the user's C, C++ or
// CUDA source (cgagen --gpc, gen/gpc/). Each output is declared as a local of the given number type,
// computed from temporaries in a scope of their own. Expressions print as in the file emitter (printer.hpp),
// through the target's Syntax record: the same literals, math calls and selects.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "emit/emit.hpp"
#include "opt/program.hpp"

namespace cgagen::emit {

struct StatementOptions {
  Target target = Target::Cpp;  // a C-family target: cpp, cuda or opencl (statement_targets())
  std::string type = "float";   // the number type of outputs and temporaries; "float" gives f-suffixed literals
  std::string indent;           // before every line
  std::string temp_prefix;      // before every temporary's name, so that temporaries meet no user name
  // How blade k of a multivector input reads: elements[input][k], a C expression. A multivector input
  // without an entry reads NAME[k]; a scalar input reads the C variable of its name.
  std::map<std::string, std::vector<std::string>> elements;
  // `#line` directives, so that a compiler's message about a statement names the source line it comes from
  // (cgagen --gpc): when line_file (quoted as the directive wants it) is not empty, a `#line N line_file`
  // goes before a statement whenever the compiler would not count its line as N. N is temp_lines[i] for
  // temporary i, output_lines[o] for output o's declaration, slot_lines[o][k] for its blade k; 0 or a
  // missing entry writes none.
  std::string line_file;
  std::vector<int> temp_lines, output_lines;
  std::vector<std::vector<int>> slot_lines;
};

// The targets statements can be printed in.
const std::vector<std::string>& statement_targets();

// The statements, one per line, each line ending in '\n':
//   T r[n];           (an output of n > 1 blades: r[k] is blade k, in the program's order)
//   T s;              (an output of one blade: the variable itself)
//   {                 (only when there are temporaries)
//     const T <prefix>t0 = ...;
//     r[0] = ...;  // e1^e2   (temporaries and elements in print order: opt/order.hpp)
//     (void)r;        (every output: the code after the block may leave some unread)
//   }
// An output without blades (identically zero) declares nothing. Throws std::invalid_argument for a target
// that is not in statement_targets().
std::string emit_statements(const opt::Program& program, const StatementOptions& options);

}  // namespace cgagen::emit
