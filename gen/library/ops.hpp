// The operations a generated library has between its types: one table, one row per operation (name, arity,
// the script expression, the operator a target may spell it with, a description). The generator
// (library/build.cpp) writes each row's script for every type (unary) or ordered pair of types (binary),
// so a new operation is a row here and a line in docs/library.md; nothing else names operations.
#pragma once

#include <string>
#include <vector>

namespace cgagen::library {

struct Operation {
  const char* name;         // the function's name in every target (gp, outer, ...)
  int arity;                // 1 or 2
  const char* expression;   // the script's right-hand side over the inputs a and b
  const char* symbol;       // the C++-family operator ("*", "^", "~"); "" for a named function only
  const char* description;  // one line for the docs and the generated file's comment
  // Versor application: a is promised to be a normalized versor (`#pragma normalized a`), and the result is
  // projected on the grades b's type has (applying a versor keeps grades), so the result has b's type.
  bool sandwich = false;
  // Only for operand types with the scalar blade (log: of a rotor, boost or motor, never a bare bivector).
  bool needs_scalar = false;
};

// Every operation, in the order the generated files list them.
const std::vector<Operation>& operations();

// True when `name` is an operation's name (a type may not be called that: the functions share a namespace).
bool is_operation(const std::string& name);

}  // namespace cgagen::library
