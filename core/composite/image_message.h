// Moving images through messages, and merging a received image with a kept one.
#pragma once

#include "core/comm/message.h"
#include "core/image/image.h"

namespace kdswap {

//! The image's pixels are moved into the message (header: x, y, w, h).
Message imageToMessage(Image image);
//! A message lending the pixels `view` sees (header as above); `owner` keeps them alive.
Message lendPixels(const ImageView& view, std::shared_ptr<const void> owner);
//! The pixels a message carries, moved or lent, seen in place (valid while the message lives);
//! throws kdswap::Error if the header and the data disagree.
ImageView viewOfMessage(const Message& message);
//! Takes the pixels out (copying them if they were lent); throws as viewOfMessage does.
Image imageFromMessage(Message& message);
//! Composite of `mine` and `theirs` over the union of their rects; `theirsInFront` gives the
//! order. `pixels` receives the number of pixels blended.
Image mergeImages(Image mine, Image theirs, bool theirsInFront, std::int64_t& pixels);
//! The image cut down to the bounding rectangle of its non-empty pixels (exact: "over" with an
//! empty pixel changes nothing). Used for sparse messages and for each node's partial image.
Image trimToContent(Image image);
//! trimToContent with the content's bounds already known (they must be image.opaqueBounds()).
Image trimTo(Image image, const Rect& content);

}  // namespace kdswap
