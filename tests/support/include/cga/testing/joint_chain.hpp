// The n-joint chain script: the shape of ga-benchmark's arm (bench/ik_arm/arm5.clu) for any number of
// joints, to measure how compile time and op count grow with a script's length (tests/gen/test_chains.cpp,
// bench/bench_generator.cpp). Header-only, no dependencies.
//
// Joint k (1-based) sits at (150 k, 0, 200 k) in the rest pose and turns about z (odd k) or y (even k),
// through its own point. Its rotor is the 4th-order Taylor series of exp of half its angle times its line;
// the line is carried along by V(k-1) = R(k-1) ... R1, the product of the joints before it, which each
// joint's statement extends by one factor. Outputs: every rotor R<k> and the end point E.
#pragma once

#include <string>

namespace cga::testing {

inline std::string joint_chain_script(int joints) {
  auto num = [](int v) { return std::to_string(v); };
  std::string s =
      "// " + num(joints) + "-joint chain (cga/testing/joint_chain.hpp)\n"
      "expp = {\n  x = _P(1);\n  1 + x + x*x/2 + x*x*x/6 + x*x*x*x/24\n}\n"
      "up3 = {\n  _P(1)*e1 + _P(2)*e2 + _P(3)*e3 + 0.5*(_P(1)*_P(1) + _P(2)*_P(2) + _P(3)*_P(3))*einf + e0\n}\n";
  for (int k = 1; k <= joints; ++k) {
    const std::string K = num(k), x = num(150 * k), z = num(200 * k);
    const std::string other = k % 2 ? "up3(" + x + ", 0, " + num(200 * k + 1) + ")" : "up3(" + x + ", 1, " + z + ")";
    const std::string rest = "*(up3(" + x + ", 0, " + z + ") ^ " + other + " ^ einf)";
    if (k == 1) {
      s += "L1 = " + rest + ";\n";
    } else {
      const std::string V = "V" + num(k - 1);
      s += "L" + K + " = " + V + " * " + rest + " * ~" + V + ";\n";
    }
    s += "?R" + K + " = expp(ang" + K + "*L" + K + "/2);\n";
    s += "V" + K + " = " + (k == 1 ? std::string("R1") : "R" + K + "*V" + num(k - 1)) + ";\n";
  }
  const std::string V = "V" + num(joints);
  s += "?E = " + V + " * up3(" + num(150 * joints + 100) + ", 0, " + num(200 * joints) + ") * ~" + V + ";\n";
  return s;
}

}  // namespace cga::testing
