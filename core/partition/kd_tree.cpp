// k-d partition and its front-to-back traversal (Ma et al. 1993, sections 3.2 and 3.4).
#include "core/partition/kd_tree.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <functional>

#include "core/camera/camera.h"
#include "core/util/check.h"
#include "core/util/error.h"

namespace kdswap {

PartitionKind parsePartition(const std::string& text, const std::string& what) {
  if (text == "kd" || text == "kd-tree" || text == "kdtree") return PartitionKind::KdTree;
  if (text == "slab" || text == "slabs") return PartitionKind::Slab;
  throw Error(what + " \"" + text + "\": expected kd or slab");
}

std::string toString(PartitionKind kind) { return kind == PartitionKind::KdTree ? "kd" : "slab"; }

namespace {

std::string describeShape(const TreeShape& shape) {
  std::string text;
  for (std::size_t i = 0; i < shape.size() && i < 16; ++i) {
    if (i) text += ',';
    text += std::to_string(shape[i]);
  }
  return text + (shape.size() > 16 ? ",..." : "");
}

//! For every entry of a preorder shape: the leaves below it and the index just past its subtree.
//! Throws if the shape is not exactly one complete tree.
void measureShape(const TreeShape& shape, std::vector<int>& leaves, std::vector<std::size_t>& ends) {
  leaves.assign(shape.size(), 0);
  ends.assign(shape.size(), 0);
  const auto bad = [&](const std::string& why) { return Error("tree shape {" + describeShape(shape) + "}: " + why); };
  std::function<std::size_t(std::size_t)> measure = [&](std::size_t at) -> std::size_t {
    if (at >= shape.size()) throw bad("ends inside a node's children");
    if (shape[at] < 0) throw bad("a negative number of children");
    std::size_t next = at + 1;
    leaves[at] = shape[at] == 0 ? 1 : 0;
    for (int c = 0; c < shape[at]; ++c) {
      const std::size_t child = next;
      next = measure(child);
      leaves[at] += leaves[child];
    }
    ends[at] = next;
    return next;
  };
  if (shape.empty()) throw bad("empty");
  if (measure(0) != shape.size()) throw bad("entries left over after the root's subtree");
}

//! Cuts `box` into one slab per entry of `counts` along one axis, each as thick as its share of
//! the ranks; fills `planes` (non-decreasing) and returns the axis. When the box is at least one
//! cell per slab thick every slab gets a cell; otherwise the first slabs get one cell each and the
//! rest are empty (as the binary split leaves its high side empty).
int cutSlabs(const VoxelBox& box, int depth, PartitionKind kind, int slabAxis, const std::vector<int>& counts,
             std::vector<int>& planes) {
  const int k = int(counts.size());
  int axis = kind == PartitionKind::Slab ? slabAxis : depth % 3;
  if (kind == PartitionKind::KdTree) {
    int thickest = axis;
    for (int attempt = 0; attempt < 3; ++attempt) {
      const int a = (depth + attempt) % 3;
      if (box.hi[a] - box.lo[a] >= k) {
        thickest = a;
        break;
      }
      if (box.hi[a] - box.lo[a] > box.hi[thickest] - box.lo[thickest]) thickest = a;
    }
    axis = thickest;
  }
  const int lo = box.lo[axis], hi = std::max(box.lo[axis], box.hi[axis]), extent = hi - lo;
  int total = 0;
  for (int c : counts) total += c;
  planes.clear();
  int before = 0, previous = lo;
  for (int j = 1; j < k; ++j) {
    before += counts[std::size_t(j - 1)];
    int plane = lo + int(std::lround(double(extent) * before / total));
    plane = extent >= k ? std::clamp(plane, previous + 1, hi - (k - j)) : std::min(previous + 1, hi);
    planes.push_back(plane);
    previous = plane;
  }
  return axis;
}

}  // namespace

TreeShape levelShape(const std::vector<int>& arity) {
  TreeShape shape;
  std::function<void(std::size_t)> emit = [&](std::size_t level) {
    if (level == arity.size()) {
      shape.push_back(0);
      return;
    }
    shape.push_back(arity[level]);
    for (int c = 0; c < arity[level]; ++c) emit(level + 1);
  };
  emit(0);
  return shape;
}

int shapeLeaves(const TreeShape& shape) {
  std::vector<int> leaves;
  std::vector<std::size_t> ends;
  measureShape(shape, leaves, ends);
  return leaves[0];
}

KdTree KdTree::build(const glm::ivec3& dims, int ranks, PartitionKind kind, int slabAxis, const TreeShape& shape,
                     const PartitionBalance& balance) {
  return buildOver(VoxelBox{glm::ivec3(0), dims - 1}, dims, ranks, kind, slabAxis, shape, balance);
}

KdTree KdTree::buildWithin(const VoxelBox& domain, const glm::ivec3& dims, int ranks, const PartitionBalance& balance) {
  return buildOver(domain, dims, ranks, PartitionKind::KdTree, 2, {}, balance);
}

KdTree KdTree::buildOver(const VoxelBox& domain, const glm::ivec3& dims, int ranks, PartitionKind kind, int slabAxis,
                         const TreeShape& shape, const PartitionBalance& balance) {
  KDSWAP_CHECK_GE(ranks, 1);
  if (!balance.rankSpeeds.empty()) {
    if (int(balance.rankSpeeds.size()) != ranks)
      throw Error(std::to_string(balance.rankSpeeds.size()) + " node speeds for " + std::to_string(ranks) + " nodes");
    for (double s : balance.rankSpeeds)
      if (!(s > 0.0 && s < 1e6)) throw Error("node speed " + std::to_string(s) + ": must be positive");
  }
  KdTree tree;
  tree.balance_ = balance;
  if (balance.active() && !tree.balance_.cost) tree.balance_.cost = std::make_shared<CostField>(CostField::uniform(dims));
  tree.dims_ = dims;
  tree.ranks_ = ranks;
  tree.virtualLeaves_ = int(std::bit_floor(unsigned(ranks)));
  tree.leafOf_.assign(ranks, -1);
  tree.nodes_.reserve(std::size_t(2 * ranks));
  if (shape.empty()) {
    tree.buildNode(domain, 0, tree.virtualLeaves_, 0, kind, slabAxis);
  } else {
    std::vector<int> leaves;
    std::vector<std::size_t> ends;
    measureShape(shape, leaves, ends);
    if (leaves[0] != ranks)
      throw Error("tree shape {" + describeShape(shape) + "}: " + std::to_string(leaves[0]) + " leaves for " +
                  std::to_string(ranks) + " nodes");
    std::size_t cursor = 0;
    int nextRank = 0;
    tree.buildShaped(domain, shape, leaves, ends, cursor, nextRank, 0, kind, slabAxis);
  }
  for (int r = 0; r < ranks; ++r) KDSWAP_CHECK_GE(tree.leafOf_[r], 0);
  tree.balance_ = {};  // only needed while building; the tree stays cheap to copy
  return tree;
}

// One node of a shaped tree: `cursor` is its preorder index on entry and just past its subtree
// on return. Leaves take ranks in preorder, so every subtree holds consecutive ranks.
int KdTree::buildShaped(const VoxelBox& box, const TreeShape& shape, const std::vector<int>& leaves,
                        const std::vector<std::size_t>& ends, std::size_t& cursor, int& nextRank, int depth,
                        PartitionKind kind, int slabAxis) {
  const int k = shape[cursor++];
  if (k == 0) return leafNode(box, nextRank++);
  const int index = int(nodes_.size());
  nodes_.emplace_back();
  nodes_[index].box = box;

  // Leaf counts of the children; each child's subtree ends where the next child starts.
  std::vector<int> counts;
  for (std::size_t c = 0, child = cursor; c < std::size_t(k); ++c, child = ends[child]) counts.push_back(leaves[child]);
  std::vector<int> planes;
  const int axis = cutSlabs(box, depth, kind, slabAxis, counts, planes);
  if (balance_.active() && box.hi[axis] - box.lo[axis] >= k) {
    std::vector<double> weights;
    for (int c = 0, rank = nextRank; c < k; rank += counts[std::size_t(c)], ++c) {
      double w = 0.0;
      for (int r = rank; r < rank + counts[std::size_t(c)]; ++r) w += speedOf(r);
      weights.push_back(w);
    }
    planes = balancedPlanes(box, axis, weights);
  }

  std::vector<int> children;
  for (int c = 0; c < k; ++c) {
    VoxelBox slab = box;
    if (c > 0) slab.lo[axis] = planes[std::size_t(c - 1)];
    if (c + 1 < k) slab.hi[axis] = planes[std::size_t(c)];
    children.push_back(buildShaped(slab, shape, leaves, ends, cursor, nextRank, depth + 1, kind, slabAxis));
  }
  KdNode& n = nodes_[index];
  n.axis = axis;
  if (k == 2) {
    n.plane = planes[0];
    n.low = children[0];
    n.high = children[1];
  }
  n.children = std::move(children);
  n.planes = std::move(planes);
  return index;
}

int KdTree::leafNode(const VoxelBox& box, int rank) {
  KdNode n;
  n.box = box;
  n.rank = rank;
  nodes_.push_back(n);
  leafOf_[rank] = int(nodes_.size()) - 1;
  return int(nodes_.size()) - 1;
}

// Chooses the axis and plane for a node with `lowCount` and `highCount` ranks on each side.
// Returns the axis, or -1 when the box is too thin to cut anywhere (the high side is then empty).
std::vector<int> KdTree::balancedPlanes(const VoxelBox& box, int axis, const std::vector<double>& weights) const {
  const int k = int(weights.size()), lo = box.lo[axis], hi = box.hi[axis];
  const std::vector<double> layers = balance_.cost->layerCosts(box, axis);
  double totalWork = 0.0, totalWeight = 0.0;
  for (double c : layers) totalWork += c;
  for (double w : weights) totalWeight += w;
  std::vector<int> planes;
  double target = 0.0, cumulative = 0.0;
  int layer = 0, previous = lo;
  for (int j = 1; j < k; ++j) {
    target += totalWork * weights[std::size_t(j - 1)] / totalWeight;
    // Advance while taking the next layer brings the running work closer to the target.
    while (layer < int(layers.size()) &&
           std::fabs(cumulative + layers[std::size_t(layer)] - target) <= std::fabs(cumulative - target)) {
      cumulative += layers[std::size_t(layer)];
      ++layer;
    }
    // Every part keeps at least one layer of cells.
    const int plane = std::clamp(lo + layer, previous + 1, hi - (k - j));
    for (; layer < plane - lo; ++layer) cumulative += layers[std::size_t(layer)];
    for (; layer > plane - lo; --layer) cumulative -= layers[std::size_t(layer - 1)];
    planes.push_back(plane);
    previous = plane;
  }
  return planes;
}

int KdTree::splitNode(const VoxelBox& box, int depth, PartitionKind kind, int slabAxis, double lowShare,
                      VoxelBox& lowBox, VoxelBox& highBox) {
  lowBox = highBox = box;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int axis = kind == PartitionKind::Slab ? slabAxis : (depth + attempt) % 3;
    const int extent = box.hi[axis] - box.lo[axis];
    if (extent >= 2) {
      // Plane in proportion to the node counts (or, balanced, to the work), kept strictly inside
      // so both sides are non-empty.
      int plane = box.lo[axis] + int(std::lround(extent * lowShare));
      if (balance_.active()) plane = balancedPlanes(box, axis, {lowShare, 1.0 - lowShare})[0];
      plane = std::clamp(plane, box.lo[axis] + 1, box.hi[axis] - 1);
      lowBox.hi[axis] = plane;
      highBox.lo[axis] = plane;
      return axis;
    }
    if (kind == PartitionKind::Slab) break;
  }
  // Too thin to cut: the low side keeps everything and the high side's bricks are empty.
  highBox.lo = highBox.hi;
  return -1;
}

