// The operation table of generated libraries (ops.hpp). The expressions use the operator set of
// docs/language.md, so every row means exactly what a script means by it.
#include "library/ops.hpp"

namespace cgagen::library {

const std::vector<Operation>& operations() {
  static const std::vector<Operation> table = {
      {"gp", 2, "a * b", "*", "geometric product"},
      {"outer", 2, "a ^ b", "^", "outer (wedge) product"},
      {"inner", 2, "hip(a, b)", "|", "Hestenes inner product (Gaalop's '.')"},
      {"dot", 2, "dot(a, b)", "", "dot product (a scalar times b is that multiple of b)"},
      {"lcont", 2, "lcont(a, b)", "", "left contraction"},
      {"rcont", 2, "rcont(a, b)", "", "right contraction"},
      {"scp", 2, "scp(a, b)", "", "scalar product <a b>_0"},
      {"cp", 2, "cp(a, b)", "", "commutator product (a b - b a) / 2"},
      {"rp", 2, "rp(a, b)", "&", "regressive product (join in PGA)"},
      {"add", 2, "a + b", "+", "sum"},
      {"sub", 2, "a - b", "-", "difference"},
      {"sandwich", 2, "a * b * ~a", "", "a applied to b, a b ~a, for a normalized versor a; keeps b's grades", true},
      {"neg", 1, "-a", "-", "negation"},
      {"reverse", 1, "~a", "~", "reverse"},
      {"involute", 1, "involute(a)", "", "grade involution"},
      {"conjugate", 1, "conjugate(a)", "", "Clifford conjugation"},
      {"dual", 1, "Dual(a)", "!", "dual (the complement map in PGA)"},
      {"undual", 1, "undual(a)", "", "inverse of the dual"},
      {"norm", 1, "abs(a)", "", "magnitude sqrt|<a ~a>_0|"},
      {"norm_sqr", 1, "rnorm_sqr(a)", "", "squared reverse norm <a ~a>_0"},
      {"inverse", 1, "invert(a)", "", "inverse a^-1"},
      {"normalize", 1, "normalize(a)", "", "a / sqrt|<a ~a>_0|"},
      {"exp", 1, "exp(a)", "", "exponential (of a bivector: a rotor, boost or motor)"},
      {"log", 1, "log(a)", "", "logarithm (of a rotor, boost or motor: a bivector)", false, true},
  };
  return table;
}

bool is_operation(const std::string& name) {
  for (const Operation& op : operations())
    if (name == op.name) return true;
  return false;
}

}  // namespace cgagen::library
