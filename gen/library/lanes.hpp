// 4-wide forms of a library's kernels. First the bilinear ones: a product of two types whose every result coefficient is
// Σ c · a_i · b_j (every product of the operator set on blade bases) printed as operations on vectors of 4
// floats, the result's coefficients 4 to a vector in storage order, as klein writes its SSE by hand:
//
//   r[4g .. 4g+3] = Σ_i splat(a_i) · (c ⊙ perm_i(b))
//
// one column per coefficient a_i that the group reads: a_i broadcast to 4 lanes times the b coefficients it
// meets in each lane (a shuffle of b's vectors). Coefficients ±1 come with the shuffle, each lane from b or from
// -b; others, or a lane without a term, are a product with a constant vector. The columns are summed as a
// balanced tree. The broadcast operand is a, or b where that takes fewer operations (then the roles swap): in
// a chain x = x * y of one type, x is broadcast and the shuffles of y are off x's critical path.
// The form is kept only where it costs fewer vector operations than the scalar kernel has operations.
//
// Then the kernels linear in b whose coefficients are polynomials of degree 2 or less in a, the sandwich
// a b ~a above all: r = M(a) b, printed as
//
//   r[4g .. 4g+3] = Σ_j splat(b_j) · m_gj,   m_gj = Σ_p splat(a_p) · (c ⊙ perm_p(a)) (+ a constant vector)
//
// The vectors m_gj of M(a) depend on a alone, so b enters at the last product and its sum: in a chain
// x = sandwich(m, x) the matrix of each m is off x's critical path, and in a loop of one versor over many
// elements it is made once. linear_code takes this form or diagonal_code's below, whichever has fewer
// operations. The library keeps it where the result is one vector, whatever its operation count (measured
// faster per call for a motor on a point or a plane), where it is two vectors and has at most 10 % more
// operations than the scalar kernel (a motor on a line, 118 against 114: measured faster), and elsewhere
// where it has fewer.
#pragma once

#include <cstddef>

#include <array>
#include <optional>
#include <string>
#include <vector>

#include "opt/program.hpp"

namespace cgagen::library {

inline constexpr size_t kNone = static_cast<size_t>(-1);  // no factor of that operand

// The C++ spellings of a float constant (9 significant digits) and of a vector of 4 of them.
std::string float_literal(double c);
std::string vector_literal(const std::array<double, 4>& c);

struct LaneTerm {
  size_t i = 0, j = 0;  // a_i * b_j (in the linear form's vectors, a_i * a_j; kNone: a missing factor)
  double c = 0;         // its coefficient
};

struct LaneForm {
  size_t na = 0, nb = 0;                   // the operands' coefficient counts
  std::vector<std::vector<LaneTerm>> out;  // per result coefficient, its terms
};

// The bilinear form of a binary kernel (its temporaries substituted), or nothing where some result
// coefficient is not a sum of numeric multiples of a_i * b_j.
std::optional<LaneForm> lane_form(const opt::Program& program);

struct LaneCode {
  std::string body;   // C++ statements over the helpers of templates/cpp/library/file.in (namespace x4)
  size_t ops = 0;     // vector operations: products, sums, shuffles, sign flips and constant products
};

LaneCode lane_code(const LaneForm& form);

struct LinearTerm {
  size_t p = kNone, q = kNone;  // a_p * a_q, p <= q; kNone where the term has fewer factors of a
  size_t j = 0;                 // times b_j
  double c = 0;
};

struct LinearForm {
  size_t na = 0, nb = 0;
  std::vector<std::vector<LinearTerm>> out;  // per result coefficient, its terms
};

// The form r = M(a) b of a binary kernel, or nothing where some term is not c · b_j times at most two
// coefficients of a.
std::optional<LinearForm> linear_form(const opt::Program& program);

LaneCode linear_code(const LinearForm& form);

// The same form a diagonal of M(a) at a time (diagonals.cpp), as klein writes its sandwiches:
//
//   r[4g .. 4g+3] = Σ_k t_k ⊙ perm_k(b),   t_k = κ_k ⊙ Σ_d ±(perm_u(a) ⊙ perm_v(a)) (+ a constant vector)
//
// Lane l of t_k is the entry of M(a) in row 4g+l and column σ_k(l): a column j that every lane of the group
// reads is one t (perm_k(b) a broadcast of b_j), the other entries lie on cyclic diagonals. Each t's lanes
// are made together from products of two shuffles of a, the terms of each lane assigned to the products by a
// search for the assignment whose shuffles are ones already made (seeded restarts, the same on every run).
// κ_k scales each lane back from coefficients ±1. The search minimizes an estimate of x86 instructions (a
// shuffle of two vectors costs more than one of one); `ops` counts each operation once, as above.
LaneCode diagonal_code(const LinearForm& form);

// The matrix of the same form, M(a) alone: column j (the vectors m_gj above) stored at c<j> + 4g, a column
// without terms as zeros; the statements of a kernel (const float* a, float* c0, ..., float* c<nb-1>).
LaneCode matrix_code(const LinearForm& form);

}  // namespace cgagen::library
