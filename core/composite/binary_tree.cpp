// Binary-tree compositing (the baseline of Ma et al. 1993, section 3.4); any P by folding.
// Level by level, node r with stride bit set sends its whole image to r - stride and idles, so
// after log2(P') levels node 0 holds the frame. Folding of the extra nodes is as in binary swap:
// node j + P' is the k-d sibling of node j, so each merged pair is a subtree.
#include "core/composite/binary_tree.h"

#include <bit>

#include "core/composite/image_message.h"

namespace kdswap {
namespace {

constexpr int kFoldTag = 300;
constexpr int kLevelTag = 301;  // + level

}  // namespace

Tile BinaryTree::compose(Image image, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                         PhaseObserver& phases) const {
  const int nodes = comm.size(), me = comm.rank();
  const int pairs = int(std::bit_floor(unsigned(nodes)));
  const int extras = nodes - pairs;
  auto prepare = [&](const Image& part) { return options_.sparse ? trimToContent(part) : part; };
  bool active = true;

  if (extras > 0) {
    std::int64_t pixels = 0;
    if (me >= pairs) {
      phases.beginPhase("fold", me - pairs);
      comm.send(me - pairs, kFoldTag, imageToMessage(prepare(image)));
      image = Image{};
      active = false;
    } else if (me < extras) {
      phases.beginPhase("fold", me + pairs);
      Message in = comm.receive(me + pairs, kFoldTag);
      image = mergeImages(std::move(image), imageFromMessage(in), order.inFront(me + pairs, me), pixels);
    } else {
      phases.beginPhase("fold", -1);
    }
    phases.endPhase(active ? frame : Rect{}, image, pixels);
  }

  for (int stride = 1, level = 0; stride < pairs; stride *= 2, ++level) {
    std::int64_t pixels = 0;
    if (!active) {
      phases.beginPhase("merge", -1);
    } else if (me & stride) {
      phases.beginPhase("merge", me - stride);
      comm.send(me - stride, kLevelTag + level, imageToMessage(prepare(image)));
      image = Image{};
      active = false;
    } else {
      phases.beginPhase("merge", me + stride);
      Message in = comm.receive(me + stride, kLevelTag + level);
      image = mergeImages(std::move(image), imageFromMessage(in), order.inFront(me + stride, me), pixels);
    }
    phases.endPhase(active ? frame : Rect{}, image, pixels);
  }
  if (!active) return Tile{};
  return Tile::owning(frame, std::move(image));
}

}  // namespace kdswap
