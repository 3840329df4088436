// The per-algebra layer of the expander: which names are basis vectors in the current algebra, what they
// are, and the built-in macros each non-CGA algebra brings (createPoint, Normalize, Dual, regProd in PGA),
// written in CluScript from the math. CGA keeps its own built-ins in expand.cpp, unchanged.
#pragma once

#include <string>

#include "symbolic/multivector.hpp"

namespace cgagen::expand_algebra {

// Is the current algebra the built-in CGA (then expand.cpp's own basis names and built-ins apply)?
bool is_cga();
// A user or diagonal basis vector name of the current (non-CGA) algebra.
bool is_basis_name(const std::string& n);
// That vector as a multivector over the user blades (a diagonal one through the basis change).
symbolic::Multivector basis(const std::string& n);
// CluScript text of the current algebra's built-in macros ("" for CGA).
std::string prelude();

}  // namespace cgagen::expand_algebra
