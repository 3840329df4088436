// An interpreter of CluScript ASTs over the naive oracle (tests/oracle), written from Gaalop's definitions
// and independent of gen/ beyond the parser: the other side of the differential fuzzer. Supports the
// language the generator (generator.hpp) writes, which is most of what cgagen accepts.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "front/ast.hpp"
#include "oracle/multivector.hpp"

namespace diff {

// Long double: a square root of a rounded zero (the magnitude of a null vector) is then ~1e-10, not ~1e-8,
// so the reference stays within the 1e-9 agreement where the exact pipeline gives 0.
using Real = long double;
using MV = oracle::MV<Real>;

// The interpreter refuses a script (a division by a non-invertible multivector, exp of a non-bivector,
// an unknown name) by throwing Refused.
struct Refused : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Outputs {
  std::vector<std::string> order;    // output names in order of first marking
  std::map<std::string, MV> values;  // their values (the last assignment)
};

// Runs the script with the given scalar inputs (a name not in `inputs` that is read before it is assigned
// is refused). A multivector input declared by '#pragma input M BLADE...' reads its coefficients from the
// inputs "M[0]", "M[1]", ... in the pragma's blade order.
Outputs interpret(const cgagen::front::Script& script, const std::map<std::string, double>& inputs);

}  // namespace diff
