// KdTree: the paper's divide step (section 3.2). The data domain [0, dims-1] (voxel coordinates)
// is split recursively by axis-aligned planes through voxel centres, alternating x, y, z (or
// always along one axis, for slabs), into one brick per node; each brick owns [lo, hi).
//
// Node counts that are not a power of two: with P' the largest power of two <= P and e = P - P',
// the tree has P' "virtual leaves"; leaf j holds rank j, and for j < e also rank j + P' as its
// sibling (IceT's folding convention). Binary-swap's extra ranks fold into their siblings, so every
// group a strategy composites is a subtree. Planes split space in proportion to the node counts
// on each side, so every node gets about the same number of voxels.
//
// Load balancing: with a PartitionBalance, every plane is placed so that the estimated work (a
// CostField) on each side is in proportion to the summed speed of the ranks on that side, instead
// of halving space; without one the tree is exactly the space-halving tree above.
//
// Other shapes (radix-k, 2-3 swap, telescoping group nodes in threes, fours or unequal halves):
// KdTree::build takes a TreeShape, and a node with k children is cut into k slabs along one axis,
// each as thick as its share of the ranks. A ray crosses parallel planes in one direction only, so
// the slabs are visited from the one holding the eye (or the near end, orthographic) outwards.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "core/partition/cost_field.h"
#include "core/volume/voxel_box.h"

namespace kdswap {

class Camera;

enum class PartitionKind { KdTree, Slab };
//! "kd" | "slab"; throws Error starting with `what` (a command-line option or a file's field).
PartitionKind parsePartition(const std::string& text, const std::string& what = "partition");
std::string toString(PartitionKind kind);

struct KdNode {
  VoxelBox box;       //!< region owned by this subtree
  int axis = -1;      //!< split axis, -1 for a leaf
  int plane = 0;      //!< split coordinate (voxel index); low child owns < plane, high child >= plane
  int low = -1, high = -1;  //!< children (indices into nodes()); -1 for a leaf and for k > 2 children
  int rank = -1;      //!< node (virtual processor) owning this leaf's brick
  std::vector<int> children;  //!< all children, in increasing coordinate along `axis` (any k)
  std::vector<int> planes;    //!< planes[i] separates children[i] and children[i + 1]
};

//! A tree shape: the number of children of every tree node in preorder, 0 for a leaf; leaves take
//! ranks 0, 1, 2, ... in that order, so every subtree holds consecutive ranks. Empty: the binary
//! tree with folded extra ranks described above. Example: {3, 0, 2, 0, 0, 0} is a root with three
//! children, of which the second has two leaves (ranks 1 and 2).
using TreeShape = std::vector<int>;
//! The shape whose level l (from the root) splits every node into arity[l] children.
TreeShape levelShape(const std::vector<int>& arity);
//! Number of leaves of a shape; throws kdswap::Error if `shape` is not one complete tree.
int shapeLeaves(const TreeShape& shape);

//! Front-to-back order of the ranks for one view. Any subtree of the k-d tree is contiguous in
//! this order, so comparing two members compares their subtrees.
struct VisibilityOrder {
  std::vector<int> frontToBack;  //!< ranks, nearest brick first
  std::vector<int> position;     //!< position[rank] = index of rank in frontToBack
  bool inFront(int a, int b) const { return position[a] < position[b]; }
};

//! How planes are placed: by space (empty), or by estimated work shared in proportion to speeds.
struct PartitionBalance {
  std::shared_ptr<const CostField> cost;  //!< work estimate; null: every cell costs the same
  std::vector<double> rankSpeeds;         //!< relative speed per rank; empty: all equal
  bool active() const { return cost != nullptr || !rankSpeeds.empty(); }
};

class KdTree {
 public:
  //! `slabAxis` is used by PartitionKind::Slab (0, 1 or 2). A non-empty `shape` must have exactly
  //! `ranks` leaves. A non-empty `balance.rankSpeeds` must have `ranks` positive entries.
  static KdTree build(const glm::ivec3& dims, int ranks, PartitionKind kind, int slabAxis = 2,
                      const TreeShape& shape = {}, const PartitionBalance& balance = {});
  //! A k-d tree over part of the volume (`domain`, a k-d box of a volume of `dims` voxels): used
  //! to cut one node's brick into sub-bricks (over-decomposition). Ranks are 0 .. ranks-1.
  static KdTree buildWithin(const VoxelBox& domain, const glm::ivec3& dims, int ranks,
                            const PartitionBalance& balance = {});

  int ranks() const { return ranks_; }
  const glm::ivec3& dims() const { return dims_; }
  const VoxelBox& brick(int rank) const { return nodes_[leafOf_[rank]].box; }
  const std::vector<KdNode>& nodes() const { return nodes_; }
  int root() const { return 0; }

  //! Visibility order for a camera; `spacing` maps voxel coordinates to world space.
  VisibilityOrder order(const Camera& camera, const glm::vec3& spacing) const;

 private:
  static KdTree buildOver(const VoxelBox& domain, const glm::ivec3& dims, int ranks, PartitionKind kind, int slabAxis,
                          const TreeShape& shape, const PartitionBalance& balance);
  int buildNode(const VoxelBox& box, int firstLeaf, int leafCount, int depth, PartitionKind kind, int slabAxis);
  int leafNode(const VoxelBox& box, int rank);
  int splitNode(const VoxelBox& box, int depth, PartitionKind kind, int slabAxis, double lowShare,
                VoxelBox& lowBox, VoxelBox& highBox);
  //! Balanced planes: cuts `box` along `axis` so each part's work matches its share of `weights`.
  std::vector<int> balancedPlanes(const VoxelBox& box, int axis, const std::vector<double>& weights) const;
  double speedOf(int rank) const { return balance_.rankSpeeds.empty() ? 1.0 : balance_.rankSpeeds[std::size_t(rank)]; }
  int buildShaped(const VoxelBox& box, const TreeShape& shape, const std::vector<int>& leaves,
                  const std::vector<std::size_t>& ends, std::size_t& cursor, int& nextRank, int depth, PartitionKind kind,
                  int slabAxis);

  glm::ivec3 dims_{0};
  int ranks_ = 0;
  int virtualLeaves_ = 0;  //!< P'
  std::vector<KdNode> nodes_;
  std::vector<int> leafOf_;  //!< rank -> node index
  PartitionBalance balance_;  //!< used while building
};

//! Slab axis for a view: the volume axis most nearly parallel to the viewing direction.
int slabAxisFor(const Camera& camera);

}  // namespace kdswap
