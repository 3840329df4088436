// `#pragma algebra NAME|FILE`: a script names the algebra it is written in (a built-in name, or a Gaalop
// definition.csv relative to the script's folder), as Gaalop's users keep the algebra with the script. The
// algebra must be chosen before the script is expanded (basis names and products depend on it): the driver
// (cgagen's main) asks script_algebra() first and selects it; the expander then checks that it was
// (expand/pragmas.cpp), so a caller that did not cannot get a script expanded in another algebra.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "algebra/algebra.hpp"
#include "front/ast.hpp"

namespace cgagen::expand_algebra_pragma {

struct ScriptAlgebra {
  std::shared_ptr<const algebra::Algebra> algebra;
  std::string spelling;  // as the pragma writes it
  front::SourceLoc loc;  // its word
};

// The algebra the script's top-level `#pragma algebra` names, or nullopt. Throws front::CompileError at the
// pragma for a missing or extra word, an unknown name or unreadable file (with the definition's own error),
// or a second pragma naming another algebra.
std::optional<ScriptAlgebra> script_algebra(const front::Script& script, const std::string& script_dir);

// The name an algebra gets when loaded from `spelling` (a built-in's name, a file's stem): what the expander
// compares with the current algebra.
std::string algebra_name(const std::string& spelling);

}  // namespace cgagen::expand_algebra_pragma
