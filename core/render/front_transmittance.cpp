// FrontTransmittance: the product, per pixel, of the transmittance of the bricks rendered so far.
#include "core/render/front_transmittance.h"

namespace kdswap {

void FrontTransmittance::addBehind(const Image& partial) {
  const Rect r = partial.rect().intersect(frame_);
  for (int y = r.y; y < r.bottom(); ++y) {
    float* t = values_.data() + std::size_t(y - frame_.y) * std::size_t(frame_.w) + std::size_t(r.x - frame_.x);
    const Rgba* p = &partial.at(r.x, y);
    for (int i = 0; i < r.w; ++i) t[i] *= 1.0f - p[i].a;
  }
}

}  // namespace kdswap
