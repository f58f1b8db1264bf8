// Image: premultiplied RGBA float pixels covering a Rect of the frame (not necessarily all of it).
// Pixels outside the rect are transparent black by definition, which is what makes sparse
// (bounding-rectangle) compositing cheap: a node only stores what its brick could cover.
#pragma once

#include <vector>

#include "core/image/image_view.h"
#include "core/image/rect.h"

namespace kdswap {

class Image {
 public:
  Image() = default;
  //! Transparent image covering `rect` (frame coordinates).
  explicit Image(const Rect& rect);
  //! Adopts `values` (4 floats per pixel, row-major over `rect`); used when a message arrives.
  Image(const Rect& rect, std::vector<float> values);
  //! A copy of the pixels `view` sees.
  explicit Image(const ImageView& view);
  // Storage comes from and goes back to the pixel pool (pixel_pool.h).
  ~Image();
  Image(const Image& other);
  Image(Image&&) noexcept = default;
  Image& operator=(const Image& other);
  Image& operator=(Image&& other) noexcept;

  const Rect& rect() const { return rect_; }
  bool empty() const { return rect_.empty(); }
  int width() const { return rect_.w; }
  int height() const { return rect_.h; }

  //! Pixel at frame coordinates (px, py), which must lie inside rect().
  Rgba& at(int px, int py) { return pixelsAt(px, py); }
  const Rgba& at(int px, int py) const { return const_cast<Image*>(this)->pixelsAt(px, py); }
  //! Value at frame coordinates; transparent outside rect().
  Rgba sample(int px, int py) const { return rect_.contains(px, py) ? at(px, py) : Rgba{}; }

  Rgba* data() { return reinterpret_cast<Rgba*>(values_.data()); }
  const Rgba* data() const { return reinterpret_cast<const Rgba*>(values_.data()); }
  //! The raw float storage, for moving into a message without copying.
  std::vector<float>& values() { return values_; }
  const std::vector<float>& values() const { return values_; }
  std::size_t bytes() const { return values_.size() * sizeof(float); }

  //! Read-only view of the whole image, or of the part inside `r`; valid while the image lives
  //! and is not resized.
  ImageView view() const { return ImageView{rect_, data(), rect_.w}; }
  ImageView view(const Rect& r) const { return view().within(r); }

  //! Copy of the part of this image inside `r` (the result's rect is rect() ∩ r).
  Image crop(const Rect& r) const;
  //! This image re-laid over `r` (which must contain rect()); new pixels are transparent.
  Image extendedTo(const Rect& r) const;
  //! Smallest rect holding every pixel with alpha > 0 (empty if none).
  Rect opaqueBounds() const;

 private:
  Rgba& pixelsAt(int px, int py) {
    return reinterpret_cast<Rgba*>(values_.data())[std::size_t(py - rect_.y) * rect_.w + (px - rect_.x)];
  }

  Rect rect_;
  std::vector<float> values_;  //!< 4 floats per pixel, premultiplied r, g, b, a
};

//! Smallest rect holding every pixel of `view` with alpha > 0 (empty if none).
Rect opaqueBounds(const ImageView& view);

//! front over back, premultiplied: back + (1 - front.a) * ... written as front + (1 - front.a) * back.
inline Rgba over(const Rgba& front, const Rgba& back) {
  const float t = 1.0f - front.a;
  return Rgba{front.r + t * back.r, front.g + t * back.g, front.b + t * back.b, front.a + t * back.a};
}

//! Composites `other` into `dst` over the pixels of other.rect(), which dst.rect() must contain.
//! `otherInFront` says which of the two is nearer the eye for this view.
//! Returns the number of pixels composited.
std::int64_t compositeInto(Image& dst, const ImageView& other, bool otherInFront);
inline std::int64_t compositeInto(Image& dst, const Image& other, bool otherInFront) {
  return compositeInto(dst, other.view(), otherInFront);
}

//! `front` over `back` on the union of their rects (pixels only one of them covers are copied,
//! as over a transparent pixel). Equal, bit for bit, to extending one to the union and compositing
//! the other into it, but each pixel of the result is written once: no clearing, no copy first.
Image overOf(const ImageView& front, const ImageView& back);

//! Full-frame image assembled from pieces (tiles or partial images); pixels outside every piece
//! are transparent. Pieces are pasted, not composited.
Image assemble(const Rect& frame, const std::vector<Image>& pieces);

//! Largest absolute difference of any channel between two images over `frame`.
float maxAbsDifference(const Image& a, const Image& b, const Rect& frame);

}  // namespace kdswap
