// Binary-swap compositing (Ma et al. 1993, section 3.4); any P by folding.
//
// Phases stride = 1, 2, 4, ...: node r pairs with r XOR stride. Both hold an image of the same
// screen region; they cut it in half (across y in even phases, x in odd ones), the node whose
// stride bit is clear keeps the first half, and each sends the other half to its partner. After
// log2(P) phases every node owns 1/P of the frame, fully composited. The pair's images come from
// two sibling subtrees of the k-d tree, so "which is in front" is decided by the tree for this
// view (VisibilityOrder), never by rank.
//
// P not a power of two: with P' = bit_floor(P), node j + P' (j < P - P') is the k-d sibling of
// node j (see kd_tree.h). In a first "fold" phase it hands its image to j and then idles.
#include "core/composite/binary_swap.h"

#include <bit>

#include "core/composite/image_message.h"
#include "core/composite/working_image.h"

namespace kdswap {
namespace {

constexpr int kFoldTag = 200;
constexpr int kSwapTag = 201;  // + phase index

//! The two halves of `region`, cut across x (axis 0) or y (axis 1). Halves may be empty when the
//! region is one pixel thick; the node keeping an empty half simply ends with an empty tile.
std::pair<Rect, Rect> splitRegion(const Rect& region, int axis) {
  Rect first = region, second = region;
  if (axis == 0) {
    first.w = region.w / 2;
    second.x = region.x + first.w;
    second.w = region.w - first.w;
  } else {
    first.h = region.h / 2;
    second.y = region.y + first.h;
    second.h = region.h - first.h;
  }
  return {first, second};
}

}  // namespace

Tile BinarySwap::compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                         PhaseObserver& phases) const {
  const int nodes = comm.size(), me = comm.rank();
  const int swapping = int(std::bit_floor(unsigned(nodes)));
  const int extras = nodes - swapping;
  WorkingImage image(std::move(partial));
  Rect region = frame;

  if (extras > 0) {  // fold the extra nodes into their k-d siblings
    std::int64_t pixels = 0;
    if (me >= swapping) {
      phases.beginPhase("fold", me - swapping);
      comm.send(me - swapping, kFoldTag, image.lend(image.rect(), options_.sparse));
      image = WorkingImage{};
      region = Rect{};
    } else if (me < extras) {
      phases.beginPhase("fold", me + swapping);
      const Message in = comm.receive(me + swapping, kFoldTag);
      image.merge(viewOfMessage(in), order.inFront(me + swapping, me), region, pixels);
    } else {
      phases.beginPhase("fold", -1);
    }
    phases.endPhase(region, image.image(), pixels);
  }

  for (int stride = 1, round = 0; stride < swapping; stride *= 2, ++round) {
    if (me >= swapping) {  // folded away: idle, but report the phase so the rows line up
      phases.beginPhase("swap", -1);
      phases.endPhase(Rect{}, Image{}, 0);
      continue;
    }
    const int partner = me ^ stride;
    phases.beginPhase("swap", partner);
    const auto [first, second] = splitRegion(region, cutAxis(round));
    const bool keepFirst = (me & stride) == 0;
    const Rect keep = keepFirst ? first : second;
    const Rect give = keepFirst ? second : first;
    // The given half is lent, not copied; the partner's half lands on the kept one in place.
    // Pixels outside `region` are stale from here on (cut away once, at the end).
    comm.send(partner, kSwapTag + round, image.lend(give, options_.sparse));
    const Message in = comm.receive(partner, kSwapTag + round);
    std::int64_t pixels = 0;
    image.merge(viewOfMessage(in), order.inFront(partner, me), keep, pixels);
    region = keep;
    phases.endPhase(region, image.image(), pixels);
  }
  return image.finish(region);
}

}  // namespace kdswap
