// Image <-> message, and the pairwise merge every strategy uses.
#include "core/composite/image_message.h"

#include "core/util/error.h"

namespace kdswap {

Message imageToMessage(Image image) {
  Message m;
  const Rect r = image.rect();
  m.header = {r.x, r.y, r.w, r.h};
  m.payload = std::move(image.values());
  return m;
}

Image imageFromMessage(Message& message) {
  if (message.header.size() < 4) throw Error("image message from node " + std::to_string(message.source) + ": header too short");
  const Rect r{int(message.header[0]), int(message.header[1]), int(message.header[2]), int(message.header[3])};
  if (message.payload.size() != std::size_t(r.area()) * 4)
    throw Error("image message from node " + std::to_string(message.source) + ": " +
                std::to_string(message.payload.size()) + " values for a " + std::to_string(r.w) + "x" +
                std::to_string(r.h) + " rectangle");
  return Image(r, std::move(message.payload));
}

Image mergeImages(Image mine, Image theirs, bool theirsInFront, std::int64_t& pixels) {
  if (theirs.empty()) return mine;
  if (mine.empty()) return theirs;
  const Rect both = mine.rect().unite(theirs.rect());
  if (both == mine.rect()) {
    pixels += compositeInto(mine, theirs, theirsInFront);
    return mine;
  }
  if (both == theirs.rect()) {
    pixels += compositeInto(theirs, mine, !theirsInFront);
    return theirs;
  }
  Image merged = mine.extendedTo(both);
  pixels += compositeInto(merged, theirs, theirsInFront);
  return merged;
}

Image trimToContent(const Image& image) {
  const Rect content = image.opaqueBounds();
  if (content == image.rect()) return image;
  return image.crop(content);
}

}  // namespace kdswap
