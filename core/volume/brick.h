// Brick: one node's private subvolume (paper section 3.2). It owns the sample positions in the
// continuous box [owned.lo, owned.hi) of voxel coordinates. It receives the voxels it needs for
// them: the owned voxels, the one replicated boundary layer that trilinear interpolation reaches
// across a cut, and one more ghost layer so its central-difference gradients equal the whole
// volume's. Gradients are precomputed per voxel (memory for time, as the paper does); once they
// are, the outer ghost layer is dropped, or kept as plain values when the brick may be shipped on.
// Voxels are kept as floats or in the compact 16-bit format (voxel_storage.h); a compact brick
// quantises the values it receives first, so its gradients, cell ranges and shipped values all
// come from the values it stores.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/util/huge_page_allocator.h"
#include "core/volume/cell_range_codes.h"
#include "core/volume/voxel_box.h"
#include "core/volume/voxel_storage.h"

namespace kdswap {

//! One stored voxel: scalar value and its central-difference gradient (per world unit).
struct Voxel {
  float value;
  glm::vec3 gradient;
};

class Brick {
 public:
  //! Whether the brick can be shipped to another node (over-decomposition): only then does it keep
  //! the outer ghost layer, which its own samples never touch (~2% of a 64^3 brick's memory).
  enum class Shipping { No, Yes };

  Brick() = default;
  //! `raw` holds the voxels of storedBoxFor(owned, dims) (x fastest); they are consumed.
  //! `cellShift`: the empty-space cells' size, 2^cellShift voxels a side (0..4); kCellShiftByVolume
  //! chooses it from the volume's size (cellShiftFor), as every node does, so all of a volume's
  //! bricks agree.
  //! `storage`: the volume's (VoxelStorage::forVolume), the same for all its bricks.
  Brick(const VoxelBox& owned, const glm::ivec3& dims, const glm::vec3& spacing, std::vector<float> raw,
        Shipping shipping = Shipping::No, int cellShift = kCellShiftByVolume,
        const VoxelStorage& storage = VoxelStorage{});
  static constexpr int kCellShiftByVolume = -1;

  //! Voxel indices a brick owning `owned` must receive: [lo - 1, hi + 1] clipped to the volume.
  static VoxelBox storedBoxFor(const VoxelBox& owned, const glm::ivec3& dims);
  //! Voxel indices whose values and gradients the brick keeps: [lo, hi], what its samples touch.
  static VoxelBox keptBoxFor(const VoxelBox& owned);
  //! Voxel indices this brick owns for accounting: [lo, hi), plus hi where hi is the volume's
  //! last voxel (the volume's upper faces belong to the bricks that touch them).
  static VoxelBox ownedVoxelsFor(const VoxelBox& owned, const glm::ivec3& dims);

  bool empty() const { return owned_.empty(); }
  const VoxelBox& owned() const { return owned_; }
  const VoxelBox& stored() const { return stored_; }  //!< the voxels kept: keptBoxFor(owned)
  const glm::ivec3& volumeDims() const { return dims_; }
  const glm::vec3& spacing() const { return spacing_; }
  glm::vec3 worldLo() const { return glm::vec3(owned_.lo) * spacing_; }
  glm::vec3 worldHi() const { return glm::vec3(owned_.hi) * spacing_; }

  const VoxelStorage& storage() const { return storage_; }
  //! Kept voxel at global index (x, y, z), which must lie in stored(); float storage only.
  const Voxel& voxel(int x, int y, int z) const { return voxels_[keptIndex(x, y, z)]; }
  //! The same for compact storage.
  const CompactVoxel& compactVoxel(int x, int y, int z) const { return compact_[keptIndex(x, y, z)]; }
  //! The stored value of kept voxel (x, y, z), either format.
  float valueAt(int x, int y, int z) const {
    const std::size_t i = keptIndex(x, y, z);
    return storage_.compactFormat() ? storage_.value(compact_[i].value) : voxels_[i].value;
  }
  const Voxel* voxelData() const { return voxels_.data(); }            //!< null for compact storage
  const CompactVoxel* compactData() const { return compact_.data(); }  //!< null for float storage
  std::size_t strideY() const { return strideY_; }
  std::size_t strideZ() const { return strideZ_; }

  //! The scalar values of storedBoxFor(owned, dims) (x fastest): what the brick was built from, so
  //! a node can ship its brick to another (over-decomposition) and the receiver rebuilds identical
  //! voxels. Only for a brick built with Shipping::Yes.
  std::vector<float> storedValues() const;
  bool shippable() const { return shipping_ == Shipping::Yes; }

