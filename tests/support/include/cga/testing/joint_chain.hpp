// The n-joint chain script: the shape of ga-benchmark's arm (bench/ik_arm/arm5.clu) for any number of
// joints, to measure how compile time and op count grow with a script's length (tests/gen/test_chains.cpp,
// bench/bench_generator.cpp). Header-only, no dependencies.
//
// Joint k (1-based) sits at (150 k, 0, 200 k) in the rest pose and turns about z (odd k) or y (even k),
// through its own point. Its rotor is the 4th-order Taylor series of exp of half its angle times its line;
// the line is carried along by V(k-1) = R(k-1) ... R1, the product of the joints before it, which each
// joint's statement extends by one factor. Outputs: every rotor R<k> and the end point E.
//
// explicit_chain_script(n) is the same chain as ga-benchmark writes its arm: each joint's carrier is the
// explicit product of all earlier rotors, C<k> = R<k-1>*...*R2*R1, written out again in every statement
// (and the end point's sandwich writes it out inline), so nothing is shared unless the generator sees the
// products (gen/expand/words.hpp). The joints, angles and outputs are those of joint_chain_script(n).
#pragma once

#include <string>

namespace cga::testing {

namespace detail {

inline std::string num(int v) { return std::to_string(v); }

// The two macros, under a first line that names the chain.
inline std::string chain_preamble(const std::string& title) {
  return "// " + title + " (cga/testing/joint_chain.hpp)\n"
         "expp = {\n  x = _P(1);\n  1 + x + x*x/2 + x*x*x/6 + x*x*x*x/24\n}\n"
         "up3 = {\n  _P(1)*e1 + _P(2)*e2 + _P(3)*e3 + 0.5*(_P(1)*_P(1) + _P(2)*_P(2) + _P(3)*_P(3))*einf + e0\n}\n";
}

// Joint k's line in the rest pose: through (150 k, 0, 200 k), along z (odd k) or y (even k).
inline std::string rest_line(int k) {
  const std::string x = num(150 * k), z = num(200 * k);
  const std::string other = k % 2 ? "up3(" + x + ", 0, " + num(200 * k + 1) + ")" : "up3(" + x + ", 1, " + z + ")";
  return "*(up3(" + x + ", 0, " + z + ") ^ " + other + " ^ einf)";
}

// The end point's sandwich by the versor `v` (a name or a parenthesized product).
inline std::string end_point(int joints, const std::string& v) {
  return "?E = " + v + " * up3(" + num(150 * joints + 100) + ", 0, " + num(200 * joints) + ") * ~" + v + ";\n";
}

}  // namespace detail

inline std::string joint_chain_script(int joints) {
  using detail::num;
  std::string s = detail::chain_preamble(num(joints) + "-joint chain");
  for (int k = 1; k <= joints; ++k) {
    const std::string K = num(k), rest = detail::rest_line(k);
    if (k == 1) {
      s += "L1 = " + rest + ";\n";
    } else {
      const std::string V = "V" + num(k - 1);
      s += "L" + K + " = " + V + " * " + rest + " * ~" + V + ";\n";
    }
    s += "?R" + K + " = expp(ang" + K + "*L" + K + "/2);\n";
    s += "V" + K + " = " + (k == 1 ? std::string("R1") : "R" + K + "*V" + num(k - 1)) + ";\n";
  }
  return s + detail::end_point(joints, "V" + num(joints));
}

inline std::string explicit_chain_script(int joints) {
  using detail::num;
  auto carrier = [&](int k) {  // R<k-1>*...*R1
    std::string c;
    for (int j = k - 1; j >= 1; --j) c += (j == k - 1 ? "" : "*") + std::string("R") + num(j);
    return c;
  };
  std::string s = detail::chain_preamble(num(joints) + "-joint chain with explicit products");
  for (int k = 1; k <= joints; ++k) {
    const std::string K = num(k);
    s += "L" + K + "init = " + detail::rest_line(k) + ";\n";
    if (k == 1) {
      s += "L1 = L1init;\n";
    } else {
      s += "C" + K + " = " + carrier(k) + ";\n";
      s += "L" + K + " = C" + K + " * L" + K + "init * ~C" + K + ";\n";
    }
    s += "?R" + K + " = expp(ang" + K + "*L" + K + "/2);\n";
  }
  return s + detail::end_point(joints, "(" + carrier(joints + 1) + ")");
}

}  // namespace cga::testing
