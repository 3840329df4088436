// How cgagen spells names in generated code (docs/generator.md, "Names"). Two layers:
//  - c_identifier(): a file stem -> an identifier, the rule of CMake's string(MAKE_C_IDENTIFIER) so that
//    cgagen_generate() derives the same function and file name: every byte other than a letter, digit or _
//    becomes _, and a leading digit gets a _ in front ("my-kernel" -> my_kernel, "2pga" -> _2pga).
//  - spellings(): per target, every emitted name (function, inputs, outputs, temporaries) is kept as written
//    unless the target cannot use it: a run of underscores becomes one (GLSL and C++ reserve "__"), a
//    reserved prefix (GLSL's gl_, C's _X) gets a k in front, a reserved word (Syntax::reserved) gets a
//    trailing _; a changed name that would equal another name of the file gets _2, _3, ... instead.
#pragma once

#include <map>
#include <set>
#include <string>

#include "emit/emit.hpp"

namespace cgagen::emit {

std::string c_identifier(const std::string& text);
// Letters, digits and _, not starting with a digit, not empty (what --name accepts).
bool is_identifier(const std::string& text);
// The reserved words of a target by name (gen/emit/reserved.cpp); empty for latex and dot.
std::set<std::string> reserved_words(const std::string& target);
// NAME in target SX, ignoring the other names of the file.
std::string spell(const Syntax& sx, const std::string& name);
// Every name of NAMES -> its spelling in SX; the spellings are distinct whenever the names are.
std::map<std::string, std::string> spellings(const Syntax& sx, const std::set<std::string>& names);

}  // namespace cgagen::emit
