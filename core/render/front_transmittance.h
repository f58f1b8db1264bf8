// FrontTransmittance: front-to-back waves (beyond the paper). The paper's nodes render
// independently, so a brick cannot know that matter in front of it already stops a ray; the
// occlusion map (occlusion_map.h) proves it from a replicated summary where it can, which misses
// thin or noisy matter. In waves the bricks render nearest first (one after another where their
// screen rectangles overlap), and each multiplies its partial image's transmittance into this frame-sized buffer: a brick then stops
// each ray where the light left in front of it times its own transmittance reaches the single-node
// ray's stop, and skips pixels already stopped. The brick behind thus takes the samples the
// single-node ray takes (no more), at the price of passing this buffer between nodes while they
// render: in one process a shared array read and written in visibility order.
#pragma once

#include <cstddef>
#include <vector>

#if defined(__SSE2__)
#include <xmmintrin.h>
#endif

#include "core/image/image.h"
#include "core/image/pixel_pool.h"
#include "core/image/rect.h"

namespace kdswap {

class FrontTransmittance {
 public:
  //! Every pixel of `frame` starts fully lit (transmittance 1). The buffer comes from the pixel
  //! pool: a fresh megabyte each frame paid its page faults in the waves' single-threaded set-up
  //! (0.10-0.13 ms at 512^2, phantom P = 64); a reused one is only filled (0.06-0.09 ms).
  explicit FrontTransmittance(const Rect& frame) : frame_(frame), values_(pixel_pool::take(std::size_t(frame.area()))) {
    values_.resize(std::size_t(frame.area()), 1.0f);
  }
  ~FrontTransmittance() { pixel_pool::give(values_); }
  FrontTransmittance(const FrontTransmittance&) = delete;
  FrontTransmittance& operator=(const FrontTransmittance&) = delete;

  //! The light left in front at pixel (x, y) of the frame.
  float at(int x, int y) const {
    return values_[offset(x, y)];
  }

  //! The light at pixel (x, y), for a brick that renders it to dim in place.
  float& lightAt(int x, int y) {
    return values_[offset(x, y)];
  }

  //! Bit j (j < n <= 8): the light in front of pixel (x + j, y) is spent, at(x + j, y) <= stop.
  int spentIn(int x, int y, int n, float stop) const {
    const float* t = &values_[offset(x, y)];
#if defined(__SSE2__)
    if (n == 8) {
      const __m128 s = _mm_set1_ps(stop);
      return _mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(t), s)) | _mm_movemask_ps(_mm_cmple_ps(_mm_loadu_ps(t + 4), s)) << 4;
    }
#endif
    int bits = 0;
    for (int j = 0; j < n; ++j) bits |= int(t[j] <= stop) << j;
    return bits;
  }

  //! Adds a brick rendered behind every brick added so far: its partial image's opacity
  //! (premultiplied "over" image: alpha = 1 - its transmittance) dims the pixels it covers. The
  //! waves' casters dim in place as they render (lightAt), to the same bits; this is the whole-image
  //! form they are tested against.
  void addBehind(const Image& partial);

 private:
  std::size_t offset(int x, int y) const {
    return std::size_t(y - frame_.y) * std::size_t(frame_.w) + std::size_t(x - frame_.x);
  }

  Rect frame_;
  std::vector<float> values_;
};

}  // namespace kdswap
