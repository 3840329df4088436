// Hints in the expander's diagnostics: which known name a misspelt one most likely meant, and what other
// geometric-algebra libraries' function names (inverse, reverse, dual, meet, norm, ...) are in cgagen.
// A name that is read picks among variables (names the script assigns, basis blades) first, a call among
// functions (built-ins and macros); see docs/language.md, "Warnings".
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "front/ast.hpp"
#include "front/diagnostics.hpp"

namespace cgagen::hints {

// Optimal string alignment distance (Levenshtein plus adjacent transpositions).
size_t edit_distance(const std::string& a, const std::string& b);

// Is `name` a likely misspelling of `known`? From 3 characters on: one edit, from 8 on two. Shorter names
// (x1 against e1, p2 against p1, nx against n) differ by one edit all the time; one of them counts only
// when `short_ok` and it is the other with a letter doubled (Tt against T, snn against sn).
bool looks_like_typo(const std::string& name, const std::string& known, bool short_ok = false);

// Of `known`, the closest likely misspelling: fewest edits, then the nearest length, then the first.
std::optional<std::string> closest(const std::string& name, const std::vector<std::string>& known,
                                   bool short_ok = false);

// A name read before it is assigned: the variable it most likely misspells (short names too), else the
// function (a function's name read without a call), else none. `inputs` are the free names read so far.
// A numbered name (a10) is one of a family when its stem has another numbered name (a9) among `variables`
// or `inputs`, or when its stem is one letter (an indexed symbol, like x1 and e1); then another stem's
// numbered name (C10) is a different family's member, no typo. The same stem's other numbers stay
// candidates (translationCGA4 for translationCGA2).
std::optional<std::string> for_read(const std::string& name, const std::vector<std::string>& variables,
                                    const std::vector<std::string>& functions,
                                    const std::vector<std::string>& inputs = {});

// An unknown function: "; did you mean 'X'?" for a misspelt function, or what cgagen writes for another
// library's name ("; cgagen writes the reverse as ~X"), or "" when nothing fits.
std::string for_call(const std::string& name, const std::vector<std::string>& functions);

// `X ^ 2`: the outer product with a number scales (R^2 is 2R), where a power R*R was likely meant. The
// warning's text, or none when the right operand of the ^ expression E is no number (`0.5^t` on the left
// is Gaalop's way to scale).
std::optional<std::string> outer_with_number(const front::Expr& e);

// Adds a warning unless one with the same location and text is there (a macro body runs once per call).
void warn_once(std::vector<front::Warning>& warnings, front::SourceLoc loc, const std::string& message);

}  // namespace cgagen::hints
