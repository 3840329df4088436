// Printing of one expression in a target's syntax (one precision): literals, sums, products, math calls and
// selects, spelt by the target's Syntax record. Shared by the file emitter (emit.cpp) and the statement
// emitter (statements.cpp).
#pragma once

#include <ginac/ginac.h>

#include <string>

#include "emit/emit.hpp"
#include "opt/program.hpp"

namespace cgagen::emit {

// Prints expressions in one target's syntax (one precision). `code_names` says how each symbol prints.
class Printer {
 public:
  Printer(Target target, const Precision& prec, const opt::SymbolNames& code_names, opt::CanonicalKeys& keys)
      : target_(target), sx_(target.syntax()), prec_(prec), single_(prec.single), code_(code_names), keys_(keys) {}

  // prec: 0 = any context, 1 = operand of * or /, 2 = needs to be an atom
  std::string print(const GiNaC::ex& e, int prec = 0);

 private:
  std::string print_product(const GiNaC::ex& e, int prec);
  std::string atom(const GiNaC::ex& b);
  std::string select(const GiNaC::ex& b, const std::string& pattern);
  // A literal in the target's spelling (Syntax::constant), and a negated operand (Syntax::negate).
  std::string number(const GiNaC::numeric& v) const;
  std::string negated(const std::string& operand) const;
  // A math call in the target's spelling: prefix + (renamed) name, or a whole pattern from math_names.
  std::string call(const std::string& name, const std::string& args) const;

  Target target_;
  const Syntax& sx_;
  const Precision& prec_;
  bool single_;
  const opt::SymbolNames& code_;
  opt::CanonicalKeys& keys_;
};

}  // namespace cgagen::emit
