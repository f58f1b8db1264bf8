// Radix-k compositing (Peterka et al. 2009, "A configurable algorithm for parallel image
// compositing applications"); any P = k_0 * k_1 * ... * k_{n-1}.
//
// Round i groups the nodes into groups of k_i. With stride s_i = k_0 * ... * k_{i-1}, node r has
// digit d = (r / s_i) % k_i, and its group is the k_i nodes that differ from r in that digit only:
// base + j * s_i, j = 0 .. k_i - 1. All members of a group hold the same region (their earlier
// digits agree); it is cut into k_i parts (across y in even rounds, x in odd ones), member j keeps
// part j, sends part m to member m and composites the k_i images of its part in visibility order.
// After n rounds each node owns 1/P of the frame. With every k_i = 2 this is binary swap, node for
// node; with one round of k_0 = P it is direct-send.
//
// Ordering: a group's images must come from sibling subtrees of the k-d tree, or "in front of"
// between two members would not describe their whole images. So the partition is built from the
// radices (treeShape): the root splits into k_{n-1} children, each of those into k_{n-2}, ..., the
// leaves' parents into k_0. Leaves are ranks in depth-first order, so rank r's digit i says which
// child it lies in at depth n - 1 - i, and round i's groups are exactly the subtrees at that depth.
#include "core/composite/radix_k.h"

#include <algorithm>

#include "core/composite/image_message.h"
#include "core/composite/working_image.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

constexpr int kRadixTag = 600;  // + round

std::vector<int> primeFactors(int n) {
  std::vector<int> factors;
  for (int f = 2; f * f <= n; ++f)
    while (n % f == 0) factors.push_back(f), n /= f;
  if (n > 1) factors.push_back(n);
  return factors;
}

std::string joined(const std::vector<int>& values) {
  std::string text;
  for (int v : values) {
    if (!text.empty()) text += ',';
    text += std::to_string(v);
  }
  return text;
}

//! Default radices: P's prime factors, smallest first, multiplied into rounds of at most 8 nodes
//! (a prime above 8 is a round of its own). Few large rounds cut the image into fewer, larger
//! parts that each node blends in one pass; measured at 1024x1024, P = 8: {8} 8.7 ms, {4,2}
//! 9.0 ms, {2,2,2} 14.1 ms (the binary-swap schedule).
std::vector<int> defaultRadices(int nodes) {
  std::vector<int> rounds;
  for (int f : primeFactors(nodes)) {
    if (!rounds.empty() && rounds.back() * f <= 8)
      rounds.back() *= f;
    else
      rounds.push_back(f);
  }
  return rounds;
}

}  // namespace

std::vector<int> RadixK::radices(int nodes) const {
  if (options_.radices.empty()) return defaultRadices(nodes);
  long long product = 1;
  bool valid = true;
  for (int k : options_.radices) {
    valid = valid && k >= 2;
    product = std::min<long long>(product * std::max(k, 1), 1LL << 40);
  }
  if (!valid || product != nodes) {
    const std::vector<int> example = primeFactors(nodes);
    throw Error("radix-k: radices " + joined(options_.radices) + " for " + std::to_string(nodes) +
                " nodes: each must be >= 2 and their product must be " + std::to_string(nodes) + " (e.g. " +
                (example.empty() ? std::string("none, for 1 node") : "--radices " + joined(example)) + ")");
  }
  return options_.radices;
}

TreeShape RadixK::treeShape(int nodes) const {
  std::vector<int> fromRoot = radices(nodes);
  std::reverse(fromRoot.begin(), fromRoot.end());
  return levelShape(fromRoot);
}

Tile RadixK::compose(Image partial, const Rect& frame, const VisibilityOrder& order, Communicator& comm,
                     PhaseObserver& phases) const {
  const int me = comm.rank();
  const std::vector<int> rounds = radices(comm.size());
  WorkingImage image(std::move(partial));
  Rect region = frame;

  for (int round = 0, stride = 1; round < int(rounds.size()); stride *= rounds[std::size_t(round)], ++round) {
    const int k = rounds[std::size_t(round)];
    const int digit = (me / stride) % k, base = me - digit * stride;
    const int axis = cutAxis(round);
    phases.beginPhase("radix-" + std::to_string(k), base + ((digit + 1) % k) * stride);

    // Lend every other member its part (staggered, as in direct-send), keep ours.
    for (int step = 1; step < k; ++step) {
      const int j = (digit + step) % k;
      comm.send(base + j * stride, kRadixTag + round, image.lend(sliceOf(region, axis, j, k), options_.sparse));
    }
    const Rect keep = sliceOf(region, axis, digit, k);

    // The members' images of our part, front to back, blended in one pass.
    std::vector<int> members(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j) members[std::size_t(j)] = base + j * stride;
    std::sort(members.begin(), members.end(), [&](int a, int b) { return order.inFront(a, b); });
    std::vector<Message> received;
    std::vector<ImageView> layers;
    int self = -1;
    for (int member : members) {
      if (member == me) {
        self = int(layers.size());
        layers.push_back(image.view(keep));
      } else {
        received.push_back(comm.receive(member, kRadixTag + round));
        layers.push_back(viewOfMessage(received.back()));
      }
    }
    std::int64_t pixels = 0;
    image.composeLayers(keep, layers, self, pixels);
    region = keep;
    phases.endPhase(region, image.image(), pixels);
  }
  return image.finish(region);
}

}  // namespace kdswap
