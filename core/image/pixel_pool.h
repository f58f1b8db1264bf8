// Pixel pool: large pixel buffers kept for reuse instead of handed back to the system. A fresh
// buffer costs a page fault per 4 KiB on first touch (the kernel zeroes every page), which in
// compositing is about as much work as blending into it; a reused buffer is already mapped. Every
// Image takes its storage from the process-wide pool and gives it back when it dies.
#pragma once

#include <cstddef>
#include <vector>

namespace kdswap::pixel_pool {

//! An empty vector whose capacity is at least `floats` (a pooled one when a close fit is kept).
std::vector<float> take(std::size_t floats);
//! Keeps `buffer`'s storage for a later take() if it is large and the pool has room (else it is
//! freed); leaves `buffer` empty.
void give(std::vector<float>& buffer);
//! Bytes held for reuse now.
std::size_t pooledBytes();

}  // namespace kdswap::pixel_pool
