// The order in which every emitter prints a Program's assignments: the temporaries in the program's order,
// and each output element as soon as the temporaries it reads are computed, instead of all outputs after
// the last temporary.
//
// Why: a C or C++ compiler allocates registers in about the order the code is written (GCC schedules
// straight-line code for pressure only after register allocation on x86). Outputs printed at the end keep
// every value an output reads live to the end of the function: ga-benchmark's arm chain, with 60 output
// elements, compiled to 117 spill loads and stores of 746 instructions; with each element stored as soon as
// it is computed, to 42 of 640 (docs/generator.md, "Print order").
//
// One restriction keeps the inputs cheap: a store the compiler cannot prove distinct from an input array
// (a caller may pass the same array as input and output) pins every later read of that input above it. So
// no output element is printed before the last temporary that reads a multivector input, and when an output
// element itself reads a multivector input, every output stays after the temporaries, as written.
#pragma once

#include <cstddef>
#include <vector>

#include "opt/program.hpp"

namespace cgagen::opt {

struct Assignment {
  enum class Kind { Temp, Output };
  Kind kind;
  size_t index;  // into program.temps, or into program.outputs
  size_t slot;   // the output's element (Kind::Output only)
};

// Every temporary once and every output element once, temporaries in program order, each after every
// temporary it reads. Deterministic: it depends only on the program.
std::vector<Assignment> print_order(const Program& program);

}  // namespace cgagen::opt
