// The optimizer's result: straight-line code for one kernel, the form every emitter prints.
//
// A Program is a list of temporaries `name = value` (each value over the inputs' symbols and earlier
// temporaries' symbols) followed by one assignment per output blade. Expressions stay GiNaC expressions;
// how they become text (and what that text costs) is fixed by lower/lower.hpp, shared by the emitters and the
// op counter so that --stats always describes the code that is printed.
#pragma once

#include <ginac/ginac.h>

#include <map>
#include <string>
#include <vector>

#include "algebra/blade.hpp"
#include "expand/kernel.hpp"

namespace cgagen::opt {

enum class Level { O0 = 0, O1 = 1, O2 = 2 };

// "-O2" -> Level::O2; throws std::invalid_argument otherwise.
Level parse_level(const std::string& text);

struct Temp {
  std::string name;   // a C/GLSL identifier, unique in the program, never an input's name
  GiNaC::realsymbol sym;  // how later expressions refer to it (real, as every kernel symbol: expand/kernel.hpp)
  GiNaC::ex value;
};

struct OutputSlot {
  algebra::BladeIndex blade;
  GiNaC::ex value;  // literal 0 for a pragma'd blade that is identically zero
};

struct ProgramOutput {
  std::string name;
  std::vector<OutputSlot> slots;  // in the kernel output's blade order
};

struct Program {
  std::string name;
  std::shared_ptr<const algebra::Algebra> algebra;  // the Kernel's (null: the thread's current algebra)
  Level level = Level::O2;
  std::vector<KernelInput> inputs;
  std::vector<Temp> temps;  // in evaluation order
  std::vector<ProgramOutput> outputs;
  // What the optimizer left out to stay within its work budget (--stats prints these as "note:" lines).
  std::vector<std::string> notes;
  // Names for the elements of an input or output that are not blades (a staged kernel's prepared values,
  // opt/stage.hpp): one label per element. Emitters and reports print these instead of blade names.
  std::map<std::string, std::vector<std::string>> labels;
};

// Kernel -> Program at the given level (see docs/generator.md for what each level does).
// Deterministic: depends only on the kernel's expressions and symbol creation order.
Program optimize(const Kernel& kernel, Level level);

}  // namespace cgagen::opt

#include "lower/lower.hpp"

namespace cgagen::opt {

// The names every symbol of the program prints as: inputs by their GiNaC names, temporaries by theirs.
SymbolNames symbol_names(const Program& program);

// Op counts of the printed code: per output (including the temporaries it needs) and for the whole program.
struct ProgramStats {
  struct Output {
    std::string name;
    OpCounts ops;
  };
  std::vector<Output> outputs;
  OpCounts temps;  // all temporaries together
  OpCounts total;  // every emitted expression once
  size_t temp_count = 0;
};
ProgramStats program_stats(const Program& program);

}  // namespace cgagen::opt
