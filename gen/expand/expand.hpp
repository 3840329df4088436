// The expand stage: walks the AST, evaluates every statement into a sparse symbolic multivector (blade ->
// GiNaC expression) and records inputs, values, outputs and pragmas as a Kernel.
#pragma once

#include <string>
#include <vector>

#include "expand/kernel.hpp"
#include "front/ast.hpp"
#include "front/diagnostics.hpp"

namespace cgagen {

// Throws front::CompileError (with the location of the offending expression) for every fault in the
// script: unknown macro, wrong arity, non-scalar function argument, division by a non-invertible
// multivector, macro recursion, unknown blade in a pragma, ...
// Expands the script in `algebra` (null: the thread's current algebra, by default CGA); the Kernel keeps it.
// `jacobian_wrt` (cgagen --jacobian): every output's partial derivatives with respect to these inputs, as
// `#pragma jacobian wrt ...` gives them (docs/generator.md, "Derivatives").
Kernel expand(const front::Script& script, const std::string& kernel_name,
              std::shared_ptr<const algebra::Algebra> algebra = nullptr,
              const std::vector<std::string>& jacobian_wrt = {});

}  // namespace cgagen
