// libFuzzer target over the generator's front end, expander and optimizer: any byte string must give either
// an optimized Program or a CompileError, never a crash, a hang, a leak or another exception type. The
// optimizer runs at -O2 (which does the -O1 substitution first), where the shared fuzz find timed out.
#include <cstddef>
#include <cstdint>
#include <string>

#include "expand/expand.hpp"
#include "front/diagnostics.hpp"
#include "front/parser.hpp"
#include "opt/program.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  cgagen::front::SourceFile file("fuzz.clu", std::string(reinterpret_cast<const char*>(data), size));
  try {
    cgagen::front::Script script = cgagen::front::parse(file);
    cgagen::Kernel kernel = cgagen::expand(script, "fuzz");
    for (const auto& w : kernel.warnings) (void)cgagen::front::format_diagnostic(file, w.loc, w.message, "warning");
    cgagen::opt::Program program = cgagen::opt::optimize(kernel, cgagen::opt::Level::O2);
    (void)program;
  } catch (const cgagen::front::CompileError& e) {
    // The diagnostic must render for any location the front end reports.
    (void)cgagen::front::format_diagnostic(file, e.loc(), e.what());
  }
  return 0;
}
