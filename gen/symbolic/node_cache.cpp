// The thread's scoped node caches (see node_cache.hpp).
#include "symbolic/node_cache.hpp"

namespace cgagen::symbolic {
namespace {
thread_local NodeCaches* open_caches = nullptr;
}

NodeCaches* NodeCaches::current() { return open_caches; }

NodeCacheScope::NodeCacheScope() {
  if (open_caches) return;
  owned_ = std::make_unique<NodeCaches>();
  open_caches = owned_.get();
}

NodeCacheScope::~NodeCacheScope() {
  if (owned_) open_caches = nullptr;
}

}  // namespace cgagen::symbolic
