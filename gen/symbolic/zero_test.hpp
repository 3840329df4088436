// Zero tests of coefficients through a chain of definitions: "is this coefficient, over the inputs and the
// symbols of earlier values, identically zero once those values are inlined down to the inputs?"
//
// The expander asks it for every coefficient it records (a blade whose coefficient vanishes is dropped, so
// sparsity survives from statement to statement) and where an identity matters (a divisor, the argument of
// exp). Each test costs time linear in the coefficient's own statement, never in the chain behind it:
//   1. exact probes modulo a prime (ProbePoints): a verdict for rational functions, and a zero verdict
//      with functions and roots taken as independent inputs;
//   2. a double sample at a fixed point: a coefficient clearly away from 0 is kept at once;
//   3. three double samples at points of either sign: far from 0 at one of them is nonzero;
//   4. for what is left (values under abs, sqrt, sin, ... that come out small at every sample), each
//      coefficient evaluated at two fixed points with 120 significant digits, together with its magnitude
//      (the value it would have if no term of any sum cancelled). Rounding leaves an identically zero
//      value at ~1e-120 of its magnitude (~1e-60 under a square root); a value that is not identically
//      zero is, at a random point, a sizeable fraction of it. Below 1e-50 of the magnitude at both points
//      is "zero", above 1e-30 at one is "nonzero", anything else is undecided. "Zero" counts only for values
//      analytic in the inputs (rational operations, integer powers, sin, cos, exp, ...; abs, roots and the
//      selects of if/else of anything but constants are not): an analytic value that vanishes at random
//      points vanishes everywhere, while abs(a*b) - a*b vanishes on half of them. (A "zero" is also wrong
//      for a value that is nonzero but 1e-50 of its own terms at both points: far below what the generated
//      code's double or float arithmetic could compute anyway.)
//   5. only undecided ones are inlined and expanded exactly, and only while the inlined form stays small
//      (kMaxInlinedNodes); past that the coefficient is kept: a kept zero costs code, never a wrong value.
// Every point is fixed (the same in every process), so every verdict is deterministic.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <cstdint>
#include <map>
#include <set>
#include <optional>

#include "symbolic/dag.hpp"
#include "symbolic/probes.hpp"

namespace cgagen::symbolic {

class ZeroTests {
 public:
  // A free symbol (an input): draws its values at every point, in order of calls.
  void add_input(const GiNaC::symbol& s);
  // A symbol standing for `definition` (over symbols added or defined before). `sample`, when known, is the
  // definition's value at the sample point (what sample() returned for it).
  void define(const GiNaC::symbol& s, const GiNaC::ex& definition, const std::optional<GiNaC::ex>& sample);

  // Is c clearly nonzero by the exact probes alone (the cheap first test)?
  bool probably_nonzero(const GiNaC::ex& c);
  // c at the sample point, or nullopt when c is identically zero with the values inlined. Where c cannot be
  // evaluated there (a pole, a function GiNaC leaves unevaluated) the result is 0 and c is kept.
  std::optional<GiNaC::ex> sample(const GiNaC::ex& c);
  // Is c identically zero once the values are inlined?
  bool vanishes(const GiNaC::ex& c);

 private:
  enum class Verdict { Zero, Nonzero, Unknown };
  GiNaC::ex next_sample();
  double next_signed_value();
  GiNaC::ex signed_sample(const GiNaC::ex& c, size_t k);
  GiNaC::ex sample_at_signed_point(const GiNaC::ex& c, size_t k);
  std::optional<GiNaC::ex> evaluate_at_sample(const GiNaC::ex& c);
  struct Precise {
    GiNaC::numeric value, magnitude;
  };
  using PreciseMap = std::map<GiNaC::ex, std::optional<Precise>, GiNaC::ex_is_less>;  // none: a pole
  Verdict precise_verdict(const GiNaC::ex& c);
  std::optional<Precise> precise_value(const GiNaC::ex& c, size_t point);
  static std::optional<Precise> evaluate_precise(const GiNaC::ex& e, const PreciseMap& at);
  bool exactly_zero(const GiNaC::ex& c);
  bool analytic(const GiNaC::ex& e) const;
  bool varies(const GiNaC::ex& e) const;
  GiNaC::ex inline_values(const GiNaC::ex& e);
  void collect_inlined(const GiNaC::ex& e, GiNaC::exmap& subs);

  ProbePoints probes_;
  // Each value symbol's definition, and (on demand) that definition inlined down to the inputs.
  GiNaC::exmap definitions_;
  GiNaC::exmap inlined_;
  // The value symbols whose inlined definitions are past the exact test's size cap (never expanded), and
  // whether the last inline_values met one.
  std::set<GiNaC::ex, GiNaC::ex_is_less> over_cap_;
  bool met_over_cap_ = false;
  // The value symbols whose definitions are analytic in the inputs (step 4 may call them zero).
  std::set<GiNaC::ex, GiNaC::ex_is_less> analytic_values_;
  // The value symbols whose definitions depend on no input (a point of constants, its magnitude).
  std::set<GiNaC::ex, GiNaC::ex_is_less> constant_values_;
  // One point with inputs in [0.3, 1.7): a cheap first test of whether a coefficient can be zero.
  GiNaC::exmap samples_;
  KeptValues kept_sample_values_;  // large nodes' values at that point (a symbol's never changes)
  std::uint64_t sample_state_ = 0x9E3779B97F4A7C15ull;
  // Three points whose inputs have either sign (magnitudes in [0.3, 1.7)): random signs, the same inputs
  // negated, independent random signs. |d| - d vanishes for every positive d, never for all of these.
  std::array<GiNaC::exmap, 3> signed_samples_;
  std::uint64_t signed_state_ = 0xD1B54A32D192ED03ull;
  // Two points with exact rational inputs of either sign: step 4 above.
  static constexpr size_t kPrecisePoints = 2;
  std::array<PreciseMap, kPrecisePoints> precise_;
  std::uint64_t precise_state_ = 0x94D049BB133111EBull;
};

}  // namespace cgagen::symbolic
