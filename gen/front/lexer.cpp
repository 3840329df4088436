// The CluScript lexer (see lexer.hpp). Number syntax follows Gaalop's lexer, extended with 'E' and '+'
// in exponents: a '.' right after digits belongs to the number, so "2.e1" is the number 20, as in Gaalop.
#include "front/lexer.hpp"

#include <cstdio>

#include "front/diagnostics.hpp"

namespace cgagen::front {
namespace {

bool is_digit(char c) { return c >= '0' && c <= '9'; }
bool is_ident_start(char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || c == '_'; }
bool is_ident_char(char c) { return is_ident_start(c) || is_digit(c); }
bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }

// A character as a diagnostic shows it: printable ASCII and whole UTF-8 sequences as themselves,
// anything else as \xHH.
std::string show_char(std::string_view rest) {
  auto byte = static_cast<unsigned char>(rest[0]);
  if (byte >= 0x20 && byte < 0x7f) return std::string(1, rest[0]);
  size_t len = byte >= 0xF0 && byte < 0xF5 ? 4 : byte >= 0xE0 ? 3 : byte >= 0xC2 && byte < 0xE0 ? 2 : 0;
  if (byte >= 0xF5) len = 0;
  bool ok = len > 0 && rest.size() >= len;
  for (size_t i = 1; ok && i < len; ++i) ok = (static_cast<unsigned char>(rest[i]) & 0xC0) == 0x80;
  if (ok) return std::string(rest.substr(0, len));
  char buf[8];
  std::snprintf(buf, sizeof buf, "\\x%02X", byte);
  return buf;
}

}  // namespace

std::string describe(TokKind kind) {
  switch (kind) {
    case TokKind::End: return "end of file";
    case TokKind::Ident: return "name";
    case TokKind::Number: return "number";
    case TokKind::LParen: return "'('";
    case TokKind::RParen: return "')'";
    case TokKind::LBrace: return "'{'";
    case TokKind::RBrace: return "'}'";
    case TokKind::Comma: return "','";
    case TokKind::Semi: return "';'";
    case TokKind::Assign: return "'='";
    case TokKind::Plus: return "'+'";
    case TokKind::Minus: return "'-'";
    case TokKind::Star: return "'*'";
    case TokKind::Slash: return "'/'";
    case TokKind::Caret: return "'^'";
    case TokKind::Dot: return "'.'";
    case TokKind::Tilde: return "'~'";
    case TokKind::Question: return "'?'";
    case TokKind::Colon: return "':'";
    case TokKind::Bang: return "'!'";
    case TokKind::Pragma: return "pragma";
    case TokKind::Compare: return "comparison";
    case TokKind::AndAnd: return "'&&'";
    case TokKind::OrOr: return "'||'";
  }
  return "token";
}

std::string describe(const Token& token) {
  if (token.kind == TokKind::End) return "end of file";
  if (token.kind == TokKind::Pragma) return "'#pragma'";
  return "'" + std::string(token.text) + "'";
}

bool Lexer::pragma_at(size_t offset) const {
  constexpr std::string_view kPragma = "#pragma";
  if (text_.compare(offset, kPragma.size(), kPragma) != 0) return false;
  size_t after = offset + kPragma.size();
  return after == text_.size() || is_blank(text_[after]) || text_[after] == '\n';
}

void Lexer::skip_blanks_and_comments() {
  while (pos_ < text_.size()) {
    char c = text_[pos_];
    if (c == '\n') {
      ++pos_;
      ++line_;
      line_start_ = pos_;
      at_line_start_ = true;
    } else if (is_blank(c)) {
      ++pos_;
    } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') {
      if (at_line_start_ && pragma_at(pos_ + 2)) return;  // "//#pragma": a token, not a comment
      while (pos_ < text_.size() && text_[pos_] != '\n') ++pos_;
    } else if (c == '/' && pos_ + 1 < text_.size() && text_[pos_ + 1] == '*') {
      size_t close = text_.find("*/", pos_ + 2);
      if (close == std::string_view::npos) throw CompileError(here(), "unterminated block comment");
      for (size_t i = pos_; i < close; ++i) {
        if (text_[i] == '\n') {
          ++line_;
          line_start_ = i + 1;
        }
      }
      pos_ = close + 2;
      at_line_start_ = false;
    } else {
      return;
    }
  }
}

Token Lexer::pragma(size_t start, size_t word_start) {
  Token t;
  t.kind = TokKind::Pragma;
  t.loc = at(word_start);  // the '#', for both spellings
  size_t i = word_start + 7;  // past "#pragma"
  size_t last = i;            // end of the last word
  while (i < text_.size() && text_[i] != '\n') {
    if (is_blank(text_[i])) {
      ++i;
      continue;
    }
    size_t b = i;
    while (i < text_.size() && text_[i] != '\n' && !is_blank(text_[i])) ++i;
    std::string_view word = text_.substr(b, i - b);
    if (word.substr(0, 2) == "//") {  // a trailing line comment ends the pragma's words
      while (i < text_.size() && text_[i] != '\n') ++i;
      break;
    }
    t.words.emplace_back(word);
    t.word_locs.push_back(at(b));
    last = i;
  }
  // The token's text stops at the last word (or "#pragma") so that end() stays on this line.
  t.text = text_.substr(start, last - start);
  if (t.words.empty()) throw CompileError(t.loc, "empty pragma");
  pos_ = i;
  return t;
}

