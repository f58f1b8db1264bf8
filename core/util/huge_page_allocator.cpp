// Large blocks are advised before their first touch: the advice applies to pages faulted in
// afterwards (khugepaged would merge pages touched earlier only slowly, if at all).
#include "core/util/huge_page_allocator.h"

#include <cstdlib>
#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace kdswap {
namespace {
constexpr std::size_t kHugePage = std::size_t(2) << 20;
constexpr std::size_t kHugeFrom = std::size_t(4) << 20;
}  // namespace

void* allocateMaybeHuge(std::size_t bytes) {
  if (bytes < kHugeFrom) {
    if (void* p = std::malloc(bytes == 0 ? 1 : bytes)) return p;
    throw std::bad_alloc();
  }
  if (bytes > std::size_t(-1) - kHugePage) throw std::bad_alloc();
  const std::size_t rounded = (bytes + kHugePage - 1) / kHugePage * kHugePage;
  void* p = std::aligned_alloc(kHugePage, rounded);
  if (!p) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  madvise(p, rounded, MADV_HUGEPAGE);  // advice only: where it fails the block keeps 4 KiB pages
#endif
  return p;
}

void freeMaybeHuge(void* block) noexcept { std::free(block); }

}  // namespace kdswap
