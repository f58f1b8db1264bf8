// k-d partition and its front-to-back traversal (Ma et al. 1993, sections 3.2 and 3.4).
#include "core/partition/kd_tree.h"

#include <bit>
#include <cmath>

#include "core/camera/camera.h"
#include "core/util/check.h"
#include "core/util/error.h"

namespace kdswap {

PartitionKind parsePartition(const std::string& text) {
  if (text == "kd" || text == "kd-tree" || text == "kdtree") return PartitionKind::KdTree;
  if (text == "slab" || text == "slabs") return PartitionKind::Slab;
  throw Error("partition \"" + text + "\": expected kd or slab");
}

std::string toString(PartitionKind kind) { return kind == PartitionKind::KdTree ? "kd" : "slab"; }

KdTree KdTree::build(const glm::ivec3& dims, int ranks, PartitionKind kind, int slabAxis) {
  KDSWAP_CHECK_GE(ranks, 1);
  KdTree tree;
  tree.dims_ = dims;
  tree.ranks_ = ranks;
  tree.virtualLeaves_ = int(std::bit_floor(unsigned(ranks)));
  tree.leafOf_.assign(ranks, -1);
  tree.nodes_.reserve(std::size_t(2 * ranks));
  const VoxelBox domain{glm::ivec3(0), dims - 1};
  tree.buildNode(domain, 0, tree.virtualLeaves_, 0, kind, slabAxis);
  for (int r = 0; r < ranks; ++r) KDSWAP_CHECK_GE(tree.leafOf_[r], 0);
  return tree;
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
int KdTree::splitNode(const VoxelBox& box, int depth, PartitionKind kind, int slabAxis, int lowCount, int highCount,
                      VoxelBox& lowBox, VoxelBox& highBox) {
  lowBox = highBox = box;
  for (int attempt = 0; attempt < 3; ++attempt) {
    const int axis = kind == PartitionKind::Slab ? slabAxis : (depth + attempt) % 3;
    const int extent = box.hi[axis] - box.lo[axis];
    if (extent >= 2) {
      // Plane in proportion to the node counts, kept strictly inside so both sides are non-empty.
      const double share = double(lowCount) / double(lowCount + highCount);
      int plane = box.lo[axis] + int(std::lround(extent * share));
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

  int lowCount, highCount;
  if (leafCount == 1) {
    lowCount = highCount = 1;  // a virtual leaf holding rank j and its folded sibling j + P'
  } else {
    lowCount = ranksIn(firstLeaf, leafCount / 2);
    highCount = ranksIn(firstLeaf + leafCount / 2, leafCount - leafCount / 2);
  }
  VoxelBox lowBox, highBox;
  const int axis = box.empty() ? -1 : splitNode(box, depth, kind, slabAxis, lowCount, highCount, lowBox, highBox);
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
    // The low side is in front when the eye is below the plane (perspective) or when the rays
    // travel toward increasing coordinates (orthographic). Ties (rays parallel to the plane) never
    // cross it, so either order is right.
    bool lowFirst;
    if (camera.orthographic()) {
      lowFirst = camera.forward()[n.axis] >= 0.0f;
    } else {
      lowFirst = camera.eye()[n.axis] < float(n.plane) * spacing[n.axis];
    }
    stack.push_back(lowFirst ? n.high : n.low);
    stack.push_back(lowFirst ? n.low : n.high);
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
