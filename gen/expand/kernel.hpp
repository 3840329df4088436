// A Kernel: what a script computes, as the expand stage leaves it for the optimizer.
//
// Each assignment of the script becomes one KernelValue: a sparse multivector whose coefficients are GiNaC
// expressions over the input symbols and over the coefficient symbols of *earlier* values (so the
// statement structure survives, which -O0 emits as written). Expressions inside one statement, macro calls
// included, are already expanded into that statement's coefficients. The optimizer substitutes values into
// each other (-O1 and up) to get outputs over the inputs alone.
#pragma once

#include <ginac/ginac.h>

#include <memory>
#include <string>
#include <vector>

#include "algebra/algebra.hpp"
#include "algebra/blade.hpp"
#include "front/ast.hpp"
#include "front/diagnostics.hpp"

namespace cgagen {

// One input of the generated function, in order of first use in the script (or of its `input` pragma).
struct KernelInput {
  std::string name;
  // Scalar input: blades == {0} and one symbol named `name`.
  // Multivector input (`#pragma input NAME BLADE...`): the declared blades (in the pragma's order) and one
  // symbol per blade, named NAME_<blade_ident>.
  bool is_multivector = false;
  std::vector<algebra::BladeIndex> blades;
  std::vector<GiNaC::realsymbol> symbols;  // real: abs(a)^2 is a^2; GiNaC keeps the domain in the type
};

// One assignment `name = expr;` of the script. A name assigned twice gives two values.
struct KernelValue {
  std::string name;
  front::SourceLoc loc;
  std::vector<algebra::BladeIndex> blades;  // Gaalop order; blades whose coefficient is not identically 0
  std::vector<GiNaC::ex> coeffs;            // one per blade, over inputs' and earlier values' symbols
  std::vector<GiNaC::realsymbol> symbols;   // one per blade: how later values refer to this coefficient
};

struct KernelOutput {
  std::string name;
  front::SourceLoc loc;
  int value = -1;  // index into Kernel::values: the last assignment of `name` in the script
  // The blades the generated function returns, in this order: those of `#pragma output NAME ...` when
  // given (blades not in the value are returned as 0), else the value's blades.
  std::vector<algebra::BladeIndex> blades;
  // True when `blades` come from `#pragma output`: then every one of them is returned, as literal 0 when
  // its coefficient is (or turns out to be, after optimization) identically zero.
  bool from_pragma = false;
};

struct ScalarRange {  // `#pragma range MIN <= NAME <= MAX`
  std::string name;
  double min = 0, max = 0;
};

struct UniformName {  // one name of `#pragma uniform NAME...`, checked by the staging pass (opt/stage.hpp)
  std::string name;
  front::SourceLoc loc;
};

// A product of the script that the products stage (expand/words.hpp) named once and reused; --stats lists them.
struct SharedProduct {
  std::string name;    // the kernel value that holds it (a script name or a bound temporary)
  std::string word;    // its word, e.g. "R3*T2*R1"
  int uses = 0;        // how many later words took it instead of computing it again
  bool bound = false;  // true when the stage bound it (a sandwich's versor), false for a script's own name
};

struct Kernel {
  std::string name;  // the function name (the script's file stem unless overridden)
  std::shared_ptr<const algebra::Algebra> algebra;  // what the blades and products are in (set by expand())
  std::vector<KernelInput> inputs;
  std::vector<KernelValue> values;    // in script order
  std::vector<KernelOutput> outputs;  // in order of first marking as output
  std::vector<ScalarRange> ranges;
  std::vector<UniformName> uniforms;  // `#pragma uniform` names, in script order
  // `#pragma normalized` names, in script order: multivector inputs the caller promises to pass with
  // X ~X = 1, which -O2 may use (opt/levels.cpp checks the names).
  std::vector<UniformName> normalized;
  std::vector<front::Warning> warnings;  // in script order
  std::vector<SharedProduct> shared_products;  // in order of naming
};

}  // namespace cgagen