Token Lexer::number() {
  Token t;
  t.kind = TokKind::Number;
  t.loc = here();
  size_t b = pos_;
  while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
  if (pos_ < text_.size() && text_[pos_] == '.') {
    ++pos_;
    while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
  }
  if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
    size_t d = pos_ + 1;
    if (d < text_.size() && (text_[d] == '+' || text_[d] == '-')) ++d;
    if (d < text_.size() && is_digit(text_[d])) {
      pos_ = d;
      while (pos_ < text_.size() && is_digit(text_[pos_])) ++pos_;
    }
  }
  size_t end = pos_;
  // Gaalop's float type suffix ("1.5f", "2d") is accepted and dropped: it says nothing about the value.
  if (pos_ < text_.size() && (text_[pos_] == 'f' || text_[pos_] == 'd') &&
      (pos_ + 1 == text_.size() || !is_ident_char(text_[pos_ + 1])))
    ++pos_;
  if (pos_ < text_.size() && is_ident_char(text_[pos_])) {
    while (pos_ < text_.size() && (is_ident_char(text_[pos_]) || text_[pos_] == '.')) ++pos_;
    throw CompileError(t.loc, "invalid number '" + std::string(text_.substr(b, pos_ - b)) + "'");
  }
  t.text = text_.substr(b, end - b);
  return t;
}

Token Lexer::next() {
  skip_blanks_and_comments();
  Token t;
  t.loc = here();
  if (pos_ >= text_.size()) {
    t.kind = TokKind::End;
    t.text = text_.substr(text_.size());
    return t;
  }
  const size_t start = pos_;
  const bool line_start = at_line_start_;
  at_line_start_ = false;
  char c = text_[pos_];
  if (c == '/' && line_start && pos_ + 1 < text_.size() && text_[pos_ + 1] == '/') return pragma(start, start + 2);
  if (c == '#') {
    if (pragma_at(pos_)) {
      if (!line_start) throw CompileError(t.loc, "'#pragma' must be the first thing on its line");
      return pragma(start, start);
    }
    throw CompileError(t.loc, "unexpected character '#' (a pragma is written '#pragma WORDS...')");
  }
  if (is_digit(c) || (c == '.' && pos_ + 1 < text_.size() && is_digit(text_[pos_ + 1]))) return number();
  if (is_ident_start(c)) {
    while (pos_ < text_.size() && is_ident_char(text_[pos_])) ++pos_;
    t.kind = TokKind::Ident;
    t.text = text_.substr(start, pos_ - start);
    return t;
  }
  // Two-character operators of if conditions: <= >= == != && ||, and < >.
  const char d = pos_ + 1 < text_.size() ? text_[pos_ + 1] : '\0';
  if ((c == '<' || c == '>' || c == '=' || c == '!') && d == '=') {
    pos_ += 2;
    t.kind = TokKind::Compare;
    t.text = text_.substr(start, 2);
    return t;
  }
  if ((c == '&' && d == '&') || (c == '|' && d == '|')) {
    pos_ += 2;
    t.kind = c == '&' ? TokKind::AndAnd : TokKind::OrOr;
    t.text = text_.substr(start, 2);
    return t;
  }
  if (c == '<' || c == '>') {
    ++pos_;
    t.kind = TokKind::Compare;
    t.text = text_.substr(start, 1);
    return t;
  }
  switch (c) {
    case '(': t.kind = TokKind::LParen; break;
    case ')': t.kind = TokKind::RParen; break;
    case '{': t.kind = TokKind::LBrace; break;
    case '}': t.kind = TokKind::RBrace; break;
    case ',': t.kind = TokKind::Comma; break;
    case ';': t.kind = TokKind::Semi; break;
    case '=': t.kind = TokKind::Assign; break;
    case '+': t.kind = TokKind::Plus; break;
    case '-': t.kind = TokKind::Minus; break;
    case '*': t.kind = TokKind::Star; break;
    case '/': t.kind = TokKind::Slash; break;
    case '^': t.kind = TokKind::Caret; break;
    case '.': t.kind = TokKind::Dot; break;
    case '~': t.kind = TokKind::Tilde; break;
    case '?': t.kind = TokKind::Question; break;
    case ':': t.kind = TokKind::Colon; break;
    case '!': t.kind = TokKind::Bang; break;
    default: throw CompileError(t.loc, "unexpected character '" + show_char(text_.substr(pos_)) + "'");
  }
  ++pos_;
  t.text = text_.substr(start, 1);
  return t;
}

}  // namespace cgagen::front
