// The CluScript lexer: turns a script's text into tokens on demand, skipping blanks and comments and
// collecting a pragma line (`#pragma ...` or `//#pragma ...` at the start of a line) into one token.
// Internal to the front end; the parser (parser.cpp) is its only user.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "front/ast.hpp"

namespace cgagen::front {

enum class TokKind {
  End,       // end of the text
  Ident,     // [A-Za-z_][A-Za-z0-9_]*
  Number,    // 12  0.5  .5  5.  1e-3  2.5E+2 (a Gaalop type suffix f/d is dropped from text)
  LParen,
  RParen,
  LBrace,
  RBrace,
  Comma,
  Semi,
  Assign,    // =
  Plus,
  Minus,
  Star,
  Slash,
  Caret,     // ^
  Dot,       // .
  Tilde,     // ~
  Question,  // ?
  Colon,     // :
  Bang,      // !
  Pragma,    // a whole pragma line; words/word_locs hold what follows "#pragma"
  Compare,   // < <= > >= == != (text: the operator), in if conditions
  AndAnd,    // &&
  OrOr,      // ||
};

struct Token {
  TokKind kind = TokKind::End;
  std::string_view text;  // points into the source; a token never spans lines
  SourceLoc loc;
  std::vector<std::string> words;    // Pragma only
  std::vector<SourceLoc> word_locs;  // Pragma only
  // The column just past the token, for "expected X after ..." diagnostics.
  SourceLoc end() const { return {loc.line, loc.col + static_cast<int>(text.size())}; }
};

// How a token kind is named in diagnostics ("';'", "end of file", "name", ...).
std::string describe(TokKind kind);
// How a particular token is named in diagnostics: its text in quotes, or "end of file".
std::string describe(const Token& token);

class Lexer {
 public:
  explicit Lexer(std::string_view text) : text_(text) {}
  // The next token; throws CompileError at an unexpected character, an unterminated block comment,
  // a malformed number or an empty pragma.
  Token next();

 private:
  void skip_blanks_and_comments();
  Token pragma(size_t start, size_t word_start);
  Token number();
  SourceLoc here() const { return {line_, static_cast<int>(pos_ - line_start_) + 1}; }
  SourceLoc at(size_t offset) const { return {line_, static_cast<int>(offset - line_start_) + 1}; }
  bool pragma_at(size_t offset) const;

  std::string_view text_;
  size_t pos_ = 0;
  int line_ = 1;
  size_t line_start_ = 0;
  bool at_line_start_ = true;  // only blanks so far on this line: a pragma may start here
};

}  // namespace cgagen::front
