// The -O2 pass table, for the command line (cgagen --passes): each pass's name and what it does, in the
// order the optimizer runs them (the table itself, with the functions, is in pipeline.cpp).
#pragma once

#include <string>
#include <vector>

namespace cgagen::opt {

struct PassInfo {
  std::string name;
  std::string description;
};

// The -O2 passes in run order; a pass that runs more than once has one row per run.
std::vector<PassInfo> pass_table();

}  // namespace cgagen::opt
