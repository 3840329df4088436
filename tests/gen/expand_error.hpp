// The expander's verdict on a script, as text: what the operator and exp/log tests compare their located
// errors with.
#pragma once

#include <string>

#include "algebra/algebra.hpp"
#include "expand/expand.hpp"
#include "front/diagnostics.hpp"
#include "front/parser.hpp"

namespace {

// The "bad.clu:line:col: error: message" text of expanding `script` in the built-in algebra `name`, or
// "no error".
inline std::string error_of(const std::string& name, const std::string& script) {
  cgagen::front::SourceFile file("bad.clu", script);
  try {
    cgagen::expand(cgagen::front::parse(file), "bad", cgagen::algebra::builtin(name));
  } catch (const cgagen::front::CompileError& e) {
    return "bad.clu:" + std::to_string(e.loc().line) + ":" + std::to_string(e.loc().col) + ": error: " + e.what();
  }
  return "no error";
}

}  // namespace
