// The expander's cost model: when a product is worth expanding symbolically, and when its operands are
// bound to named temporaries first.
//
// Expanding a statement symbolically pays while it folds constants, exposes zeros and lets CSE share work:
// a product of operands whose coefficients are single symbols or numbers costs one multiplication per
// pair of blades, and its result is visible to every later pass. It stops paying when the operands'
// coefficients are themselves long sums: the product's coefficients then have (terms of a) x (terms of b)
// terms each, and a chain of such products (M1 M2 M3 X ~M3 ~M2 ~M1) grows exponentially in the chain's
// length while the code that computes it step by step grows linearly.
//
// So before each product the expander measures its cost: the number of terms the product would expand to,
// summed over the pairs of blades that meet (the same count the work budget charges). Past
// kBindProductTerms the operand with the longer coefficients has its blades bound to temporaries (each
// coefficient becomes one symbol; the blade support stays exact, so no sparsity is lost), and the product is
// measured again. A bound value is an ordinary value of the kernel: -O1 and -O2 still substitute it into
// its users where the result is small, so binding never costs the optimizer a form it could have used.
#pragma once

#include <cstddef>

#include "algebra/products.hpp"
#include "symbolic/multivector.hpp"

namespace cgagen::expand_cost {

// Past this many expanded terms a product binds its costlier operand. Every product of the bundled
// scripts stays below it, so their kernels are the same as with full expansion.
constexpr std::size_t kBindProductTerms = 3000;

// The argument of exp or log is bound when one of its coefficients has more expression nodes than this: their
// closed forms square and expand the argument's parts and test signs on the expansion, which on a nested
// call's expressions (log(exp(B)) in one statement) would take minutes; on symbols it takes milliseconds.
constexpr std::size_t kBindArgumentNodes = 64;  // (symbolic::tree_larger_than)

// Terms of one coefficient: a sum's operands, else 1.
std::size_t coefficient_terms(const GiNaC::ex& c);
// Terms of all coefficients of m.
std::size_t terms(const symbolic::Multivector& m);
// Whether binding m would change anything: some coefficient is more than one term.
bool bindable(const symbolic::Multivector& m);
// The terms a product of kind `kind` of a and b expands to before collecting, over the pairs of blades
// whose product is not 0.
std::size_t product_terms(algebra::ProductKind kind, const symbolic::Multivector& a, const symbolic::Multivector& b);

// Which operands to bind before a product: none, the first, the second (the one with more terms per blade
// goes first; the other follows if the product is still too costly).
struct BindPlan {
  bool a = false, b = false;
};
BindPlan plan_product(algebra::ProductKind kind, const symbolic::Multivector& a, const symbolic::Multivector& b);

}  // namespace cgagen::expand_cost
