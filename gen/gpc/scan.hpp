// Reading a C, C++ or CUDA source for cgagen --gpc: its line table, the `#pragma gpc` / `#pragma clucalc`
// lines, and the calls of the GPC functions (mv_from_array, to_array, ...) in its C text, found outside
// comments, string and character literals. Nothing here knows what a block means (gpc.cpp does).
#pragma once

#include <set>
#include <string>
#include <vector>

#include "front/ast.hpp"

namespace cgagen::gpc {

// The source text with its line starts.
class Text {
 public:
  explicit Text(const std::string& text);
  const std::string& str() const { return text_; }
  int lines() const { return static_cast<int>(starts_.size()); }
  size_t line_start(int line) const;  // 1-based; text size past the last line
  size_t line_end(int line) const;    // the offset of the line's '\n' (or the text size)
  front::SourceLoc loc(size_t offset) const;  // 1-based line and column (in bytes)

 private:
  const std::string& text_;
  std::vector<size_t> starts_;
};

enum class PragmaKind { GpcBegin, GpcEnd, ClucalcBegin, ClucalcEnd };

struct PragmaLine {
  PragmaKind kind;
  int line = 0;
  front::SourceLoc loc;  // the '#'
  std::string indent;    // the blanks before the '#'
};

// The lines whose first non-blank text is `#pragma gpc begin|end` or `#pragma clucalc begin|end` (blanks
// allowed around each word, a // or /* comment after), in order. C text is read with its comments, so a
// pragma inside a /* */ comment is no pragma; the lines after `#pragma clucalc begin` are script text, read
// only for the next `#pragma clucalc end` or `#pragma gpc` line. Throws front::CompileError for
// `#pragma gpc` or `#pragma clucalc` followed by another word.
std::vector<PragmaLine> find_pragmas(const Text& text);

// Whether a (logical) line is a conditional preprocessor directive: #if, #ifdef, #ifndef, #elif, #else,
// #endif (and C23's #elifdef, #elifndef).
bool is_conditional_directive(const std::string& line);

struct Arg {
  std::string text;  // without the blanks around it
  size_t begin = 0;  // offset of its first non-blank character (of the ')' when empty)
};

struct Call {
  std::string fn;
  size_t name = 0;   // offset of the function name
  size_t close = 0;  // offset of the closing ')'
  std::vector<Arg> args;  // split at the top-level commas; one empty Arg for "()"
};

// Calls of the functions in `names` within text[begin, end): the name not preceded by a letter, digit,
// '_', '.', "->" or "::", then blanks and '('. Throws front::CompileError for a '(' never closed before end.
std::vector<Call> find_calls(const Text& text, size_t begin, size_t end, const std::set<std::string>& names);

// Offset of the first non-blank character at or after `pos` (or end); of the last one before `pos`.
size_t skip_blanks(const std::string& s, size_t pos, size_t end);
bool is_ident_char(char c);
bool is_identifier(const std::string& s);

}  // namespace cgagen::gpc