int KdTree::buildNode(const VoxelBox& box, int firstLeaf, int leafCount, int depth, PartitionKind kind, int slabAxis) {
  const int extras = ranks_ - virtualLeaves_;
  auto ranksIn = [&](int first, int count) { return count + std::clamp(extras - first, 0, count); };
  const int index = int(nodes_.size());
  if (leafCount == 1 && firstLeaf >= extras) return leafNode(box, firstLeaf);
  nodes_.emplace_back();
  nodes_[index].box = box;

  // Summed speed of the ranks below virtual leaves [first, first + count) (each node counts 1
  // when unbalanced, so the share is the node-count share).
  auto weightOf = [&](int first, int count) {
    if (!balance_.active()) return double(ranksIn(first, count));
    double w = 0.0;
    for (int j = first; j < first + count; ++j) w += speedOf(j) + (j < extras ? speedOf(j + virtualLeaves_) : 0.0);
    return w;
  };
  double lowWeight, highWeight;
  if (leafCount == 1) {
    // A virtual leaf holding rank j and its folded sibling j + P'.
    lowWeight = balance_.active() ? speedOf(firstLeaf) : 1.0;
    highWeight = balance_.active() ? speedOf(firstLeaf + virtualLeaves_) : 1.0;
  } else {
    lowWeight = weightOf(firstLeaf, leafCount / 2);
    highWeight = weightOf(firstLeaf + leafCount / 2, leafCount - leafCount / 2);
  }
  VoxelBox lowBox, highBox;
  const int axis = box.empty() ? -1
                               : splitNode(box, depth, kind, slabAxis, lowWeight / (lowWeight + highWeight), lowBox,
                                           highBox);
  if (box.empty()) lowBox = highBox = box;
  nodes_[index].axis = axis < 0 ? 0 : axis;
  nodes_[index].plane = axis < 0 ? box.hi[0] : lowBox.hi[axis];

  int low, high;
  if (leafCount == 1) {
    low = leafNode(lowBox, firstLeaf);
    high = leafNode(highBox, firstLeaf + virtualLeaves_);
  } else {
    low = buildNode(lowBox, firstLeaf, leafCount / 2, depth + 1, kind, slabAxis);
    high = buildNode(highBox, firstLeaf + leafCount / 2, leafCount - leafCount / 2, depth + 1, kind, slabAxis);
  }
  nodes_[index].low = low;
  nodes_[index].high = high;
  nodes_[index].children = {low, high};
  nodes_[index].planes = {nodes_[index].plane};
  return index;
}

