// ThreadSanitizer builds only (scripts/tsan.sh): oneTBB runs every parallel loop on the thread
// that calls it. Debian's libtbb is not instrumented, so TSan cannot see the synchronisation
// inside its scheduler: each hand-over of a loop body between oneTBB worker threads (and the
// caller reading the results afterwards) would be reported as a race in kdswap's loop body. With
// no workers, each virtual node (one std::thread in sanitizer builds, NodeExecution::Threads) runs
// its ray caster's loops itself, and the concurrency left is kdswap's own, all instrumented: node
// threads, mailboxes, the stall watchdog and the host.
#include <cstdio>

#include <oneapi/tbb/global_control.h>
#include <oneapi/tbb/tbb_allocator.h>

namespace {

//! Lives for the whole test run; constructed before main, destroyed after it.
const tbb::global_control kOneThreadPerCaller(tbb::global_control::max_allowed_parallelism, 1);

//! scripts/tsan.sh hides libtbbmalloc from oneTBB (why: there); say so when it is in use anyway.
const bool kWarnedAboutTbbmalloc = [] {
  const bool scalable = tbb::tbb_allocator<char>::allocator_type() == tbb::tbb_allocator<char>::scalable;
  if (scalable)
    std::fprintf(stderr, "kdswap_tests (ThreadSanitizer build): oneTBB allocates from libtbbmalloc, whose recycled "
                         "blocks TSan cannot follow; scripts/tsan.sh runs the tests without it.\n");
  return scalable;
}();

}  // namespace
