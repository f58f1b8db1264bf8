// Allocator for a brick's voxels: large arrays read at random along rays. Blocks of 4 MiB or more
// are aligned to 2 MiB, rounded up to whole 2 MiB pages and advised for transparent huge pages
// (madvise MADV_HUGEPAGE, which Debian's default "madvise" mode needs), so a ray stepping from
// slice to slice, each slice on another 4 KiB page, misses the TLB less. Measured with
// `kdswap bench --nodes 1,1 --interleave` and a temporary switch that gave the advice to one of
// the two clusters only: turbulence 256^3 at P = 1, 512x512, 1.5-6% less wall time in each of
// four runs; the phantom at P = 1 and the P = 8 scenes mostly 1-3% less, within the noise.
// Smaller blocks (a 256^3 volume's bricks at P = 64 are ~2 MiB) and kernels without transparent
// huge pages get ordinary memory.
#pragma once

#include <cstddef>
#include <new>

namespace kdswap {

//! The allocation behind HugePageAllocator; throws std::bad_alloc.
void* allocateMaybeHuge(std::size_t bytes);
void freeMaybeHuge(void* block) noexcept;

template <typename T>
struct HugePageAllocator {
  using value_type = T;
  HugePageAllocator() = default;
  template <typename U>
  HugePageAllocator(const HugePageAllocator<U>&) noexcept {}
  T* allocate(std::size_t n) {
    if (n > std::size_t(-1) / sizeof(T)) throw std::bad_array_new_length();
    return static_cast<T*>(allocateMaybeHuge(n * sizeof(T)));
  }
  void deallocate(T* p, std::size_t) noexcept { freeMaybeHuge(p); }
  template <typename U>
  bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

}  // namespace kdswap
