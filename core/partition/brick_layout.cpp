// Over-decomposed bricks: one small k-d tree per node.
#include "core/partition/brick_layout.h"

#include "core/util/error.h"

namespace kdswap {

BrickLayout::BrickLayout(const KdTree& nodes, int perNode, const PartitionBalance& balance) : perNode_(perNode) {
  if (perNode < 1 || perNode > 64)
    throw Error("bricks per node " + std::to_string(perNode) + ": must be from 1 to 64");
  PartitionBalance within;
  within.cost = balance.cost;  // a node's sub-bricks share its speed: balance work only
  within_.reserve(std::size_t(nodes.ranks()));
  for (int r = 0; r < nodes.ranks(); ++r)
    within_.push_back(KdTree::buildWithin(nodes.brick(r), nodes.dims(), perNode, within));
}

std::vector<int> BrickLayout::frontToBack(int node, const Camera& camera, const glm::vec3& spacing) const {
  std::vector<int> order = within_[std::size_t(node)].order(camera, spacing).frontToBack;
  for (int& b : order) b += node * perNode_;
  return order;
}

}  // namespace kdswap
