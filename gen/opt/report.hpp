// Human-readable reports on Programs: the --stats text, numeric evaluation (--eval) and the --diff of
// two levels.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "opt/program.hpp"

namespace cgagen::opt {

// "kernel NAME at -O2\noutput P: 9 add, 12 mul, 0 div, 0 call\n...total: ...\n"
std::string format_stats(const Program& program);
// "inputs: a, b, M (1, e1^e2)": the kernel's inputs in parameter order, so that a user sees what became an
// input; a multivector input with its blades.
std::string format_inputs(const Program& program);
std::string format_counts(const OpCounts& c);
// The products the expander's products stage named once and reused (expand/words.hpp), one line each:
// "product R2_R1 = R2*R1: bound once, 2 reuses"; "" when there are none.
std::string format_products(const Kernel& kernel);
// "passes: orient, pair-products, ...": the -O2 passes in the order they ran (cgagen --passes describes
// them); "" below -O2.
std::string format_passes(const Program& program);

// Input values by name: one value for a scalar input, one per declared blade for a multivector input.
using InputValues = std::map<std::string, std::vector<double>>;

struct EvalLine {
  std::string output;
  algebra::BladeIndex blade;
  std::string blade_name;  // in the program's algebra
  double value;
};
// Evaluates the program in double precision exactly as the emitted code computes it (same operation
// structure). Throws std::invalid_argument for a missing, unknown or wrongly sized input.
std::vector<EvalLine> evaluate(const Program& program, const InputValues& inputs);
// "OUTPUT BLADE VALUE" lines, values with %.17g.
std::string format_eval(const std::vector<EvalLine>& lines);

// A unified-style line diff ("--- a", "+++ b", "@@" hunks with 3 lines of context); "" when equal.
std::string unified_diff(const std::string& a, const std::string& b, const std::string& name_a,
                         const std::string& name_b);
// The op-count change from a to b, per output and in total.
std::string stats_delta(const Program& a, const Program& b);

}  // namespace cgagen::opt
