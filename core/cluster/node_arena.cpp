// NodeArena: slots for the nodes' suspended tasks, threads as asked.
#include "core/cluster/node_arena.h"

#include <algorithm>

#include <oneapi/tbb/info.h>

namespace kdswap {

NodeArena::NodeArena(int threads, int nodes)
    : threads_(threads > 0 ? threads : tbb::info::default_concurrency()),
      slots_(std::max(threads_, (std::max(nodes, 1) + kNodesPerSlot - 1) / kNodesPerSlot)) {
  // Workers come from the process's pool, which allows max_allowed_parallelism threads in all
  // (one per core unless set lower): extra slots stay empty when the thread count is at that bound
  // already; below it the bound is lowered while this arena lives.
  const auto allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  if (slots_ > threads_ && std::size_t(threads_) < allowed)
    limit_.emplace(tbb::global_control::max_allowed_parallelism, std::size_t(threads_));
  arena_.initialize(slots_);
}

}  // namespace kdswap
