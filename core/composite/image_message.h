// Moving images through messages, and merging a received image with a kept one.
#pragma once

#include "core/comm/message.h"
#include "core/image/image.h"

namespace kdswap {

//! The image's pixels are moved into the message (header: x, y, w, h).
Message imageToMessage(Image image);
//! Takes the pixels back out; throws kdswap::Error if the header and payload disagree.
Image imageFromMessage(Message& message);
//! Composite of `mine` and `theirs` over the union of their rects; `theirsInFront` gives the
//! order. `pixels` receives the number of pixels blended.
Image mergeImages(Image mine, Image theirs, bool theirsInFront, std::int64_t& pixels);
//! For sparse compositing: the image cut down to the bounding rectangle of its non-empty pixels.
Image trimToContent(const Image& image);

}  // namespace kdswap