  //! Bytes of this node's private memory held by the brick.
  std::uint64_t bytes() const {
    return voxels_.size() * sizeof(Voxel) + compact_.size() * sizeof(CompactVoxel) + shell_.size() * sizeof(float) +
           cellRanges_.bytes() + uniformCells_.size();
  }

  //! Macro cells for empty-space skipping: cell c covers samples whose floor lies in
  //! [c << shift, (c + 1) << shift) (global voxel index, per axis; shift = cellShift()) and keeps a
  //! range containing the min and max of every voxel a trilinear sample there can touch
  //! (CellRangeCodes: 2 bytes a cell). Sample values in the cell lie within that range.
  int cellShift() const { return cellShift_; }
  //! The cell size for a volume of `dims`: one voxel up to kVoxelCellVoxels voxels (128^3), 2^3
  //! voxels up to kFineCellVoxels (512^3), 4^3 above. Finer cells leave out more invisible samples
  //! and mark more samples uniform (one-voxel cells: the default scene 4% and small scans 5-10%
  //! faster; 2^3 against 4^3: the 256^3-class scans and the phantom with waves 7-13%, dense
  //! turbulence within 2%), but cost memory: ~5 bytes per voxel for one-voxel cells, ~0.4 for 2^3,
  //! ~0.05 for 4^3, in the cells' codes and the empty-space maps (~10 MB for 128^3 one-voxel cells,
  //! over 50 MB past 512^3 for 2^3 cells, where coarser cells keep memory to the voxels).
  static int cellShiftFor(const glm::ivec3& dims);
  static constexpr std::int64_t kVoxelCellVoxels = std::int64_t(1) << 21;
  static constexpr std::int64_t kFineCellVoxels = std::int64_t(1) << 27;
  const glm::ivec3& cellLo() const { return cellLo_; }      //!< first cell index per axis
  const glm::ivec3& cellCount() const { return cellCount_; }
  const CellRangeCodes& cellRanges() const { return cellRanges_; }
  //! Per macro cell (x fastest, as cellRanges): 1 where every voxel a sample in the cell touches
  //! holds the same record (value and gradient, byte for byte), else 0. A sample there takes that
  //! record as its value and gradient: what interpolating eight equal corners gives, up to
  //! rounding, without loading them. Piecewise-constant data (phantoms, label volumes) are mostly
  //! such cells; scans with noise have almost none.
  const std::vector<std::uint8_t>& uniformCells() const { return uniformCells_; }
  //! Widens `ranges` (cells of 2^shift voxels, first cell `cellLo`, `cellCount` per axis, x
  //! fastest) by the value of every voxel this brick's samples touch, each in the cells of the
  //! samples that touch it. The brick's own macro cells are built this way, and so is the
  //! finer whole-volume summary occlusion culling reads.
  void widenCellRanges(int shift, const glm::ivec3& cellLo, const glm::ivec3& cellCount,
                       std::vector<glm::vec2>& ranges) const;

 private:
  VoxelBox owned_;
  VoxelBox stored_;    //!< kept voxels (values and gradients)
  VoxelBox received_;  //!< storedBoxFor(owned, dims)
  glm::ivec3 dims_{0};
  glm::vec3 spacing_{1.0f};
  std::size_t strideY_ = 0, strideZ_ = 0;
  VoxelStorage storage_;
  std::vector<Voxel, HugePageAllocator<Voxel>> voxels_;                 //!< float storage
  std::vector<CompactVoxel, HugePageAllocator<CompactVoxel>> compact_;  //!< compact storage
  std::vector<float> shell_;  //!< Shipping::Yes: values of received_ outside stored_, in received_'s order
  Shipping shipping_ = Shipping::No;
  int cellShift_ = 2;
  glm::ivec3 cellLo_{0}, cellCount_{0};
  CellRangeCodes cellRanges_;  //!< per macro cell, x fastest
  std::vector<std::uint8_t> uniformCells_;  //!< per macro cell: uniformCells()

  void buildCells();
  std::size_t keptIndex(int x, int y, int z) const {
    return std::size_t(z - stored_.lo.z) * strideZ_ + std::size_t(y - stored_.lo.y) * strideY_ +
           std::size_t(x - stored_.lo.x);
  }
};

}  // namespace kdswap
