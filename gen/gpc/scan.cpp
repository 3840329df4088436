// The source reader of cgagen --gpc (scan.hpp): line table, pragma lines, GPC function calls.
#include "gpc/scan.hpp"

#include <cctype>

#include "front/diagnostics.hpp"

namespace cgagen::gpc {

using front::CompileError;
using front::SourceLoc;

Text::Text(const std::string& text) : text_(text) {
  starts_.push_back(0);
  for (size_t i = 0; i < text.size(); ++i)
    if (text[i] == '\n' && i + 1 < text.size()) starts_.push_back(i + 1);
}

size_t Text::line_start(int line) const {
  if (line < 1) return 0;
  return line <= lines() ? starts_[static_cast<size_t>(line - 1)] : text_.size();
}

size_t Text::line_end(int line) const {
  const size_t s = line_start(line);
  const size_t e = text_.find('\n', s);
  return e == std::string::npos ? text_.size() : e;
}

SourceLoc Text::loc(size_t offset) const {
  size_t lo = 0, hi = starts_.size();
  while (hi - lo > 1) {
    const size_t mid = (lo + hi) / 2;
    (starts_[mid] <= offset ? lo : hi) = mid;
  }
  return {static_cast<int>(lo + 1), static_cast<int>(offset - starts_[lo] + 1)};
}

bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

bool is_identifier(const std::string& s) {
  if (s.empty() || std::isdigit(static_cast<unsigned char>(s[0]))) return false;
  for (char c : s)
    if (!is_ident_char(c)) return false;
  return true;
}

size_t skip_blanks(const std::string& s, size_t pos, size_t end) {
  while (pos < end && (s[pos] == ' ' || s[pos] == '\t' || s[pos] == '\r' || s[pos] == '\n')) ++pos;
  return pos;
}

namespace {

bool blank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

// A word of letters, digits and _ at pos (empty when there is none); pos moves past it.
std::string word_at(const std::string& s, size_t& pos, size_t end) {
  const size_t b = pos;
  while (pos < end && is_ident_char(s[pos])) ++pos;
  return s.substr(b, pos - b);
}

// The pragma on the line [b, e), if it is a gpc or clucalc one.
bool pragma_line(const Text& t, int line, PragmaLine& out) {
  const std::string& s = t.str();
  const size_t b = t.line_start(line), e = t.line_end(line);
  size_t p = b;
  while (p < e && blank(s[p])) ++p;
  if (p >= e || s[p] != '#') return false;
  const size_t hash = p++;
  while (p < e && blank(s[p])) ++p;
  if (word_at(s, p, e) != "pragma" || p >= e || !blank(s[p])) return false;
  while (p < e && blank(s[p])) ++p;
  const std::string family = word_at(s, p, e);
  if (family != "gpc" && family != "clucalc") return false;
  if (p < e && !blank(s[p]) && s[p] != '/') return false;  // "#pragma gpc_x": not ours
  while (p < e && blank(s[p])) ++p;
  const size_t at = p;
  const std::string what = word_at(s, p, e);
  size_t q = p;
  while (q < e && blank(s[q])) ++q;
  const bool rest_ok = q >= e || s.compare(q, 2, "//") == 0 || s.compare(q, 2, "/*") == 0;
  if ((what != "begin" && what != "end") || !rest_ok)
    throw CompileError(t.loc(at), "unknown '#pragma " + family + "' line (expected '#pragma " + family +
                                      " begin' or '#pragma " + family + " end')");
  out.kind = family == "gpc" ? (what == "begin" ? PragmaKind::GpcBegin : PragmaKind::GpcEnd)
                             : (what == "begin" ? PragmaKind::ClucalcBegin : PragmaKind::ClucalcEnd);
  out.line = line;
  out.loc = t.loc(hash);
  out.indent = s.substr(b, hash - b);
  return true;
}

// Reads C text from pos to the end of the line that pos is on, keeping the comment state; returns true
// when the line ends inside a block comment.
enum class State { Code, BlockComment };

State scan_line(const std::string& s, size_t p, size_t e, State st) {
  char quote = 0;
  while (p < e) {
    const char c = s[p];
    if (st == State::BlockComment) {
      if (c == '*' && p + 1 < e && s[p + 1] == '/') st = State::Code, ++p;
    } else if (quote) {
      if (c == '\\') ++p;
      else if (c == quote) quote = 0;
    } else if (c == '/' && p + 1 < e && s[p + 1] == '/') {
      return st;  // the rest of the line is a comment
    } else if (c == '/' && p + 1 < e && s[p + 1] == '*') {
      st = State::BlockComment, ++p;
    } else if (c == '"' || (c == '\'' && !(p > 0 && std::isalnum(static_cast<unsigned char>(s[p - 1]))))) {
      quote = c;  // a ' after a digit or letter is a digit separator (1'000) or part of a prefix (u8'x')
    }
    ++p;
  }
  return st;
}

}  // namespace

std::vector<PragmaLine> find_pragmas(const Text& t) {
  std::vector<PragmaLine> out;
  State st = State::Code;
  bool script = false;
  for (int line = 1; line <= t.lines(); ++line) {
    PragmaLine pl;
    if (st == State::Code && pragma_line(t, line, pl)) {
      out.push_back(pl);
      if (pl.kind == PragmaKind::ClucalcBegin) script = true;
      else script = false;  // after clucalc end, and after a gpc line (an unterminated section: gpc.cpp's error)
      continue;
    }
    if (!script) st = scan_line(t.str(), t.line_start(line), t.line_end(line), st);
  }
  return out;
}

bool is_conditional_directive(const std::string& line) {
  size_t p = 0;
  while (p < line.size() && blank(line[p])) ++p;
  if (p >= line.size() || line[p] != '#') return false;
  ++p;
  while (p < line.size() && blank(line[p])) ++p;
  const std::string w = word_at(line, p, line.size());
  return w == "if" || w == "ifdef" || w == "ifndef" || w == "elif" || w == "else" || w == "endif" ||
         w == "elifdef" || w == "elifndef";
}

std::vector<Call> find_calls(const Text& t, size_t begin, size_t end, const std::set<std::string>& names) {
  const std::string& s = t.str();
  std::vector<Call> calls;
  size_t p = begin;
  while (p < end) {
    const char c = s[p];
    if (c == '/' && p + 1 < end && s[p + 1] == '/') {
      while (p < end && s[p] != '\n') ++p;
      continue;
    }
    if (c == '/' && p + 1 < end && s[p + 1] == '*') {
      const size_t close = s.find("*/", p + 2);
      p = close == std::string::npos || close + 2 > end ? end : close + 2;
      continue;
    }
    if (c == '"' || (c == '\'' && !(p > begin && std::isalnum(static_cast<unsigned char>(s[p - 1]))))) {
      ++p;
      while (p < end && s[p] != c && s[p] != '\n') p += s[p] == '\\' ? 2 : 1;
      ++p;
      continue;
    }
    if (!is_ident_char(c)) {
      ++p;
      continue;
    }
    const size_t name_at = p;
    const std::string w = word_at(s, p, end);
    if (!names.count(w)) continue;
    const bool qualified = name_at > begin && (s[name_at - 1] == '.' ||
                                               (name_at >= begin + 2 && (s.compare(name_at - 2, 2, "->") == 0 ||
                                                                         s.compare(name_at - 2, 2, "::") == 0)));
    size_t open = p;
    while (open < end && (blank(s[open]) || s[open] == '\n')) ++open;
    if (qualified || open >= end || s[open] != '(') continue;
    Call call{w, name_at, 0, {}};
    int depth = 0;
    size_t arg_start = open + 1;
    auto add_arg = [&](size_t to) {
      size_t a = arg_start, b = to;
      while (a < b && (blank(s[a]) || s[a] == '\n')) ++a;
      while (b > a && (blank(s[b - 1]) || s[b - 1] == '\n')) --b;
      call.args.push_back({s.substr(a, b - a), a});
    };
    size_t q = open;
    for (; q < end; ++q) {
      const char d = s[q];
      if (d == '"' || d == '\'') {
        ++q;
        while (q < end && s[q] != d && s[q] != '\n') q += s[q] == '\\' ? 2 : 1;
        continue;
      }
      if (d == '(' || d == '[' || d == '{') ++depth;
      else if (d == ')' || d == ']' || d == '}') {
        if (--depth == 0) break;
      } else if (d == ',' && depth == 1) {
        add_arg(q);
        arg_start = q + 1;
      }
    }
    if (q >= end) throw CompileError(t.loc(open), "'(' of " + w + " is not closed");
    add_arg(q);
    call.close = q;
    calls.push_back(call);
    p = q + 1;
  }
  return calls;
}

}  // namespace cgagen::gpc
