// NodeArena: slots for the nodes' suspended tasks, threads as asked.
#include "core/cluster/node_arena.h"

#include <algorithm>

#include <oneapi/tbb/info.h>

namespace kdswap {

NodeArena::NodeArena(int threads, int nodes)
    : threads_(threads > 0 ? threads : tbb::info::default_concurrency()),
      slots_(std::max(threads_, (std::max(nodes, 1) + kNodesPerSlot - 1) / kNodesPerSlot)) {
  // Workers may take slots_ - reserved = threads_ - 1 slots; the thread that calls execute() takes
  // a reserved one.
  arena_.initialize(slots_, unsigned(slots_ - threads_ + 1));
}

}  // namespace kdswap
