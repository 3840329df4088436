// Lexer and parser for CluScript, Gaalop's dialect of CLUCalc. See docs/language.md for the grammar.
// Operator precedence, tightest first (Gaalop's grammar): ( ), prefix * (dual), prefix ~ (reverse),
// ^ (outer), . (inner), / , * (geometric), unary -, binary + -. All binary operators are left associative.
#pragma once

#include "front/ast.hpp"
#include "front/diagnostics.hpp"

namespace cgagen::front {

// Parses a whole script. Throws CompileError at the first fault.
Script parse(const SourceFile& file);

}  // namespace cgagen::front
