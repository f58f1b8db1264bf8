// NodeArena: slots for a quarter of the nodes (oneTBB's spare coroutines for suspended nodes), and
// never more threads at once than asked for.
#include <doctest/doctest.h>

#include <chrono>
#include <mutex>
#include <set>
#include <thread>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/parallel_for.h>

#include "core/cluster/node_arena.h"

using namespace kdswap;

namespace {

//! Distinct threads that ran a parallel loop of short sleeps inside `arena`.
std::size_t threadsInLoop(NodeArena& arena) {
  std::mutex mutex;
  std::set<std::thread::id> seen;
  arena.execute([&] {
    tbb::parallel_for(0, 400, [&](int) {
      std::this_thread::sleep_for(std::chrono::microseconds(100));
      std::lock_guard<std::mutex> lock(mutex);
      seen.insert(std::this_thread::get_id());
    });
  });
  return seen.size();
}

}  // namespace

TEST_CASE("node arena: a slot per four nodes, at least one per thread") {
  CHECK(NodeArena(2, 8).slots() == 2);
  CHECK(NodeArena(2, 64).slots() == 16);
  CHECK(NodeArena(2, 65).slots() == 17);
  CHECK(NodeArena(4, 1).slots() == 4);
  CHECK(NodeArena(1, 512).slots() == 128);
  CHECK(NodeArena(0, 4).threads() >= 1);
}

TEST_CASE("node arena: extra slots add no threads, and nothing outside the arena changes") {
  const std::size_t allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  // One thread asked for, 16 slots: oneTBB's workers could take the spare slots on a machine with
  // several cores unless they are reserved for the calling thread.
  NodeArena one(1, 64);
  CHECK(one.slots() == 16);
  CHECK(threadsInLoop(one) == 1);
  // Two asked for: at most two, whatever the machine has.
  NodeArena two(2, 64);
  CHECK(threadsInLoop(two) <= 2);
  // The process's bound on threads is untouched (other arenas keep their workers).
  CHECK(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism) == allowed);
}
