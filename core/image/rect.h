// Integer pixel rectangle in frame coordinates: [x, x+w) x [y, y+h), y down. Empty when w or h <= 0.
#pragma once

#include <algorithm>
#include <cstdint>

namespace kdswap {

struct Rect {
  int x = 0, y = 0, w = 0, h = 0;

  bool empty() const { return w <= 0 || h <= 0; }
  std::int64_t area() const { return empty() ? 0 : std::int64_t(w) * h; }
  int right() const { return x + w; }
  int bottom() const { return y + h; }
  bool contains(int px, int py) const { return px >= x && px < right() && py >= y && py < bottom(); }
  bool contains(const Rect& r) const {
    return r.empty() || (r.x >= x && r.y >= y && r.right() <= right() && r.bottom() <= bottom());
  }
  bool operator==(const Rect&) const = default;

  Rect intersect(const Rect& r) const {
    const int nx = std::max(x, r.x), ny = std::max(y, r.y);
    const int nr = std::min(right(), r.right()), nb = std::min(bottom(), r.bottom());
    if (nr <= nx || nb <= ny) return Rect{};
    return Rect{nx, ny, nr - nx, nb - ny};
  }
  //! Smallest rectangle holding both; an empty operand is ignored.
  Rect unite(const Rect& r) const {
    if (empty()) return r.empty() ? Rect{} : r;
    if (r.empty()) return *this;
    const int nx = std::min(x, r.x), ny = std::min(y, r.y);
    return Rect{nx, ny, std::max(right(), r.right()) - nx, std::max(bottom(), r.bottom()) - ny};
  }
};

//! Slice `index` of `count` equal slices of `r`, cut across x (axis 0) or y (axis 1). Slices are
//! empty when `r` is thinner than `count` pixels; together they always cover `r` exactly.
inline Rect sliceOf(const Rect& r, int axis, int index, int count) {
  const auto cut = [&](int length, int i) { return int(std::int64_t(length) * i / count); };
  Rect s = r;
  if (axis == 0) {
    s.x = r.x + cut(r.w, index);
    s.w = r.x + cut(r.w, index + 1) - s.x;
  } else {
    s.y = r.y + cut(r.h, index);
    s.h = r.y + cut(r.h, index + 1) - s.y;
  }
  return s;
}

}  // namespace kdswap
