// Brick storage and per-voxel gradients; the gradient formula matches the whole volume's exactly
// (central differences inside, one-sided at the volume's faces), which is what makes split rays
// equal whole rays next to a cut.
#include "core/volume/brick.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "core/util/check.h"

namespace kdswap {

VoxelBox Brick::storedBoxFor(const VoxelBox& owned, const glm::ivec3& dims) {
  if (owned.empty()) return VoxelBox{};
  return VoxelBox{glm::max(owned.lo - 1, glm::ivec3(0)), glm::min(owned.hi + 2, dims)};
}

VoxelBox Brick::keptBoxFor(const VoxelBox& owned) {
  if (owned.empty()) return VoxelBox{};
  return VoxelBox{owned.lo, owned.hi + 1};
}

int Brick::cellShiftFor(const glm::ivec3& dims) {
  const std::int64_t voxels = std::int64_t(dims.x) * dims.y * dims.z;
  return voxels <= kVoxelCellVoxels ? 0 : voxels <= kFineCellVoxels ? 1 : 2;
}

VoxelBox Brick::ownedVoxelsFor(const VoxelBox& owned, const glm::ivec3& dims) {
  if (owned.empty()) return VoxelBox{};
  VoxelBox v = owned;
  for (int a = 0; a < 3; ++a)
    if (owned.hi[a] == dims[a] - 1) v.hi[a] = dims[a];
  return v;
}

std::vector<float> Brick::storedValues() const {
  KDSWAP_CHECK(shippable() || owned_.empty());
  std::vector<float> values;
  values.reserve(std::size_t(received_.count()));
  std::size_t next = 0;
  for (int z = received_.lo.z; z < received_.hi.z; ++z)
    for (int y = received_.lo.y; y < received_.hi.y; ++y)
      for (int x = received_.lo.x; x < received_.hi.x; ++x)
        values.push_back(stored_.contains(glm::ivec3(x, y, z)) ? valueAt(x, y, z) : shell_[next++]);
  return values;
}

Brick::Brick(const VoxelBox& owned, const glm::ivec3& dims, const glm::vec3& spacing, std::vector<float> raw,
             Shipping shipping, int cellShift, const VoxelStorage& storage)
    : owned_(owned),
      stored_(keptBoxFor(owned)),
      received_(storedBoxFor(owned, dims)),
      dims_(dims),
      spacing_(spacing),
      storage_(storage),
      shipping_(shipping),
      cellShift_(cellShift == kCellShiftByVolume ? cellShiftFor(dims) : cellShift) {
  KDSWAP_CHECK(cellShift_ >= 0 && cellShift_ <= 4);
  if (owned_.empty()) return;
  KDSWAP_CHECK_EQ(raw.size(), std::size_t(received_.count()));
  const glm::ivec3 r = received_.size();
  auto at = [&](int x, int y, int z) {
    return raw[(std::size_t(z - received_.lo.z) * r.y + std::size_t(y - received_.lo.y)) * r.x + (x - received_.lo.x)];
  };
  const glm::ivec3 s = stored_.size();
  strideY_ = std::size_t(s.x);
  strideZ_ = std::size_t(s.x) * s.y;
  const bool compact = storage_.compactFormat();
  if (compact) {
    for (float& v : raw) v = storage_.value(storage_.quantiseValue(v));  // from here on: the stored values
    compact_.resize(std::size_t(stored_.count()));
  } else {
    voxels_.resize(std::size_t(stored_.count()));
  }
  // Every kept voxel gets its gradient; the outer ghost layer of `raw` only feeds them.
  for (int z = stored_.lo.z; z < stored_.hi.z; ++z)
    for (int y = stored_.lo.y; y < stored_.hi.y; ++y)
      for (int x = stored_.lo.x; x < stored_.hi.x; ++x) {
        const glm::ivec3 p(x, y, z);
        glm::vec3 gradient;
        for (int a = 0; a < 3; ++a) {
          glm::ivec3 lo = p, hi = p;
          lo[a] = std::max(p[a] - 1, 0);
          hi[a] = std::min(p[a] + 1, dims[a] - 1);
          const float span = float(hi[a] - lo[a]) * spacing[a];
          gradient[a] = (at(hi.x, hi.y, hi.z) - at(lo.x, lo.y, lo.z)) / span;
        }
        const std::size_t i = keptIndex(x, y, z);
        if (compact) {
          CompactVoxel& out = compact_[i];
          out.value = storage_.quantiseValue(at(x, y, z));
          for (int a = 0; a < 3; ++a) out.gradient[a] = storage_.quantiseGradient(gradient[a]);
        } else {
          voxels_[i] = Voxel{at(x, y, z), gradient};
        }
      }
  if (shipping_ == Shipping::Yes) {
    for (int z = received_.lo.z; z < received_.hi.z; ++z)
      for (int y = received_.lo.y; y < received_.hi.y; ++y)
        for (int x = received_.lo.x; x < received_.hi.x; ++x)
          if (!stored_.contains(glm::ivec3(x, y, z))) shell_.push_back(at(x, y, z));
    shell_.shrink_to_fit();
  }
  buildCells();
}

void Brick::buildCells() {
  // Cells over the owned samples: floor(p) ranges over [owned.lo, owned.hi - 1].
  cellLo_ = owned_.lo >> cellShift_;
  const glm::ivec3 cellHi = ((owned_.hi - 1) >> cellShift_) + 1;
  cellCount_ = cellHi - cellLo_;
  std::vector<glm::vec2> ranges(std::size_t(cellCount_.x) * cellCount_.y * cellCount_.z,
                                glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()));
  widenCellRanges(cellShift_, cellLo_, cellCount_, ranges);
  cellRanges_ = CellRangeCodes(ranges);
  // Uniform cells: only those whose value range is one value can be; then every touched record
  // (value and gradient) must equal the first, byte for byte (-0 and +0 differ: the safe side).
  uniformCells_.assign(ranges.size(), 0);
  const bool compact = storage_.compactFormat();
  for (int cz = 0; cz < cellCount_.z; ++cz)
    for (int cy = 0; cy < cellCount_.y; ++cy)
      for (int cx = 0; cx < cellCount_.x; ++cx) {
        const std::size_t i = (std::size_t(cz) * cellCount_.y + cy) * cellCount_.x + cx;
        if (ranges[i].x != ranges[i].y) continue;
        // The samples with floor in the cell (and the owned box) touch voxels floor .. floor + 1.
        const glm::ivec3 c = glm::ivec3(cx, cy, cz) + cellLo_;
        const glm::ivec3 lo = glm::max(c << cellShift_, owned_.lo);
        const glm::ivec3 hi = glm::min((c + 1) << cellShift_, owned_.hi);
        const std::size_t first = keptIndex(lo.x, lo.y, lo.z);
        bool same = true;
        for (int z = lo.z; z <= hi.z && same; ++z)
          for (int y = lo.y; y <= hi.y && same; ++y)
            for (int x = lo.x; x <= hi.x && same; ++x) {
              const std::size_t k = keptIndex(x, y, z);
              same = compact ? std::memcmp(&compact_[k], &compact_[first], sizeof(CompactVoxel)) == 0
                             : std::memcmp(&voxels_[k], &voxels_[first], sizeof(Voxel)) == 0;
            }
        uniformCells_[i] = same ? 1 : 0;
      }
}

