// Values of large shared expression nodes kept between calls of the float probes and the symbol counts,
// for as long as a NodeCacheScope is open on the thread. The expander and the optimizer each open one; an
// inner scope uses the outer one's caches, so a driver that opens one around both shares them.
// Entries hold their node alive, so an address is never reused for another node while the scope lives.
// With no scope open nothing is kept between calls. That matters in a long-lived process (the fuzzer):
// each input then frees all it allocated, and no input's work depends on the inputs before it.
#pragma once

#include <array>
#include <cstddef>
#include <memory>
#include <unordered_map>

#include <ginac/ginac.h>

namespace cgagen::symbolic {

struct NodeCaches {
  // Entries per map before it is emptied: bounds the memory of one very large script.
  static constexpr std::size_t kMaxEntries = 20000;

  struct Value {
    GiNaC::ex node;
    GiNaC::numeric value;
  };
  struct Count {
    GiNaC::ex node;
    std::size_t count;
  };
  std::array<std::unordered_map<const GiNaC::basic*, Value>, 2> probe_values;  // per probe point
  std::unordered_map<const GiNaC::basic*, Count> symbol_counts;

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
