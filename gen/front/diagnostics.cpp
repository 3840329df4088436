// SourceFile (a script's text with an index of line starts) and the rendering of compile errors as
// `path:line:col: error: message`, the quoted line and a caret under the column.
#include "front/diagnostics.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

namespace cgagen::front {

SourceFile::SourceFile(std::string path, std::string text) : path_(std::move(path)), text_(std::move(text)) {
  line_starts_.push_back(0);
  for (size_t i = 0; i < text_.size(); ++i)
    if (text_[i] == '\n') line_starts_.push_back(i + 1);
}

SourceFile SourceFile::load(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  std::ostringstream buf;
  buf << in.rdbuf();
  if (in.bad()) throw std::runtime_error("cannot read " + path + ": " + std::strerror(errno));
  return SourceFile(path, buf.str());
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
  std::string text = file.line(loc.line);
  out += text + "\n";
  // The caret line copies tabs so that it lines up under any tab width, and counts a UTF-8 sequence as
  // one column on screen (columns in locations are bytes).
  std::string caret;
  size_t upto = loc.col > 1 ? static_cast<size_t>(loc.col - 1) : 0;
  for (size_t i = 0; i < upto; ++i) {
    char c = i < text.size() ? text[i] : ' ';
    if ((static_cast<unsigned char>(c) & 0xC0) == 0x80) continue;
    caret += c == '\t' ? '\t' : ' ';
  }
  out += caret + "^\n";
  return out;
}

}  // namespace cgagen::front
