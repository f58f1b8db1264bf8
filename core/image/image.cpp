// Image storage and the "over" operator on premultiplied colour (Porter & Duff 1984).
#include "core/image/image.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "core/image/pixel_pool.h"
#include "core/util/check.h"

namespace kdswap {

Image::Image(const Rect& rect) : rect_(rect.empty() ? Rect{} : rect) {
  values_ = pixel_pool::take(std::size_t(rect_.area()) * 4);
  values_.resize(std::size_t(rect_.area()) * 4, 0.0f);
}

Image::~Image() { pixel_pool::give(values_); }

Image::Image(const Image& other) : rect_(other.rect_) {
  values_ = pixel_pool::take(other.values_.size());
  values_.assign(other.values_.begin(), other.values_.end());
}

Image& Image::operator=(const Image& other) {
  if (this != &other) {
    rect_ = other.rect_;
    values_.assign(other.values_.begin(), other.values_.end());
  }
  return *this;
}

Image& Image::operator=(Image&& other) noexcept {
  if (this != &other) {
    pixel_pool::give(values_);
    rect_ = other.rect_;
    values_ = std::move(other.values_);
  }
  return *this;
}

Image::Image(const Rect& rect, std::vector<float> values)
    : rect_(rect.empty() ? Rect{} : rect), values_(std::move(values)) {
  KDSWAP_CHECK_EQ(values_.size(), std::size_t(rect_.area()) * 4);
}

Image::Image(const ImageView& view) : rect_(view.rect.empty() ? Rect{} : view.rect) {
  // Rows are appended, not copied over zeros: one pass over the pixels (compositing moves a lot
  // of them, so this matters).
  values_ = pixel_pool::take(std::size_t(rect_.area()) * 4);
  for (int y = rect_.y; y < rect_.bottom(); ++y) {
    const float* row = &view.row(y)->r;
    values_.insert(values_.end(), row, row + std::size_t(rect_.w) * 4);
  }
}

Image Image::crop(const Rect& r) const { return Image(view(r)); }

Image Image::extendedTo(const Rect& r) const {
  KDSWAP_CHECK(r.contains(rect_));
  Image out(r);
  for (int y = rect_.y; y < rect_.bottom(); ++y)
    std::memcpy(&out.at(rect_.x, y), &at(rect_.x, y), sizeof(Rgba) * std::size_t(rect_.w));
  return out;
}

Rect Image::opaqueBounds() const { return kdswap::opaqueBounds(view()); }

Rect opaqueBounds(const ImageView& view) {
  const Rect& r = view.rect;
  int x0 = r.right(), y0 = r.bottom(), x1 = r.x - 1, y1 = r.y - 1;
  for (int y = r.y; y < r.bottom(); ++y) {
    const Rgba* row = view.row(y);
    for (int i = 0; i < r.w; ++i) {
      if (row[i].a > 0.0f) {
        x0 = std::min(x0, r.x + i);
        x1 = std::max(x1, r.x + i);
        y0 = std::min(y0, y);
        y1 = std::max(y1, y);
      }
    }
  }
  if (x1 < x0) return Rect{};
  return Rect{x0, y0, x1 - x0 + 1, y1 - y0 + 1};
}

std::int64_t compositeInto(Image& dst, const ImageView& other, bool otherInFront) {
  const Rect& r = other.rect;
  if (r.empty()) return 0;
  KDSWAP_CHECK(dst.rect().contains(r));
  for (int y = r.y; y < r.bottom(); ++y) {
    Rgba* d = &dst.at(r.x, y);
    const Rgba* s = other.row(y);
    if (otherInFront) {
      for (int i = 0; i < r.w; ++i) d[i] = over(s[i], d[i]);
    } else {
      for (int i = 0; i < r.w; ++i) d[i] = over(d[i], s[i]);
    }
  }
  return r.area();
}

Image overOf(const ImageView& front, const ImageView& back) {
  const Rect both = front.rect.unite(back.rect);
  std::vector<float> values = pixel_pool::take(std::size_t(both.area()) * 4);
  auto append = [&values](const Rgba* pixels, int n) {
    values.insert(values.end(), &pixels->r, &pixels->r + std::size_t(n) * 4);
  };
  for (int y = both.y; y < both.bottom(); ++y) {
    // The row is appended piece by piece in x order, each pixel written once: where neither
    // image covers it transparent, where one does a copy, where both do `back` copied and
    // `front` blended onto it while the row is still in the cache.
    const bool inBack = y >= back.rect.y && y < back.rect.bottom();
    const bool inFront = y >= front.rect.y && y < front.rect.bottom();
    const int backLo = inBack ? back.rect.x : both.right(), backHi = inBack ? back.rect.right() : both.right();
    const int frontLo = inFront ? front.rect.x : both.right(), frontHi = inFront ? front.rect.right() : both.right();
    const Rgba* b = inBack ? back.row(y) - back.rect.x : nullptr;  // indexed by frame x
    const Rgba* f = inFront ? front.row(y) - front.rect.x : nullptr;
    for (int x = both.x; x < both.right();) {
      const bool coveredByBack = x >= backLo && x < backHi, coveredByFront = x >= frontLo && x < frontHi;
      // The piece ends where either image starts or ends.
      int end = both.right();
      for (const int edge : {backLo, backHi, frontLo, frontHi})
        if (edge > x) end = std::min(end, edge);
      const int n = end - x;
      if (coveredByBack) {
        const std::size_t at = values.size();
        append(b + x, n);
        if (coveredByFront) {
          Rgba* row = reinterpret_cast<Rgba*>(values.data() + at) - x;
          for (int i = x; i < end; ++i) row[i] = over(f[i], row[i]);
        }
      } else if (coveredByFront) {
        append(f + x, n);
      } else {
        values.insert(values.end(), std::size_t(n) * 4, 0.0f);
      }
      x = end;
    }
  }
  return Image(both, std::move(values));
}

Image assemble(const Rect& frame, const std::vector<Image>& pieces) {
  Image out(frame);
  for (const Image& piece : pieces) {
    const Rect r = piece.rect().intersect(frame);
    for (int y = r.y; y < r.bottom(); ++y)
      std::memcpy(&out.at(r.x, y), &piece.at(r.x, y), sizeof(Rgba) * std::size_t(r.w));
  }
  return out;
}

float maxAbsDifference(const Image& a, const Image& b, const Rect& frame) {
  float worst = 0.0f;
  for (int y = frame.y; y < frame.bottom(); ++y) {
    for (int x = frame.x; x < frame.right(); ++x) {
      const Rgba p = a.sample(x, y), q = b.sample(x, y);
      const float d = std::max({std::fabs(p.r - q.r), std::fabs(p.g - q.g), std::fabs(p.b - q.b),
                                std::fabs(p.a - q.a)});
      if (!(d <= worst)) worst = d;  // NaN propagates as a failure
    }
  }
  return worst;
}

}  // namespace kdswap
