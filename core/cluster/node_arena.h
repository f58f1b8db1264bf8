// NodeArena: the oneTBB arena that virtual nodes run in as tasks. Its concurrency is the thread
// count asked for; its slot count is at least a quarter of the nodes it runs, because oneTBB keeps
// four spare coroutines (stacks) per slot, and every node that waits for a message suspends on one.
// With two slots, 64 nodes on 2 threads mapped and unmapped ~55 stacks a frame: each unmap flushes
// the other core's TLB (an inter-processor interrupt, dear in a virtual machine) and each new stack
// faults its pages in again (phantom 256^3 at P = 64: 61 -> 50 ms a frame, turbulence at P = 512
// 670 -> 563 ms). The slots beyond the thread count are reserved for application threads, which
// oneTBB's workers never take, and only the one thread that runs the cluster enters: the arena
// still runs the thread count asked for, and nothing outside it changes.
#pragma once

#include <utility>

#include <oneapi/tbb/task_arena.h>

namespace kdswap {

class NodeArena {
 public:
  //! `threads` workers (0: one per core) for `nodes` nodes.
  NodeArena(int threads, int nodes);

  template <typename F>
  decltype(auto) execute(F&& f) {
    return arena_.execute(std::forward<F>(f));
  }
  //! The thread count asked for (0 resolved to one per core); fewer run where the process allows
  //! fewer (tbb::global_control).
  int threads() const { return threads_; }
  //! Arena slots (>= threads()).
  int slots() const { return slots_; }

  //! Nodes one slot keeps spare coroutines for (oneTBB: 4 per slot).
  static constexpr int kNodesPerSlot = 4;

 private:
  int threads_, slots_;
  tbb::task_arena arena_;
};

}  // namespace kdswap
