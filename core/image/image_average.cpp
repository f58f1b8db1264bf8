// ImageAverage: running sums of premultiplied pixels.
#include "core/image/image_average.h"

namespace kdswap {

ImageAverage::ImageAverage(const Rect& frame) : sum_(frame) {}

void ImageAverage::add(const Image& image) {
  const Rect overlap = sum_.rect().intersect(image.rect());
  for (int y = overlap.y; y < overlap.bottom(); ++y)
    for (int x = overlap.x; x < overlap.right(); ++x) {
      const Rgba& p = image.at(x, y);
      Rgba& s = sum_.at(x, y);
      s.r += p.r, s.g += p.g, s.b += p.b, s.a += p.a;
    }
  ++count_;
}

Image ImageAverage::mean() const {
  Image mean = sum_;
  if (count_ == 0) return mean;
  const float scale = 1.0f / float(count_);
  for (float& v : mean.values()) v *= scale;
  return mean;
}

}  // namespace kdswap
