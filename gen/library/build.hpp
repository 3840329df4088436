// The library generator's middle: every operation of the table (ops.hpp) for every type (unary) and ordered
// pair of types (binary) of a spec, as one optimized kernel (the script the row spells, expanded and
// optimized like any script), with its result type. The emitters (library/emit.hpp) print the kernels with
// the target's own records and templates and wrap them in the target's types and operators.
#pragma once

#include <string>
#include <vector>

#include "library/ops.hpp"
#include "library/spec.hpp"
#include "opt/program.hpp"

namespace cgagen::library {

struct Function {
  const Operation* op = nullptr;
  size_t a = 0, b = 0;  // operand types (indices into Library::types); b only for binary operations
  size_t result = 0;    // result type
  opt::Program program; // named after op and types (kernel_name), output r over the result type's blades
};

// An operation that does not exist for its operands: its result is identically 0 (outer of a vector with
// itself), or the operator set refuses it (exp of a vector, the inverse of a null type).
struct Skipped {
  const Operation* op = nullptr;
  size_t a = 0, b = 0;
  std::string reason;
};

// The matrix of a versor's sandwich on a type: the kernel of a alone whose output cJ is sandwich(a, B_J) for
// B_J the J-th blade of type b, in the sandwich's result type, so that sandwich(a, x) = sum_J x_J cJ (a
// motor's 3x4 or 4x4 matrix on points or planes, made once for many elements). For every versor type with the
// scalar blade (rotors, translators, motors) and every type.
struct Matrix {
  size_t a = 0, b = 0, result = 0;  // the versor's type, the type it moves, and the sandwich's result type
  size_t sandwich = 0;              // the sandwich's index in Library::functions
  opt::Program program;             // named matrix_A_B, outputs c0 .. c(n-1) for b's n blades
};

struct Library {
  std::string name;
  std::string algebra;                 // as the spec spells it
  std::shared_ptr<const algebra::Algebra> algebra_ptr;
  std::vector<Alias> aliases;
  std::vector<Type> types;             // "scalar" first, then the spec's, then the generated ones
  std::vector<Function> functions;     // operations in table order; per operation, types in order
  std::vector<Skipped> skipped;
  std::vector<Matrix> matrices;        // per sandwich(a, b) of a type a with the scalar blade, in that order
  size_t declared = 0;                 // types[0 .. declared) are the scalar and the spec's types
};

// The result type of a blade support: the smallest declared type (fewest blades; the first declared on a tie)
// holding every blade of `support`, else a generated one named mv_<hex bit mask of the blades>, its blades in
// the algebra's order. Appends a generated type to lib.types once.
size_t result_type(Library& lib, const std::vector<algebra::BladeIndex>& support);

// Builds every kernel at `level`. Throws only for faults of the generator itself; an operation a type does not
// have is a Skipped entry.
Library build(const Spec& spec, opt::Level level);

// The script of matrix(a, b): n outputs, the sandwiches of b's blades, under the sandwich's rules.
std::string matrix_script(const Type& a, const Type& b, const algebra::Algebra& alg);

// The script of one operation (what build() expands), for `cgagen --library` diagnostics and the docs.
std::string operation_script(const Operation& op, const Type& a, const Type* b, const algebra::Algebra& alg);

}  // namespace cgagen::library
