// Compile errors and warnings with a location, and their rendering as `file:line:col: error: message` (or
// `warning:`), the line, a caret.
// Every stage that finds a fault in the user's script throws CompileError; the tool catches it, prints
// format_diagnostic(...) to stderr and exits 1.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

#include "front/ast.hpp"

namespace cgagen::front {

// A file that is no script: a directory, a binary file (a NUL byte, invalid UTF-8), a line longer than
// kMaxLineBytes. what() is the whole one-line diagnostic, "path:line:col: error: message".
struct FileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};
constexpr size_t kMaxLineBytes = 65536;

// A script's text, kept so that diagnostics can quote the offending line.
class SourceFile {
 public:
  SourceFile(std::string path, std::string text);
  // Throws std::runtime_error("cannot read PATH: reason"), or FileError for a directory or what check() refuses.
  static SourceFile load(const std::string& path);
  void check() const;  // throws FileError for a binary file or an over-long line
  const std::string& path() const { return path_; }
  const std::string& text() const { return text_; }
  std::string line(int line_number) const;  // 1-based, without the newline; "" when out of range
 private:
  std::string path_;
  std::string text_;
  std::vector<size_t> line_starts_;
};

class CompileError : public std::runtime_error {
 public:
  CompileError(SourceLoc loc, const std::string& message) : std::runtime_error(message), loc_(loc) {}
  SourceLoc loc() const { return loc_; }
 private:
  SourceLoc loc_;
};

// A warning: the script compiles, but probably not as meant (a misspelt name that became an input).
struct Warning {
  SourceLoc loc;
  std::string message;
};

// "path:line:col: error: message\n<the source line>\n<spaces>^\n" (or "warning:" for severity "warning").
// The quoted line is cut to kQuoteColumns around the column ("..." marks a cut) and a control byte or a byte
// that is no UTF-8 is printed as \xNN, so the caret stays under the column.
constexpr size_t kQuoteColumns = 120;
std::string format_diagnostic(const SourceFile& file, SourceLoc loc, const std::string& message,
                              const std::string& severity = "error");

}  // namespace cgagen::front
