// Random well-formed CluScripts for the differential fuzzer: every binary operator (+ - * / . ^), every
// prefix operator (- ~ *), mixed precedence with and without parentheses, the built-ins (VecN3,
// createPoint, SphereN3 in both forms, TranslatorN3, RotorN3, exp, abs, sqrt, sin, cos, atan2, coefficient,
// Normalize, invert, Dual, floor, ceil), macros with _P arguments, pragmas (output, range, in2out-free), if/else
// (comparisons, && || !, else if, names assigned in one branch only) and the
// division forms (by a scalar, a vector, a translator, a rotor). Deterministic for a seed.
#pragma once

#include <cstdint>
#include <map>
#include <string>

namespace diff {

struct Program {
  std::string text;
  std::map<std::string, double> inputs;  // a value for every scalar input the script may read
};

Program generate(std::uint64_t seed);

}  // namespace diff
