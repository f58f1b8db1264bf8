// BrickLayout: over-decomposition (issue 8). Every node's k-d brick is cut again, by a small k-d
// tree of its own, into `perNode` sub-bricks, so B = perNode x P bricks in all. Brick b's home is
// node b / perNode and a home's bricks are exactly one subtree of the partition: whoever renders
// them, their images composited in the subtree's front-to-back order give the home's partial
// image, and compositing between nodes goes on unchanged.
#pragma once

#include <vector>

#include "core/partition/kd_tree.h"

namespace kdswap {

class BrickLayout {
 public:
  BrickLayout() = default;
  //! Cuts each brick of `nodes` into `perNode` (1..64) sub-bricks; `balance` places the cuts.
  BrickLayout(const KdTree& nodes, int perNode, const PartitionBalance& balance = {});

  int nodes() const { return int(within_.size()); }
  int perNode() const { return perNode_; }
  int bricks() const { return nodes() * perNode_; }
  int home(int brick) const { return brick / perNode_; }
  const VoxelBox& box(int brick) const { return within_[std::size_t(home(brick))].brick(brick % perNode_); }
  //! `node`'s bricks, nearest first, for a camera.
  std::vector<int> frontToBack(int node, const Camera& camera, const glm::vec3& spacing) const;

 private:
  int perNode_ = 1;
  std::vector<KdTree> within_;  //!< within_[node]: the tree cutting that node's brick
};

}  // namespace kdswap
