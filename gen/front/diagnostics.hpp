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

// A script's text, kept so that diagnostics can quote the offending line.
class SourceFile {
 public:
  SourceFile(std::string path, std::string text);
  static SourceFile load(const std::string& path);  // throws std::runtime_error("cannot read PATH: reason")
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

// "path:line:col: error: message\n<the source line>\n<spaces>^\n" (or "warning:" for severity "warning")
std::string format_diagnostic(const SourceFile& file, SourceLoc loc, const std::string& message,
                              const std::string& severity = "error");

}  // namespace cgagen::front
