// ImageView: read-only pixels of a rectangle that lie inside some other image's storage (rows may
// be further apart than the rectangle is wide). It lets a node hand part of its image to another
// node, or composite part of it, without copying the pixels first.
#pragma once

#include <cstdint>

#include "core/image/rect.h"
#include "core/image/rgba.h"

namespace kdswap {

struct ImageView {
  Rect rect;                    //!< frame coordinates of the pixels seen
  const Rgba* first = nullptr;  //!< pixel (rect.x, rect.y)
  std::int64_t stride = 0;      //!< pixels from one row to the next

  bool empty() const { return rect.empty(); }
  //! First pixel of frame row `py` (which must lie in rect).
  const Rgba* row(int py) const { return first + std::int64_t(py - rect.y) * stride; }
  //! The part of this view inside `r` (same storage).
  ImageView within(const Rect& r) const {
    const Rect o = rect.intersect(r);
    if (o.empty()) return ImageView{};
    return ImageView{o, row(o.y) + (o.x - rect.x), stride};
  }
};

}  // namespace kdswap
