// SourceFile (a script's text with an index of line starts) and the rendering of compile errors as
// `path:line:col: error: message`, the quoted line and a caret under the column.
#include "front/diagnostics.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace cgagen::front {

SourceFile::SourceFile(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {
  line_starts_.push_back(0);
  for (size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
}

namespace {

std::string located(const std::string& path, size_t line, size_t col, const std::string& message) {
  return path + ":" + std::to_string(line) + ":" + std::to_string(col) + ": error: " + message;
}

std::string hex_byte(unsigned char c) {
  static const char* digits = "0123456789ABCDEF";  // as the lexer prints a byte
  return std::string("\\x") + digits[c >> 4] + digits[c & 15];
}

// The length of the UTF-8 sequence at text[i], 0 when it is none (a stray or overlong byte, a surrogate).
size_t utf8_length(const std::string& text, size_t i) {
  const unsigned char c = static_cast<unsigned char>(text[i]);
  if (c < 0x80) return 1;
  size_t n = c >= 0xF0 && c <= 0xF4 ? 4 : c >= 0xE0 ? (c <= 0xEF ? 3 : 0) : c >= 0xC2 ? 2 : 0;
  if (n == 0 || i + n > text.size()) return 0;
  for (size_t k = 1; k < n; ++k)
    if ((static_cast<unsigned char>(text[i + k]) & 0xC0) != 0x80) return 0;
  const unsigned char d = static_cast<unsigned char>(text[i + 1]);
  if ((c == 0xE0 && d < 0xA0) || (c == 0xED && d > 0x9F) || (c == 0xF0 && d < 0x90) || (c == 0xF4 && d > 0x8F))
    return 0;
  return n;
}

}  // namespace

// A NUL byte anywhere, or a byte that is no UTF-8 outside a comment (scripts from other tools may have
// Latin-1 in their comments, which the lexer skips), makes a binary file.
void SourceFile::check() const {
  size_t line = 1, line_start = 0;
  enum { Code, LineComment, BlockComment } state = Code;
  for (size_t i = 0; i < text_.size();) {
    const unsigned char c = static_cast<unsigned char>(text_[i]);
    if (c == '\n') {
      ++line, line_start = ++i;
      if (state == LineComment) state = Code;
      continue;
    }
    if (state == Code && c == '/' && i + 1 < text_.size() && (text_[i + 1] == '/' || text_[i + 1] == '*')) {
      state = text_[i + 1] == '/' ? LineComment : BlockComment;
      i += 2;
      continue;
    }
    if (state == BlockComment && c == '*' && i + 1 < text_.size() && text_[i + 1] == '/') {
      state = Code;
      i += 2;
      continue;
    }
    if (i - line_start >= kMaxLineBytes)
      throw FileError(located(path_, line, i - line_start + 1, "line " + std::to_string(line) + " is longer than " +
                                                                   std::to_string(kMaxLineBytes) +
                                                                   " bytes; a script's lines are shorter"));
    size_t n = c == 0 ? 0 : utf8_length(text_, i);
    if (n == 0 && c != 0 && state != Code) n = 1;
    if (n == 0)
      throw FileError(located(path_, line, i - line_start + 1,
                              "not a text file: byte " + hex_byte(c) + (c == 0 ? "" : ", which is not UTF-8") +
                                  "; a script is UTF-8 text"));
    i += n;
  }
}

SourceFile SourceFile::load(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw FileError(located(path, 1, 1, "is a directory, not a script"));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  SourceFile file(path, buf.str());
  file.check();
  return file;
}

std::string SourceFile::line(int line_number) const {
  if (line_number < 1 || static_cast<size_t>(line_number) > line_starts_.size()) return "";
  size_t begin = line_starts_[line_number - 1];
  size_t end = static_cast<size_t>(line_number) < line_starts_.size() ? line_starts_[line_number] - 1 : text_.size();
  // A CRLF file's '\r' is part of the line break, not of the line.
  if (end > begin && text_[end - 1] == '\r') --end;
  return text_.substr(begin, end - begin);
}

std::string format_diagnostic(const SourceFile& file, SourceLoc loc, const std::string& message,
                              const std::string& severity) {
  std::string out = file.path();
  if (loc.line < 1) return out + ": " + severity + ": " + message + "\n";
  out += ":" + std::to_string(loc.line) + ":" + std::to_string(loc.col) + ": " + severity + ": " + message + "\n";
  const std::string text = file.line(loc.line);
  // Screen pieces of the line: one per UTF-8 sequence (one column), a tab (copied into the caret line so
  // that it lines up under any tab width), or \xNN for any other control byte or a byte that is no UTF-8.
  struct Piece {
    std::string shown;
    size_t columns;
  };
  std::vector<Piece> pieces;
  std::vector<size_t> piece_of;  // byte -> its piece
  for (size_t i = 0; i < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    size_t n = c == '\t' || (c >= 0x20 && c != 0x7F) ? utf8_length(text, i) : 0;
    if (n == 0) {
      pieces.push_back({hex_byte(c), 4});
      n = 1;
    } else {
      pieces.push_back({text.substr(i, n), 1});
    }
    for (size_t k = 0; k < n; ++k) piece_of.push_back(pieces.size() - 1);
    i += n;
  }
  const size_t byte = loc.col > 1 ? static_cast<size_t>(loc.col - 1) : 0;
  const size_t at = byte < piece_of.size() ? piece_of[byte] : pieces.size() + (byte - piece_of.size());
  // A window of about kQuoteColumns columns around the column.
  size_t first = 0, last = pieces.size();
  size_t width = 0;
  for (const auto& p : pieces) width += p.columns;
  if (width > kQuoteColumns) {
    first = at > kQuoteColumns / 2 ? at - kQuoteColumns / 2 : 0;
    size_t w = 0;
    last = first;
    while (last < pieces.size() && w + pieces[last].columns <= kQuoteColumns) w += pieces[last++].columns;
    if (last < at) last = std::min(pieces.size(), at + 1);
  }
  std::string quote = first > 0 ? "..." : "", caret = first > 0 ? "   " : "";
  for (size_t i = first; i < last; ++i) {
    quote += pieces[i].shown;
    if (i < at) caret += pieces[i].shown == "\t" ? "\t" : std::string(pieces[i].columns, ' ');
  }
  for (size_t i = std::max(last, pieces.size()); i < at; ++i) caret += ' ';  // a column past the end
  if (last < pieces.size()) quote += "...";
  out += quote + "\n" + caret + "^\n";
  return out;
}

}  // namespace cgagen::front
