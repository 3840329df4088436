// Zero tests through a chain of definitions by exact evaluation (polynomial identity testing).
//
// The expander sees each statement over the symbols of earlier statements, so "is this coefficient
// identically zero?" is a question about the coefficient with every earlier value inlined down to the
// inputs. Inlining and expanding that answers it exactly but can take seconds (a sandwich of an
// interpolated motor inlines into thousands of rational terms). ProbePoints answers it instead by carrying
// every symbol's value at a few fixed pseudo-random points: an input gets drawn values, a value gets its
// definition evaluated at the values of the symbols it uses. Evaluating one coefficient is then linear in
// the size of its own statement. Values are kept modulo the prime p = 2^61 - 1, so they stay one machine
// word however deep the chain of statements (exact rationals would double in size with every product).
//
// A rational function N/D that is not identically zero vanishes at a point drawn uniformly from F_p^n with
// probability at most deg(N)/p (Schwartz–Zippel), and "zero" needs all kPoints points to vanish, so a wrong
// "zero" needs (deg(N)/2^61)^3 luck. That bound says nothing once deg(N) nears p: (c + s·i)^(2^128) has an
// imaginary part that vanishes at every point of F_p. So a zero verdict also needs a bound on deg(N), the
// degree of the numerator over the common denominator the evaluation forms, of at most kMaxDegree; past
// it the test says so (ZeroPastDegree) and proves nothing. The points are fixed (the same in every process
// and every run), so the verdict is deterministic.
//
// Sums, products, integer powers and rational numbers are evaluated. Every other node (abs, sqrt, sin,
// Pi, x^y, ...) is opaque: it gets a drawn value of its own, as one more input, the same for structurally
// equal nodes. A coefficient that vanishes with its opaque nodes taken as independent inputs vanishes
// whatever their values, so "zero" stands; "nonzero" does not (sin(a)^2 + cos(a)^2 - 1 is nonzero as a
// polynomial in independent sin and cos; abs(a-b) - (a-b) vanishes on half of all points), and such
// coefficients, like those with a pole at a point, get no verdict: callers fall back to other tests.
#pragma once

#include <ginac/ginac.h>

#include <array>
#include <cstdint>
#include <optional>
#include <vector>

#include "symbolic/dag.hpp"

namespace cgagen::symbolic {

// Degree bounds of a rational function N/D as the probes evaluate it: deg N, and D as a product of factors
// (the numerators of inverted subexpressions), each named by its node, so that a sum of terms over the same
// denominator takes it once (their least common multiple), not once per term.
struct RationalDegree {
  struct Factor {
    std::uintptr_t id;      // the inverted node (low bit set: a merged product of factors, see probes.cpp)
    std::uint64_t degree;   // of one factor
    std::uint64_t power;
  };
  std::uint64_t numerator = 0;
  std::vector<Factor> denominator;  // sorted by id
};

class ProbePoints {
 public:
  static constexpr int kPoints = 3;
  // Largest numerator degree a zero verdict stands for: a wrong one then needs (2^-21)^3 = 2^-63 luck.
  static constexpr std::uint64_t kMaxDegree = std::uint64_t{1} << 40;
  // ZeroPastDegree: zero at every point, but of a degree past kMaxDegree, where that proves nothing (and
  // where expanding the value exactly is out of reach too).
  enum class Verdict { Zero, Nonzero, Unknown, ZeroPastDegree };

  // A free symbol (an input): draws its value at every point, in order of calls.
  void add_input(const GiNaC::symbol& s);
  // A symbol standing for `definition` (over symbols added or defined before): its value at every point
  // where the definition evaluates to a rational number. Computed at the first test that needs it, point
  // by point: a nonzero coefficient is usually proved so at the first point, so most values never need the
  // others (nor, when no later statement uses them, even the first), and a value is the same whenever it
  // is computed.
  void define(const GiNaC::symbol& s, const GiNaC::ex& definition);
  // Zero when e evaluates to exactly 0 at every point and its numerator's degree is at most kMaxDegree
  // (ZeroPastDegree when that degree is larger), Nonzero when it is a nonzero rational at some point (and
  // takes no opaque input), Unknown otherwise.
  Verdict test(const GiNaC::ex& e);

 private:
  using Values = ExHashMap<std::optional<std::uint64_t>>;  // symbol -> value in [0, p), or none there
  std::optional<std::uint64_t> value_at_point(const GiNaC::ex& e, int k, bool* opaque_met);
  std::uint64_t numerator_degree(const GiNaC::ex& e);

  std::array<Values, kPoints> at_;  // inputs and the defined symbols evaluated so far
  ExHashMap<GiNaC::ex> definitions_;
  ExHashMap<RationalDegree> degrees_;  // inputs and the defined symbols whose degree was needed
  std::array<ExHashMap<std::uint64_t>, kPoints> opaque_values_;  // each opaque node's value, by structure
  ExHashMap<bool> opaque_symbols_;  // defined symbols whose values take opaque nodes as inputs
  std::uint64_t state_ = 0x243F6A8885A308D3ull;  // fixed: the same points in every run
  std::uint64_t opaque_state_ = 0x13198A2E03707344ull;
};

}  // namespace cgagen::symbolic
