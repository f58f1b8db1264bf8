// Telescoping binary swap (Moreland, Kendall, Peterka & Huang 2011, "An image compositing
// solution at scale", section 4; IceT's bswap.c); any P, no node folded away before compositing.
//
// Groups. P is split into its powers of two, largest first: 13 = 8 + 4 + 1 gives groups of ranks
// 0-7, 8-11 and 12. Each group runs plain binary swap on its own (node r pairs with r XOR stride
// inside the group, halves cut across x, then y, ...), so a group of 2^m nodes ends with its
// composite cut into 2^m pieces after m rounds, while the larger groups are still swapping.
//
// Telescoping. Then, smallest first, each group sends its result into the next larger group: the
// pieces of the small group (2^m) are the pieces of the larger group (2^M) after its first m
// rounds, because both cut the same frame by the same rule, so larger-group node u lies inside
// the piece of small-group node u mod 2^m and receives from it exactly the pixels of u's final
// piece. The small group's result already holds every smaller group's, so after the last step the
// largest group holds the whole frame, 1/2^M per node, and the other nodes end with empty tiles.
//
// Ordering: the partition is built so that each group is a complete binary subtree and sits beside
// the subtree of all smaller groups (13: root = {8, {4, 1}}). Each telescoping step then merges two
// sibling subtrees, and "which is in front" is decided by the tree for this view.
#include "core/composite/telescoping.h"

#include <bit>

#include "core/composite/image_message.h"
#include "core/composite/working_image.h"

namespace kdswap {
namespace {

constexpr int kSwapTag = 800;       // + round
constexpr int kTelescopeTag = 850;  // + step

struct PowerGroup {
  int first = 0, size = 1;
  int rounds() const { return std::countr_zero(unsigned(size)); }
};

//! The power-of-two groups of `nodes`, largest first.
std::vector<PowerGroup> groupsOf(int nodes) {
  std::vector<PowerGroup> groups;
  int first = 0;
  for (int bit = 30; bit >= 0; --bit)
    if (nodes & (1 << bit)) {
      groups.push_back({first, 1 << bit});
      first += 1 << bit;
    }
  return groups;
}

//! The halves of `region` across x (axis 0) or y (axis 1), as in binary_swap.cpp.
Rect halfOf(const Rect& region, int axis, bool second) {
  Rect r = region;
  if (axis == 0) {
    r.w = region.w / 2;
    if (second) r.x += r.w, r.w = region.w - r.w;
  } else {
    r.h = region.h / 2;
    if (second) r.y += r.h, r.h = region.h - r.h;
  }
  return r;
}

//! The piece of `frame` a node with index `local` in its group owns after `rounds` swap rounds.
Rect pieceAfter(const Rect& frame, int local, int rounds) {
  Rect region = frame;
  for (int round = 0; round < rounds; ++round) region = halfOf(region, cutAxis(round), (local >> round) & 1);
  return region;
}

void emitComplete(int leaves, TreeShape& shape) {
  if (leaves == 1) {
    shape.push_back(0);
    return;
  }
  shape.push_back(2);
  emitComplete(leaves / 2, shape);
  emitComplete(leaves / 2, shape);
}

}  // namespace

TreeShape Telescoping::treeShape(int nodes) const {
  const std::vector<PowerGroup> groups = groupsOf(nodes);
  TreeShape shape;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (g + 1 < groups.size()) shape.push_back(2);  // this group beside the smaller ones
    emitComplete(groups[g].size, shape);
  }
  return shape;
}

Tile Telescoping::compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                          PhaseObserver& phases) const {
  const int me = comm.rank();
  const std::vector<PowerGroup> groups = groupsOf(comm.size());
  int mine = 0;
  while (me >= groups[std::size_t(mine)].first + groups[std::size_t(mine)].size) ++mine;
  const PowerGroup& group = groups[std::size_t(mine)];
  const int local = me - group.first;
  WorkingImage image(std::move(partial));
  Rect region = frame;

  // Binary swap inside each group; smaller groups finish early and report idle rounds.
  for (int round = 0; round < groups[0].rounds(); ++round) {
    if (round >= group.rounds()) {
      phases.beginPhase("swap", -1);
      phases.endPhase(region, image.image(), 0);
      continue;
    }
    const int partner = group.first + (local ^ (1 << round));
    phases.beginPhase("swap", partner);
    const bool second = (local >> round) & 1;
    const Rect keep = halfOf(region, cutAxis(round), second), give = halfOf(region, cutAxis(round), !second);
    // As in binary swap: the given half is lent, the partner's lands on the kept one in place,
    // and pixels outside `region` are stale from here on.
    comm.send(partner, kSwapTag + round, image.lend(give, options_.sparse));
    const Message in = comm.receive(partner, kSwapTag + round);
    std::int64_t pixels = 0;
    image.merge(viewOfMessage(in), order.inFront(partner, me), keep, pixels);
    region = keep;
    phases.endPhase(region, image.image(), pixels);
  }

  // Telescoping, smallest group first: step s sends group G-1-s into group G-2-s.
  const int count = int(groups.size());
  for (int step = 0; step + 1 < count; ++step) {
    const PowerGroup& from = groups[std::size_t(count - 1 - step)];
    const PowerGroup& into = groups[std::size_t(count - 2 - step)];
    std::int64_t pixels = 0;
    if (&from == &group) {
      // Node `local` of the sender covers receivers local, local + 2^m, local + 2 * 2^m, ...
      phases.beginPhase("telescope", into.first + local);
      for (int u = local; u < into.size; u += from.size)
        comm.send(into.first + u, kTelescopeTag + step,
                  image.lend(pieceAfter(frame, u, into.rounds()).intersect(region), options_.sparse));
      image = WorkingImage{};
      region = Rect{};
    } else if (&into == &group) {
      const int sender = from.first + local % from.size;
      phases.beginPhase("telescope", sender);
      const Message in = comm.receive(sender, kTelescopeTag + step);
      image.merge(viewOfMessage(in), order.inFront(sender, me), region, pixels);
    } else {
      phases.beginPhase("telescope", -1);
    }
    phases.endPhase(region, image.image(), pixels);
  }
  return image.finish(region);
}

}  // namespace kdswap
