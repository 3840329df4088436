// libFuzzer target over the script front end and the expander: any byte string must give either a Kernel or
// a CompileError — never a crash, a hang, a leak or another exception type.
#include <cstddef>
#include <cstdint>
#include <string>

#include "expand/expand.hpp"
#include "front/diagnostics.hpp"
#include "front/parser.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cgagen::front::SourceFile file("fuzz.clu", std::string(reinterpret_cast<const char*>(data), size));
  try {
    cgagen::front::Script script = cgagen::front::parse(file);
    cgagen::Kernel kernel = cgagen::expand(script, "fuzz");
    (void)kernel;
  } catch (const cgagen::front::CompileError& e) {
    // The diagnostic must render for any location the front end reports.
    (void)cgagen::front::format_diagnostic(file, e.loc(), e.what());
  }
  return 0;
}
