// Names in generated code: see names.hpp for the rule.
#include "emit/names.hpp"

namespace cgagen::emit {

namespace {
bool is_letter(char c) { return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z'); }
bool is_digit(char c) { return c >= '0' && c <= '9'; }
}  // namespace

std::string c_identifier(const std::string& text) {
  std::string s;
  for (char c : text) s += is_letter(c) || is_digit(c) || c == '_' ? c : '_';
  if (s.empty() || is_digit(s[0])) s = "_" + s;
  return s;
}

bool is_identifier(const std::string& text) {
  if (text.empty() || is_digit(text[0])) return false;
  for (char c : text)
    if (!is_letter(c) && !is_digit(c) && c != '_') return false;
  return true;
}

std::string spell(const Syntax& sx, const std::string& name) {
  if (sx.ident) return sx.ident(name);  // LaTeX: math-mode spelling, no reserved words
  if (sx.reserved.empty() && sx.reserved_prefixes.empty()) return name;
  std::string s;
  for (char c : name)
    if (!(c == '_' && !s.empty() && s.back() == '_' && sx.single_underscores)) s += c;
  for (const auto& p : sx.reserved_prefixes)
    if (s.compare(0, p.size(), p) == 0) {
      s = "k" + s;
      break;
    }
  if (sx.reserved.count(s)) s += s.back() == '_' ? "k" : "_";  // "_" (WGSL, Rust) -> "_k", never "__"
  return s;
}

std::map<std::string, std::string> spellings(const Syntax& sx, const std::set<std::string>& names) {
  std::map<std::string, std::string> out;
  std::set<std::string> used;
  for (const auto& n : names)  // names kept as written first: a changed one must avoid all of them
    if (spell(sx, n) == n) out[n] = n, used.insert(n);
  for (const auto& n : names) {
    if (out.count(n)) continue;
    const std::string base = spell(sx, n);
    std::string s = base;
    for (int k = 2; used.count(s) || names.count(s); ++k)
      s = base + (base.back() == '_' ? "" : "_") + std::to_string(k);
    out[n] = s;
    used.insert(s);
  }
  return out;
}

}  // namespace cgagen::emit
