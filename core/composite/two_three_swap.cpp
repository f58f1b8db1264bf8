// 2-3 swap compositing (Yu, Wang & Ma 2008, "Massively parallel volume rendering using 2-3 swap
// image compositing"); any P >= 1, no idle node in any round.
//
// Grouping. Binary swap idles the P - 2^n extra nodes; 2-3 swap instead merges groups of two or
// three. The nodes are the leaves of a tree in which every inner node has 2 or 3 children and
// every leaf lies at depth D = floor(log2 P), which exists because 2^D <= P <= 3^D. A subtree of
// n leaves that must still be D' levels deep is split into 2 children when n <= 2 * 3^(D'-1) and
// into 3 otherwise, as evenly as possible (every child then fits 2^(D'-1) .. 3^(D'-1) leaves).
// For P a power of two every split is binary, and 2-3 swap is binary swap. Examples (round 0's
// groups are the innermost): 5 = (3 + 2), two rounds; 7 = (3 + 2 + 2), a 3-way merge after
// them; 13 = ((3 + 2 + 2) + (3 + 3)), three rounds.
// The k-d partition is built in the same shape (treeShape), so every group is a k-d subtree.
//
// Rounds. Round t merges the subtrees at depth D - 1 - t. Before it, the n_c leaves of each child
// subtree c hold the composite of c cut into n_c equal bands of the frame (a leaf's band is the
// whole frame); after it, the n leaves of the merged subtree hold its composite cut into n bands.
// A new band overlaps at most two old bands of each child (n >= n_c), so each node exchanges
// with at most about six others per round, and every pair knows from the band arithmetic alone
// whether a message passes between them. The receiver composites the children's pieces child by
// child, front to back; the pieces of one child are disjoint, so their order does not matter.
// This is the paper's scheme with its 1D pixel ranges made bands of whole rows (or columns, when
// the frame is wider than tall).
#include "core/composite/two_three_swap.h"

#include <algorithm>
#include <bit>

#include "core/composite/image_message.h"
#include "core/composite/working_image.h"
#include "core/util/check.h"

namespace kdswap {
namespace {

constexpr int kSwapTag = 700;  // + round

//! A group: the leaves first .. first + sum(children) - 1, in children of the given leaf counts.
struct Group {
  int first = 0;
  std::vector<int> children;
  int size() const {
    int n = 0;
    for (int c : children) n += c;
    return n;
  }
};

int rounds(int nodes) { return int(std::bit_width(unsigned(nodes))) - 1; }

//! Leaf counts of the children of a subtree of `n` leaves that must be `depth` levels deep.
std::vector<int> splitGroup(int n, int depth) {
  long long threes = 1;  // 3^(depth - 1)
  for (int i = 1; i < depth; ++i) threes *= 3;
  const int k = n <= 2 * threes ? 2 : 3;
  std::vector<int> sizes;
  for (int c = 0; c < k; ++c) sizes.push_back(n / k + (c < n % k ? 1 : 0));
  return sizes;
}

//! For node `me`: its group in every round, round 0 (the deepest) first.
std::vector<Group> groupsOf(int nodes, int me) {
  std::vector<Group> path;
  int first = 0, n = nodes;
  for (int depth = rounds(nodes); depth > 0; --depth) {
    Group g{first, splitGroup(n, depth)};
    path.push_back(g);
    for (int c : g.children) {
      if (me < first + c) {
        n = c;
        break;
      }
      first += c;
    }
  }
  std::reverse(path.begin(), path.end());
  return path;
}

void emitShape(int n, int depth, TreeShape& shape) {
  if (depth == 0) {
    KDSWAP_CHECK_EQ(n, 1);
    shape.push_back(0);
    return;
  }
  const std::vector<int> sizes = splitGroup(n, depth);
  shape.push_back(int(sizes.size()));
  for (int c : sizes) emitShape(c, depth - 1, shape);
}


}  // namespace

TreeShape TwoThreeSwap::treeShape(int nodes) const {
  TreeShape shape;
  emitShape(nodes, rounds(nodes), shape);
  return shape;
}

Tile TwoThreeSwap::compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                           PhaseObserver& phases) const {
  const int me = comm.rank();
  const int axis = frame.h >= frame.w ? 1 : 0;
  WorkingImage image(std::move(partial));
  const std::vector<Group> path = groupsOf(comm.size(), me);
  Rect region = frame;

  for (int round = 0; round < int(path.size()); ++round) {
    const Group& g = path[std::size_t(round)];
    const int n = g.size(), tag = kSwapTag + round;
    // Old bands: a child of c leaves starting at leaf f holds band (leaf - f) of c.
    std::vector<int> childFirst;
    for (int c = 0, f = g.first; c < int(g.children.size()); f += g.children[std::size_t(c)], ++c)
      childFirst.push_back(f);
    const Rect mine = sliceOf(frame, axis, me - g.first, n);

    // Who sends to us, child by child front to back; the first of them is the partner shown.
    std::vector<int> children(g.children.size());
    for (int c = 0; c < int(children.size()); ++c) children[std::size_t(c)] = c;
    std::sort(children.begin(), children.end(), [&](int a, int b) {
      return order.inFront(childFirst[std::size_t(a)], childFirst[std::size_t(b)]);
    });
    std::vector<std::pair<int, Rect>> sources;  // (node, overlap of its old band with ours)
    for (int c : children)
      for (int q = 0; q < g.children[std::size_t(c)]; ++q) {
        const Rect overlap = sliceOf(frame, axis, q, g.children[std::size_t(c)]).intersect(mine);
        if (!overlap.empty()) sources.emplace_back(childFirst[std::size_t(c)] + q, overlap);
      }
    int partner = g.first + (me - g.first + 1) % n;
    for (const auto& [node, overlap] : sources)
      if (node != me) {
        partner = node;
        break;
      }
    phases.beginPhase(g.children.size() == 3 ? "3-swap" : "2-swap", partner);

    // Lend each member of the group the part of our old band that lies in its new band.
    for (int step = 1; step < n; ++step) {
      const int p = g.first + (me - g.first + step) % n;
      const Rect overlap = sliceOf(frame, axis, p - g.first, n).intersect(region);
      if (!overlap.empty()) comm.send(p, tag, image.lend(overlap, options_.sparse));
    }
    // Every part of our new band, front to back, blended in one pass.
    std::vector<Message> received;
    std::vector<ImageView> layers;
    int self = -1;
    for (const auto& [node, overlap] : sources) {
      if (node == me) {
        self = int(layers.size());
        layers.push_back(image.view(overlap));
      } else {
        received.push_back(comm.receive(node, tag));
        layers.push_back(viewOfMessage(received.back()));
      }
    }
    std::int64_t pixels = 0;
    image.composeLayers(mine, layers, self, pixels);
    region = mine;
    phases.endPhase(region, image.image(), pixels);
  }
  return image.finish(region);
}

}  // namespace kdswap
