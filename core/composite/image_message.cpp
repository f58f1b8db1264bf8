// Image <-> message, and the pairwise merge every strategy uses.
#include "core/composite/image_message.h"

#include "core/util/check.h"
#include "core/util/error.h"

namespace kdswap {

Message imageToMessage(Image image) {
  Message m;
  const Rect r = image.rect();
  m.header = {r.x, r.y, r.w, r.h};
  m.payload = std::move(image.values());
  return m;
}

Message lendPixels(const ImageView& view, std::shared_ptr<const void> owner) {
  Message m;
  const Rect r = view.rect;
  m.header = {r.x, r.y, r.w, r.h};
  if (r.empty()) return m;
  m.loan = FloatLoan{std::move(owner), &view.first->r, r.h, std::int64_t(r.w) * 4, view.stride * 4};
  return m;
}

ImageView viewOfMessage(const Message& message) {
  auto fail = [&](const std::string& what) {
    return Error("image message from node " + std::to_string(message.source) + ": " + what);
  };
  if (message.header.size() < 4) throw fail("header too short");
  const auto& h = message.header;
  if (h[2] < 0 || h[3] < 0 || h[2] > (1 << 24) || h[3] > (1 << 24)) throw fail("impossible rectangle size");
  const Rect r{int(h[0]), int(h[1]), int(h[2]), int(h[3])};
  const std::int64_t values = r.area() * 4;
  if (message.loan.count() > 0) {
    if (!message.payload.empty() || message.loan.rows != r.h || message.loan.rowFloats != std::int64_t(r.w) * 4)
      throw fail("lent pixels do not match a " + std::to_string(r.w) + "x" + std::to_string(r.h) + " rectangle");
    return ImageView{r, reinterpret_cast<const Rgba*>(message.loan.first), message.loan.strideFloats / 4};
  }
  if (std::int64_t(message.payload.size()) != values)
    throw fail(std::to_string(message.payload.size()) + " values for a " + std::to_string(r.w) + "x" +
               std::to_string(r.h) + " rectangle");
  if (r.empty()) return ImageView{};
  return ImageView{r, reinterpret_cast<const Rgba*>(message.payload.data()), r.w};
}

Image imageFromMessage(Message& message) {
  const ImageView view = viewOfMessage(message);
  if (message.loan.count() > 0) return Image(view);
  return Image(view.rect, std::move(message.payload));
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
  pixels += theirs.rect().area();
  return theirsInFront ? overOf(theirs.view(), mine.view()) : overOf(mine.view(), theirs.view());
}

Image trimToContent(Image image) {
  const Rect content = image.opaqueBounds();
  return trimTo(std::move(image), content);
}

Image trimTo(Image image, const Rect& content) {
  KDSWAP_CHECK(content == image.opaqueBounds());
  if (content == image.rect()) return image;
  return image.crop(content);
}

}  // namespace kdswap
