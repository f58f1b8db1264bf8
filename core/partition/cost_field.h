// CostField: an estimate of ray-casting work over the volume, for placing k-d planes by work
// instead of by space (the load balancing the paper's conclusion asks for).
//
// The volume's cells (the cubes between voxel centres) are grouped into blocks of kBlock^3. A
// block whose voxel range is visible under the transfer function costs one unit per cell: rays
// sample it at full rate. An invisible block costs kEmptyCellCost per cell: empty-space skipping
// steps over it, but rays still cross it. Early ray termination depends on the view and is not
// modelled, so the estimate suits translucent and sparse data best.
#pragma once

#include <algorithm>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/volume/voxel_box.h"

namespace kdswap {

class TransferTable;
class VolumeSource;

class CostField {
 public:
  static constexpr int kBlock = 8;
  static constexpr double kEmptyCellCost = 0.05;

  //! Reads the volume block layer by block layer (never all of it at once) and classifies every
  //! block with `table` over the normalised `valueRange`.
  static CostField estimate(const VolumeSource& source, const TransferTable& table, glm::vec2 valueRange);
  //! estimate() of the block layers [firstLayer, endLayer) along z only; the others cost 0, so
  //! fields of processes that estimated different layers add up (blockCosts) to estimate()'s:
  //! MPI ranks each read a share of the volume.
  static CostField estimateLayers(const VolumeSource& source, const TransferTable& table, glm::vec2 valueRange,
                                  int firstLayer, int endLayer);
  //! Block layers along z (cells in blocks of kBlock^3).
  static int blockLayers(const glm::ivec3& dims) { return (std::max(dims.z - 1, 0) + (kBlock - 1)) / kBlock; }
  //! Per block, the cost of each of its cells (x fastest); fromBlockCosts gives the field back.
  const std::vector<float>& blockCosts() const { return perCell_; }
  //! The field of a volume of `dims` with these block costs (e.g. blockCosts() summed over ranks).
  //! Throws kdswap::Error when their number does not fit `dims`.
  static CostField fromBlockCosts(const glm::ivec3& dims, std::vector<float> costs);
  //! Every cell costs one unit: planes placed by this field halve space.
  static CostField uniform(const glm::ivec3& dims);

  //! cost[i]: estimated work of the cells of `box` (k-d box: continuous [lo, hi)) in the layer
  //! [lo[axis] + i, lo[axis] + i + 1) along `axis`.
  std::vector<double> layerCosts(const VoxelBox& box, int axis) const;
  //! Estimated work of the cells of a k-d box.
  double cost(const VoxelBox& box) const;
  //! Fraction of cells in visible blocks, for reports.
  double visibleFraction() const;

 private:
  glm::ivec3 cells_{0};   //!< dims - 1
  glm::ivec3 blocks_{0};  //!< ceil(cells / kBlock)
  std::vector<float> perCell_;  //!< per block: cost of each of its cells
  std::size_t index(int bx, int by, int bz) const { return (std::size_t(bz) * blocks_.y + by) * blocks_.x + bx; }
};

}  // namespace kdswap
