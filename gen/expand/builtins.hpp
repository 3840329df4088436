// The built-in functions of the language (docs/language.md, "Built-in functions"): one table of name,
// argument counts and definition, shared by every algebra (the CGA constructions say so and are refused
// elsewhere). The expander looks a call up here after the script's and the algebra's macros, checks the
// argument count, evaluates the arguments and runs the definition, which may ask the expander for what
// needs its zero tests (Context).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "front/ast.hpp"
#include "symbolic/multivector.hpp"

namespace cgagen::expand_builtins {

using symbolic::Multivector;

// What a definition may ask of the expander.
class Context {
 public:
  virtual ~Context() = default;
  // m without the blades above grade 0 that vanish once earlier values are inlined, when that leaves a scalar.
  virtual Multivector scalar_part_if_scalar(const Multivector& m) = 0;
  // m without the bivector-free blades (grade != 2) that vanish: what exp looks at.
  virtual Multivector bivector_part_if_bivector(const Multivector& m) = 0;
  // m, or, where its coefficients are long expressions, a reference to it bound to temporaries (the cost
  // model's binding, expand/cost.hpp): what exp and log take, so their sign tests and expansions work on
  // symbols and stay bounded in time.
  virtual Multivector bind_if_long(const Multivector& m, front::SourceLoc loc) = 0;
  // Is the coefficient c zero once earlier values are inlined?
  virtual bool vanishes(const GiNaC::ex& c) = 0;
  // a / b as the language's division defines it; errors at `divisor`.
  virtual Multivector divide(const Multivector& a, const Multivector& b, const front::Expr& divisor) = 0;
};

// One call: its name, its evaluated arguments, the call expression (for error locations) and the context.
struct Call {
  const std::string& name;
  std::vector<Multivector>& args;
  const front::Expr& expr;
  Context& ctx;
  // Argument i as a scalar, or a located error naming the function ("'sin' takes a scalar argument, ...").
  GiNaC::ex scalar(size_t i) const;
  // Every argument as a scalar.
  std::vector<GiNaC::ex> scalars() const;
};

struct Builtin {
  std::string name;
  std::vector<size_t> arities;  // the argument counts it takes
  bool cga_only;                // a construction of the CGA null basis (e1 e2 e3 einf e0), refused elsewhere
  std::function<Multivector(const Call&)> define;
};

// Gaalop's abs of a multivector: its magnitude sqrt(|<X ~X>_0|).
Multivector magnitude(const Multivector& m);
// For messages: "e1, e1^e2", and "a multivector with blades e1, e1^e2".
std::string blade_list(const Multivector& m);
std::string describe(const Multivector& m);

// exp and log of scalars, rotors and motors (exponential.cpp).
Multivector exponential(const Call& c);
Multivector logarithm(const Call& c);

// The built-in called `name`, or null.
const Builtin* find(const std::string& name);
// Every built-in's name (for "did you mean" hints).
std::vector<std::string> names();

}  // namespace cgagen::expand_builtins
