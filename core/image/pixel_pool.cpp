// Pixel pool: a small best-fit free list under one mutex (takes and gives are a few per node per
// frame, each for megabytes, so the lock is never contended for long).
#include "core/image/pixel_pool.h"

#include <algorithm>
#include <mutex>

namespace kdswap::pixel_pool {
namespace {

constexpr std::size_t kMinPooledFloats = std::size_t(64) << 10;   //!< 256 KiB: smaller ones are cheap
constexpr std::size_t kMaxPooledBytes = std::size_t(128) << 20;   //!< what idle buffers may hold
constexpr std::size_t kMaxWaste = 2;  //!< never hand out a buffer more than 2x the size asked for

struct Pool {
  std::mutex mutex;
  std::vector<std::vector<float>> free;
  std::size_t bytes = 0;
};

Pool& pool() {
  static Pool* p = new Pool;  // never destroyed: images may die during static destruction
  return *p;
}

// Sanitizer builds get fresh buffers every time, so a use after free is still caught.
#if defined(KDSWAP_SANITIZED)
constexpr bool kPooling = false;
#else
constexpr bool kPooling = true;
#endif

}  // namespace

std::vector<float> take(std::size_t floats) {
  std::vector<float> out;
  if (kPooling && floats >= kMinPooledFloats) {
    Pool& p = pool();
    std::lock_guard<std::mutex> lock(p.mutex);
    std::size_t best = p.free.size();
    for (std::size_t i = 0; i < p.free.size(); ++i) {
      const std::size_t c = p.free[i].capacity();
      if (c >= floats && c <= floats * kMaxWaste && (best == p.free.size() || c < p.free[best].capacity())) best = i;
    }
    if (best < p.free.size()) {
      out = std::move(p.free[best]);
      p.free[best] = std::move(p.free.back());
      p.free.pop_back();
      p.bytes -= out.capacity() * sizeof(float);
    } else {
      // A miss allocates fresh memory: first hand back idle buffers of at least that size, so the
      // new buffer takes their place instead of adding to the process's peak.
      std::size_t released = 0;
      while (!p.free.empty() && released < floats) {
        auto largest = std::max_element(p.free.begin(), p.free.end(),
                                        [](const auto& a, const auto& b) { return a.capacity() < b.capacity(); });
        released += largest->capacity();
        p.bytes -= largest->capacity() * sizeof(float);
        std::vector<float>().swap(*largest);
        *largest = std::move(p.free.back());
        p.free.pop_back();
      }
    }
  }
  out.clear();
  out.reserve(floats);
  return out;
}

void give(std::vector<float>& buffer) {
  std::vector<float> kept = std::move(buffer);
  buffer.clear();
  const std::size_t bytes = kept.capacity() * sizeof(float);
  if (!kPooling || kept.capacity() < kMinPooledFloats) return;
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  if (p.bytes + bytes > kMaxPooledBytes) return;  // `kept` is freed after the lock is released
  p.bytes += bytes;
  p.free.push_back(std::move(kept));
}

std::size_t pooledBytes() {
  Pool& p = pool();
  std::lock_guard<std::mutex> lock(p.mutex);
  return p.bytes;
}

}  // namespace kdswap::pixel_pool
