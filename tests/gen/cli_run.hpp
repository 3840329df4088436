// Running the built cgagen from CLI tests: its exit status and its stdout + stderr, and scratch scripts.
// CGAGEN_EXE, CGA_SOURCE_DIR and CGA_BINARY_DIR come from tests/kernels/CMakeLists.txt.
#pragma once

#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

namespace cga_test {

struct Result {
  int code;
  std::string out;  // stdout and stderr together
};

// A shell command as written (add " 2>&1" for its stderr): its exit status and stdout.
inline Result shell(const std::string& cmd) {
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) throw std::runtime_error("popen failed");
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  int status = pclose(p);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

inline Result run(const std::string& args) { return shell(std::string(CGAGEN_EXE) + " " + args + " 2>&1"); }

// Writes `text` to CGA_BINARY_DIR/name and returns the path.
inline std::string write_temp(const std::string& name, const std::string& text) {
  std::string path = std::string(CGA_BINARY_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

// The whole of the file at `path` (empty if it cannot be read).
inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

inline std::string script(const std::string& name) { return std::string(CGA_SOURCE_DIR) + "/runtime/scripts/" + name; }

}  // namespace cga_test
