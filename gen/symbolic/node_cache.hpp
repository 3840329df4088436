// Values of large shared expression nodes kept between calls of the float probes and the symbol counts,
// for as long as a NodeCacheScope is open on the thread. The expander and the optimizer each open one; an
// inner scope uses the outer one's caches, so a driver that opens one around both shares them.
// With no scope open nothing is kept between calls. That matters in a long-lived process (the fuzzer):
// each input then frees all it allocated, and no input's work depends on the inputs before it.
#pragma once

#include <array>
#include <cstddef>
#include <memory>

#include <ginac/ginac.h>

#include "symbolic/dag.hpp"

namespace cgagen::symbolic {

struct NodeCaches {
  std::array<NodeTable<GiNaC::numeric>, 2> probe_values;  // per probe point
  NodeTable<std::size_t> symbol_counts;

  // The caches of the thread's open scope, or nullptr.
  static NodeCaches* current();
};

class NodeCacheScope {
 public:
  NodeCacheScope();
  ~NodeCacheScope();
  NodeCacheScope(const NodeCacheScope&) = delete;
  NodeCacheScope& operator=(const NodeCacheScope&) = delete;

 private:
  std::unique_ptr<NodeCaches> owned_;  // null when an outer scope's caches are used
};

}  // namespace cgagen::symbolic
