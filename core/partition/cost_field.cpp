// Work estimate per block of cells, and its sums over k-d boxes.
#include "core/partition/cost_field.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "core/transfer/transfer_function.h"
#include "core/util/error.h"
#include "core/volume/volume_source.h"

namespace kdswap {

CostField CostField::uniform(const glm::ivec3& dims) {
  CostField f;
  f.cells_ = glm::max(dims - 1, glm::ivec3(0));
  f.blocks_ = (f.cells_ + (kBlock - 1)) / kBlock;
  f.perCell_.assign(std::size_t(f.blocks_.x) * f.blocks_.y * f.blocks_.z, 1.0f);
  return f;
}

CostField CostField::estimate(const VolumeSource& source, const TransferTable& table, glm::vec2 valueRange) {
  return estimateLayers(source, table, valueRange, 0, blockLayers(source.info().dims));
}

CostField CostField::fromBlockCosts(const glm::ivec3& dims, std::vector<float> costs) {
  CostField f = uniform(dims);
  if (costs.size() != f.perCell_.size())
    throw Error("cost field: " + std::to_string(costs.size()) + " block costs for " + std::to_string(f.perCell_.size()) +
                " blocks");
  f.perCell_ = std::move(costs);
  return f;
}

CostField CostField::estimateLayers(const VolumeSource& source, const TransferTable& table, glm::vec2 valueRange,
                                    int firstLayer, int endLayer) {
  const glm::ivec3 dims = source.info().dims;
  CostField f = uniform(dims);
  std::fill(f.perCell_.begin(), f.perCell_.end(), 0.0f);
  const float scale = valueRange.y > valueRange.x ? 1.0f / (valueRange.y - valueRange.x) : 0.0f;
  std::vector<float> layer;
  for (int bz = std::max(firstLayer, 0); bz < std::min(endLayer, f.blocks_.z); ++bz) {
    // A block of cells spans kBlock + 1 voxel layers (its cells' corners).
    const int z0 = bz * kBlock, z1 = std::min(z0 + kBlock + 1, dims.z);
    const VoxelBox box{glm::ivec3(0, 0, z0), glm::ivec3(dims.x, dims.y, z1)};
    layer.resize(std::size_t(box.count()));
    source.read(box, layer.data());
    for (int by = 0; by < f.blocks_.y; ++by)
      for (int bx = 0; bx < f.blocks_.x; ++bx) {
        float lo = 1e30f, hi = -1e30f;
        const int y1 = std::min(by * kBlock + kBlock + 1, dims.y), x1 = std::min(bx * kBlock + kBlock + 1, dims.x);
        for (int z = 0; z < z1 - z0; ++z)
          for (int y = by * kBlock; y < y1; ++y) {
            const float* row = layer.data() + (std::size_t(z) * dims.y + y) * dims.x;
            for (int x = bx * kBlock; x < x1; ++x) lo = std::min(lo, row[x]), hi = std::max(hi, row[x]);
          }
        const bool visible = table.anyVisible((lo - valueRange.x) * scale, (hi - valueRange.x) * scale);
        f.perCell_[f.index(bx, by, bz)] = visible ? 1.0f : float(kEmptyCellCost);
      }
  }
  return f;
}

std::vector<double> CostField::layerCosts(const VoxelBox& box, int axis) const {
  const glm::ivec3 lo = glm::clamp(box.lo, glm::ivec3(0), cells_), hi = glm::clamp(box.hi, lo, cells_);
  std::vector<double> out(std::size_t(std::max(0, box.hi[axis] - box.lo[axis])), 0.0);
  if (glm::any(glm::lessThanEqual(hi, lo))) return out;
  // Cells overlapping a block on the two other axes, per block row: sum block by block, then
  // spread each block's per-layer cost over the layers it covers.
  const glm::ivec3 blo = lo / kBlock, bhi = (hi + (kBlock - 1)) / kBlock;
  auto overlap = [&](int a, int b) {
    return std::min(hi[a], (b + 1) * kBlock) - std::max(lo[a], b * kBlock);
  };
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  for (int ba = blo[axis]; ba < bhi[axis]; ++ba) {
    double perLayer = 0.0;  // cost of one layer of cells within this block slice of the box
    for (int bu = blo[u]; bu < bhi[u]; ++bu)
      for (int bv = blo[v]; bv < bhi[v]; ++bv) {
        glm::ivec3 b;
        b[axis] = ba, b[u] = bu, b[v] = bv;
        perLayer += double(perCell_[index(b.x, b.y, b.z)]) * overlap(u, bu) * overlap(v, bv);
      }
    const int l0 = std::max(lo[axis], ba * kBlock), l1 = std::min(hi[axis], (ba + 1) * kBlock);
    for (int l = l0; l < l1; ++l) out[std::size_t(l - box.lo[axis])] = perLayer;
  }
  return out;
}

double CostField::cost(const VoxelBox& box) const {
  double sum = 0.0;
  for (double c : layerCosts(box, 0)) sum += c;
  return sum;
}

double CostField::visibleFraction() const {
  if (perCell_.empty()) return 0.0;
  std::size_t visible = 0;
  for (float c : perCell_) visible += c == 1.0f;
  return double(visible) / double(perCell_.size());
}

}  // namespace kdswap
