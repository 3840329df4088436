// Kernels built by hand (GiNaC symbols + the symbolic Multivector), so that the optimizer and emitter tests
// do not depend on the parser or the expander.
#pragma once

#include <string>
#include <vector>

#include "algebra/blade.hpp"
#include "expand/kernel.hpp"
#include "symbolic/multivector.hpp"

namespace cga_test {

using cgagen::Kernel;
using cgagen::KernelInput;
using cgagen::KernelOutput;
using cgagen::KernelValue;
using cgagen::symbolic::Multivector;

// The 12 blades of a motor T*R*D (facts file order).
inline std::vector<int> motor_blades() {
  std::vector<int> b;
  for (const char* n : {"1", "e1^e2", "e1^e3", "e1^einf", "e2^e3", "e2^einf", "e3^einf", "einf^e0",
                        "e1^e2^e3^einf", "e1^e2^einf^e0", "e1^e3^einf^e0", "e2^e3^einf^e0"})
    b.push_back(cgagen::algebra::parse_blade(n)->index);
  return b;
}

inline KernelInput scalar_input(const std::string& name) {
  return KernelInput{name, false, {0}, {GiNaC::realsymbol(name)}};
}

inline KernelInput mv_input(const std::string& name, const std::vector<int>& blades) {
  KernelInput in{name, true, blades, {}};
  for (int b : blades) in.symbols.push_back(GiNaC::realsymbol(name + "_" + cgagen::algebra::blade_ident(b)));
  return in;
}

inline Multivector as_mv(const KernelInput& in) {
  Multivector m;
  for (size_t i = 0; i < in.blades.size(); ++i) m = m + Multivector::blade(in.blades[i], in.symbols[i]);
  return m;
}

// Appends `name = value` to the kernel and returns the multivector of its symbols (how later values see it).
inline Multivector add_value(Kernel& k, const std::string& name, const Multivector& value) {
  KernelValue v;
  v.name = name;
  Multivector ref;
  for (const auto& [b, c] : value.terms()) {
    v.blades.push_back(b);
    v.coeffs.push_back(c);
    v.symbols.push_back(GiNaC::realsymbol("val" + std::to_string(k.values.size()) + "_" + cgagen::algebra::blade_ident(b)));
    ref = ref + Multivector::blade(b, v.symbols.back());
  }
  k.values.push_back(v);
  return ref;
}

inline void add_output(Kernel& k, const std::string& name, std::vector<int> blades = {}) {
  int vi = -1;
  for (size_t i = 0; i < k.values.size(); ++i)
    if (k.values[i].name == name) vi = static_cast<int>(i);
  KernelOutput o;
  o.name = name;
  o.value = vi;
  o.from_pragma = !blades.empty();
  o.blades = o.from_pragma ? blades : k.values.at(vi).blades;
  k.outputs.push_back(o);
}

inline Multivector up(const GiNaC::ex& x, const GiNaC::ex& y, const GiNaC::ex& z) {
  return Multivector::blade(1, x) + Multivector::blade(2, y) + Multivector::blade(3, z) +
         Multivector::blade(4, (x * x + y * y + z * z) / 2) + Multivector::e0();
}

// transform_point: X = up(x,y,z); P = M*X*~M with a 12-blade motor input, output P on e1 e2 e3 e0.
inline Kernel transform_point_kernel() {
  Kernel k;
  k.name = "transform_point";
  k.inputs.push_back(mv_input("M", motor_blades()));
  for (const char* n : {"x", "y", "z"}) k.inputs.push_back(scalar_input(n));
  Multivector M = as_mv(k.inputs[0]);
  Multivector X = add_value(k, "X", up(k.inputs[1].symbols[0], k.inputs[2].symbols[0], k.inputs[3].symbols[0]));
  add_value(k, "P", M * X * M.reverse());
  add_output(k, "P", {1, 2, 3, 5});
  return k;
}

// A kernel with a shared denominator, a square root, a function call, a dead value and a zero blade:
//   n = sqrt(x*x + y*y); u = (x*e1 + y*e2)/n; dead = sin(x)*e3; ?u; ?s = atan2(y, x) + u.u - 1 (pragma'd 1, e1)
inline Kernel normalize_kernel() {
  Kernel k;
  k.name = "normalize2";
  k.inputs.push_back(scalar_input("x"));
  k.inputs.push_back(scalar_input("y"));
  GiNaC::ex x = k.inputs[0].symbols[0], y = k.inputs[1].symbols[0];
  Multivector n = add_value(k, "n", Multivector(GiNaC::sqrt(x * x + y * y)));
  Multivector u = add_value(k, "u", (Multivector::blade(1, x) + Multivector::blade(2, y)) / n.scalar());
  add_value(k, "dead", Multivector::blade(3, GiNaC::sin(x)));
  add_value(k, "s", Multivector(GiNaC::atan2(y, x)) + inner(u, u) - Multivector(1));
  add_output(k, "u");
  add_output(k, "s", {0, 1});
  return k;
}

}  // namespace cga_test