VisibilityOrder KdTree::order(const Camera& camera, const glm::vec3& spacing) const {
  VisibilityOrder result;
  result.frontToBack.reserve(std::size_t(ranks_));
  // Iterative depth-first traversal, nearer child first.
  std::vector<int> stack{root()};
  while (!stack.empty()) {
    const KdNode& n = nodes_[stack.back()];
    stack.pop_back();
    if (n.rank >= 0) {
      result.frontToBack.push_back(n.rank);
      continue;
    }
    // The slab holding the eye comes first (perspective), then the slabs on either side walking
    // away from it: a ray crosses the parallel planes in one direction only, so any interleaving of
    // the two sides is valid. Orthographic: the first slab is the one the rays enter, the low end
    // when they travel toward increasing coordinates. Ties (rays parallel to the planes) never
    // cross them, so either order is right. For two children this is the low side first when the
    // eye is below the plane.
    const int k = int(n.children.size());
    int first;
    if (camera.orthographic()) {
      first = camera.forward()[n.axis] >= 0.0f ? 0 : k - 1;
    } else {
      first = 0;
      while (first < k - 1 && camera.eye()[n.axis] >= float(n.planes[std::size_t(first)]) * spacing[n.axis]) ++first;
    }
    // Pushed in reverse: upper side farthest first, then the lower side, then the eye's slab on top.
    for (int c = k - 1; c > first; --c) stack.push_back(n.children[std::size_t(c)]);
    for (int c = 0; c < first; ++c) stack.push_back(n.children[std::size_t(c)]);
    stack.push_back(n.children[std::size_t(first)]);
  }
  result.position.assign(std::size_t(ranks_), -1);
  for (int i = 0; i < ranks_; ++i) result.position[result.frontToBack[i]] = i;
  return result;
}

int slabAxisFor(const Camera& camera) {
  const glm::vec3 f = camera.forward();
  const glm::vec3 a(std::fabs(f.x), std::fabs(f.y), std::fabs(f.z));
  return a.x >= a.y && a.x >= a.z ? 0 : (a.y >= a.z ? 1 : 2);
}

}  // namespace kdswap
