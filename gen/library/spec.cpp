// The library spec parser (spec.hpp): one declaration per line, words separated by blanks, `#` to the end of
// the line a comment. Every fault is located at its word.
#include "library/spec.hpp"

#include <algorithm>
#include <filesystem>
#include <map>
#include <set>

#include "emit/names.hpp"
#include "library/ops.hpp"

namespace cgagen::library {

namespace {

struct Word {
  std::string text;
  front::SourceLoc loc;
};

std::vector<Word> words_of(const std::string& line, int number) {
  std::vector<Word> out;
  size_t i = 0;
  while (i < line.size() && line[i] != '#') {
    if (line[i] == ' ' || line[i] == '\t' || line[i] == '\r') {
      ++i;
      continue;
    }
    const size_t start = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r' && line[i] != '#') ++i;
    out.push_back({line.substr(start, i - start), {number, static_cast<int>(start) + 1}});
  }
  return out;
}

// Words a type may not be called: the operations and the scalar (a target's reserved word is spelt as its
// other names are, emit/names.hpp).
void check_type_name(const Word& w) {
  if (!emit::is_identifier(w.text))
    throw front::CompileError(w.loc, "'" + w.text + "' is not a type name: letters, digits and _, not starting with a digit");
  if (w.text.front() == '_' || w.text.back() == '_' || w.text.find("__") != std::string::npos)
    throw front::CompileError(w.loc, "'" + w.text + "': a type name may not start or end with _ nor contain __ (its functions' names join it with _)");
  if (w.text == kScalarType)
    throw front::CompileError(w.loc, "'scalar' is the library's own type of the scalar blade; choose another name");
  if (is_operation(w.text))
    throw front::CompileError(w.loc, "'" + w.text + "' is the name of an operation of the library; choose another name");
  if (w.text.rfind("mv_", 0) == 0)
    throw front::CompileError(w.loc, "names starting with mv_ are the generator's own (types it names for results)");
}

algebra::BladeIndex parse_blade(const algebra::Algebra& alg, const Word& w) {
  if (w.text == "1") return 0;
  const auto b = alg.parse_blade(w.text);
  if (!b || b->index == 0)
    throw front::CompileError(w.loc, "'" + w.text + "' is not a blade of " + alg.name() + " (its vectors: " + [&] {
      std::string v;
      for (const auto& n : alg.vector_names()) v += (v.empty() ? "" : " ") + n;
      return v;
    }() + "; blades join them with ^, the scalar is 1)");
  if (b->sign < 0)
    throw front::CompileError(w.loc, "write '" + alg.blade_name(b->index) + "' for '" + w.text + "' (" + alg.name() +
                                         "'s spelling; the coefficient then changes sign)");
  return b->index;
}

}  // namespace

Spec parse_spec(const front::SourceFile& file, const std::string& dir) {
  file.check();
  Spec spec;
  std::optional<front::SourceLoc> library_at, algebra_at;
  std::map<std::string, front::SourceLoc> names;
  std::map<std::vector<algebra::BladeIndex>, std::string> by_blades;
  const std::string& text = file.text();
  int number = 0;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    ++number;
    const std::vector<Word> w = words_of(text.substr(start, end - start), number);
    start = end + 1;
    if (w.empty()) continue;
    const std::string& key = w[0].text;
    if (key == "library" || key == "algebra") {
      auto& at = key == "library" ? library_at : algebra_at;
      if (at)
        throw front::CompileError(w[0].loc, "a second '" + key + "' line (the first is on line " + std::to_string(at->line) + ")");
      if (w.size() != 2) throw front::CompileError(w.size() < 2 ? w[0].loc : w[2].loc, "'" + key + "' takes one word");
      at = w[0].loc;
      if (key == "library") {
        if (!emit::is_identifier(w[1].text))
          throw front::CompileError(w[1].loc, "'" + w[1].text + "' is not a library name: letters, digits and _, not starting with a digit");
        spec.name = w[1].text;
      } else {
        spec.algebra_spelling = w[1].text;
        std::string path = w[1].text;
        if (!algebra::builtin(path) && !dir.empty() && std::filesystem::path(path).is_relative())
          path = (std::filesystem::path(dir) / path).string();
        try {
          spec.algebra = algebra::load(path);
        } catch (const std::exception& e) {
          throw front::CompileError(w[1].loc, e.what());
        }
      }
    } else if (key == "type") {
      if (!spec.algebra) throw front::CompileError(w[0].loc, "a type before the 'algebra' line (its blades need the algebra)");
      if (w.size() < 3) throw front::CompileError(w[0].loc, "'type' takes a name and at least one blade");
      check_type_name(w[1]);
      if (auto it = names.find(w[1].text); it != names.end())
        throw front::CompileError(w[1].loc, "type '" + w[1].text + "' again (first on line " + std::to_string(it->second.line) + ")");
      names[w[1].text] = w[1].loc;
      Type t{w[1].text, {}, w[1].loc};
      std::set<algebra::BladeIndex> seen;
      for (size_t i = 2; i < w.size(); ++i) {
        const algebra::BladeIndex b = parse_blade(*spec.algebra, w[i]);
        if (!seen.insert(b).second) throw front::CompileError(w[i].loc, "blade '" + w[i].text + "' twice in type '" + t.name + "'");
        t.blades.push_back(b);
      }
      std::vector<algebra::BladeIndex> sorted = t.blades;
      std::sort(sorted.begin(), sorted.end());
      if (auto it = by_blades.find(sorted); it != by_blades.end())
        throw front::CompileError(w[1].loc, "type '" + t.name + "' has the blades of '" + it->second +
                                                "' (a result's type would be ambiguous)");
      if (sorted == std::vector<algebra::BladeIndex>{0})
        throw front::CompileError(w[1].loc, "the scalar blade alone is the library's type 'scalar'");
      by_blades[sorted] = t.name;
      spec.types.push_back(std::move(t));
    } else if (key == "alias") {
      if (w.size() != 3) throw front::CompileError(w[0].loc, "'alias' takes a new name and a declared type");
      check_type_name(w[1]);
      if (auto it = names.find(w[1].text); it != names.end())
        throw front::CompileError(w[1].loc, "'" + w[1].text + "' is already a name (line " + std::to_string(it->second.line) + ")");
      const bool known = std::any_of(spec.types.begin(), spec.types.end(), [&](const Type& t) { return t.name == w[2].text; });
      if (!known) throw front::CompileError(w[2].loc, "'" + w[2].text + "' is not a type declared above");
      names[w[1].text] = w[1].loc;
      spec.aliases.push_back({w[1].text, w[2].text, w[1].loc});
    } else {
      throw front::CompileError(w[0].loc, "unknown declaration '" + key +
                                              "' (a line is 'library NAME', 'algebra NAME|FILE', 'type NAME BLADE...' or 'alias NAME TYPE')");
    }
  }
  const front::SourceLoc end{std::max(1, number), 1};
  if (!library_at) throw front::CompileError({1, 1}, "no 'library NAME' line");
  if (!algebra_at) throw front::CompileError({1, 1}, "no 'algebra NAME|FILE' line");
  if (spec.types.empty()) throw front::CompileError(end, "no 'type NAME BLADE...' line");
  return spec;
}

}  // namespace cgagen::library
