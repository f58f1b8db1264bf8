// WorkingImage: the image a node composites into during one frame, able to lend parts of itself
// to other nodes instead of copying them into messages (zero-copy compositing in process).
//
// A strategy lends the parts it gives away and keeps compositing into the part it keeps; those
// are disjoint in every strategy, so the partner reads lent pixels while this node writes others.
// Lent pixels are frozen all the same: a write that would touch one first moves the image to a
// fresh buffer (copy on write), so no order of phases can change what a slower node still reads.
// The buffer lives until the last message lending from it is dropped.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "core/comm/message.h"
#include "core/composite/strategy.h"
#include "core/image/image.h"

namespace kdswap {

class WorkingImage {
 public:
  WorkingImage() = default;
  explicit WorkingImage(Image image);

  bool empty() const { return !image_ || image_->empty(); }
  //! The whole buffer, for phase observers (pixels outside the node's current region are stale).
  const Image& image() const;
  Rect rect() const { return image_ ? image_->rect() : Rect{}; }
  //! Read-only view of the part inside `r` (valid until this image is next changed).
  ImageView view(const Rect& r) const { return image().view(r); }

  //! A message lending the pixels inside `part` (cut to their non-empty bounds when `sparse`).
  Message lend(const Rect& part, bool sparse);
  //! Composites `theirs` with this image; `theirsInFront` gives the order. Only the pixels inside
  //! `keep` (the node's region from here on) are needed afterwards: where the result needs a new
  //! buffer it covers theirs and this image's part inside `keep`, not the parts given away.
  //! Adds the pixels blended to `pixels`.
  void merge(const ImageView& theirs, bool theirsInFront, const Rect& keep, std::int64_t& pixels);
  //! Makes the pixels of `target` the composite of `layers`, given front to back. Layer `self`
  //! (or none, -1) is this image's own part of `target`: the others are blended onto it in place,
  //! in one pass over row blocks, so the result is written once. Adds the pixels blended.
  void composeLayers(const Rect& target, const std::vector<ImageView>& layers, int self, std::int64_t& pixels);
  //! The finished tile: the pixels inside `region`, left where they are (the tile shares the
  //! buffer). Leaves this image empty.
  Tile finish(const Rect& region);

 private:
  //! The image, made safe to write inside `r` (copied first if `r` touches a lent part).
  Image& writableFor(const Rect& r);

  std::shared_ptr<Image> image_;
  std::vector<Rect> lent_;
};

}  // namespace kdswap