void Brick::widenCellRanges(int shift, const glm::ivec3& cellLo, const glm::ivec3& cellCount,
                            std::vector<glm::vec2>& ranges) const {
  // Each voxel v touches the cells of samples with floor in {v - 1, v}: cells of v - 1 and v.
  for (int z = std::max(stored_.lo.z, owned_.lo.z); z <= std::min(stored_.hi.z - 1, owned_.hi.z); ++z)
    for (int y = std::max(stored_.lo.y, owned_.lo.y); y <= std::min(stored_.hi.y - 1, owned_.hi.y); ++y)
      for (int x = std::max(stored_.lo.x, owned_.lo.x); x <= std::min(stored_.hi.x - 1, owned_.hi.x); ++x) {
        const float v = valueAt(x, y, z);
        const glm::ivec3 p(x, y, z);
        const glm::ivec3 c0 = glm::max((glm::max(p - 1, owned_.lo) >> shift) - cellLo, glm::ivec3(0));
        const glm::ivec3 c1 = glm::min((glm::min(p, owned_.hi - 1) >> shift) - cellLo, cellCount - 1);
        for (int cz = c0.z; cz <= c1.z; ++cz)
          for (int cy = c0.y; cy <= c1.y; ++cy)
            for (int cx = c0.x; cx <= c1.x; ++cx) {
              glm::vec2& r = ranges[(std::size_t(cz) * cellCount.y + cy) * cellCount.x + cx];
              r.x = std::min(r.x, v);
              r.y = std::max(r.y, v);
            }
      }
}

}  // namespace kdswap
