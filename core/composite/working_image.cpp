// WorkingImage: lending without copies, copy on write, and the one-pass layer composite.
#include "core/composite/working_image.h"

#include <algorithm>

#include "core/composite/image_message.h"

namespace kdswap {
namespace {

//! Rows per block in composeLayers: a block of the target (8 rows of a 1024-pixel frame is 128 KiB)
//! stays in the core's cache while every layer is blended onto it.
constexpr int kRowsPerBlock = 8;

const Image kNoImage;

}  // namespace

WorkingImage::WorkingImage(Image image) : image_(std::make_shared<Image>(std::move(image))) {}

const Image& WorkingImage::image() const { return image_ ? *image_ : kNoImage; }

Message WorkingImage::lend(const Rect& part, bool sparse) {
  if (empty()) return lendPixels(ImageView{}, nullptr);
  ImageView view = image_->view(part);
  if (sparse) view = view.within(opaqueBounds(view));
  if (!view.empty()) lent_.push_back(view.rect);
  return lendPixels(view, image_);
}

Image& WorkingImage::writableFor(const Rect& r) {
  const bool touchesLent =
      std::any_of(lent_.begin(), lent_.end(), [&](const Rect& l) { return !l.intersect(r).empty(); });
  if (touchesLent) {  // a reader may still be on those pixels: write a private copy instead
    image_ = std::make_shared<Image>(*image_);
    lent_.clear();
  }
  return *image_;
}

void WorkingImage::merge(const ImageView& theirs, bool theirsInFront, const Rect& keep, std::int64_t& pixels) {
  if (theirs.empty()) return;
  if (!empty() && rect().contains(theirs.rect)) {
    pixels += compositeInto(writableFor(theirs.rect), theirs, theirsInFront);
    return;
  }
  // A new buffer: the given-away parts of ours (lent, or stale) are left behind, not copied.
  const ImageView mine = empty() ? ImageView{} : image_->view(keep);
  if (mine.empty()) {
    *this = WorkingImage(Image(theirs));
    return;
  }
  pixels += theirs.rect.area();
  *this = WorkingImage(theirsInFront ? overOf(theirs, mine) : overOf(mine, theirs));
}

void WorkingImage::composeLayers(const Rect& target, const std::vector<ImageView>& layers, int self,
                                 std::int64_t& pixels) {
  const bool inPlace = self >= 0 && !empty() && rect().contains(target) &&
                       layers[std::size_t(self)].rect == target;
  if (inPlace) {
    // Behind ours, nearest first (dst over layer); then in front, nearest first (layer over dst).
    Image& dst = writableFor(target);
    for (int y0 = target.y; y0 < target.bottom(); y0 += kRowsPerBlock) {
      const Rect block{target.x, y0, target.w, std::min(kRowsPerBlock, target.bottom() - y0)};
      for (int i = self + 1; i < int(layers.size()); ++i)
        pixels += compositeInto(dst, layers[std::size_t(i)].within(block), false);
      for (int i = self - 1; i >= 0; --i) pixels += compositeInto(dst, layers[std::size_t(i)].within(block), true);
    }
    return;
  }
  // Sparse or missing own pixels: build the result in a new buffer, accumulating front to back.
  Rect covered;
  for (const ImageView& layer : layers) covered = covered.unite(layer.rect.intersect(target));
  // When the front layer covers it all, start from a copy of it (one write instead of clearing
  // the new buffer and blending onto transparent).
  const bool startFromFront = !layers.empty() && layers[0].rect.intersect(target) == covered;
  Image result = startFromFront ? Image(layers[0].within(target)) : Image(covered);
  for (int y0 = covered.y; y0 < covered.bottom(); y0 += kRowsPerBlock) {
    const Rect block{covered.x, y0, covered.w, std::min(kRowsPerBlock, covered.bottom() - y0)};
    for (std::size_t i = startFromFront ? 1 : 0; i < layers.size(); ++i)
      pixels += compositeInto(result, layers[i].within(block), false);
  }
  *this = WorkingImage(std::move(result));
}

Tile WorkingImage::finish(const Rect& region) {
  Tile tile{region, empty() ? ImageView{} : image_->view(region), image_};
  image_.reset();
  lent_.clear();
  return tile;
}

}  // namespace kdswap
