// `#pragma algebra NAME|FILE` (algebra_pragma.hpp).
#include "expand/algebra_pragma.hpp"

#include <filesystem>

#include "front/diagnostics.hpp"

namespace cgagen::expand_algebra_pragma {

std::string algebra_name(const std::string& spelling) {
  if (algebra::builtin(spelling)) return spelling;
  return std::filesystem::path(spelling).stem().string();
}

std::optional<ScriptAlgebra> script_algebra(const front::Script& script, const std::string& script_dir) {
  std::optional<ScriptAlgebra> found;
  for (const auto& s : script.statements) {
    if (s->kind != front::Stmt::Kind::Pragma || s->words.empty() || s->words[0] != "algebra") continue;
    if (s->words.size() != 2)
      throw front::CompileError(s->words.size() > 2 ? s->word_locs.at(2) : s->loc,
                                "'#pragma algebra' takes one built-in name or definition file");
    const std::string& spelling = s->words[1];
    const front::SourceLoc at = s->word_locs.at(1);
    if (found) {
      if (algebra_name(spelling) != algebra_name(found->spelling))
        throw front::CompileError(at, "'#pragma algebra " + spelling + "' after '#pragma algebra " + found->spelling +
                                          "' at line " + std::to_string(found->loc.line));
      continue;
    }
    std::string path = spelling;
    if (!algebra::builtin(spelling) && !script_dir.empty() && std::filesystem::path(spelling).is_relative())
      path = (std::filesystem::path(script_dir) / spelling).string();
    try {
      found = ScriptAlgebra{algebra::load(path), spelling, at};
    } catch (const algebra::AlgebraError& e) {
      throw front::CompileError(at, std::string("'#pragma algebra': ") + e.what());
    }
  }
  return found;
}

}  // namespace cgagen::expand_algebra_pragma
