// In-memory volume source.
#include "core/volume/memory_volume.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "core/util/error.h"

namespace kdswap {

MemoryVolume::MemoryVolume(VolumeInfo info, std::vector<float> voxels)
    : info_(std::move(info)), voxels_(std::move(voxels)) {
  validateVolumeInfo(info_, info_.name);
  if (std::int64_t(voxels_.size()) != info_.voxelCount())
    throw Error(info_.name + ": holds " + std::to_string(voxels_.size()) + " voxels, dimensions need " +
                std::to_string(info_.voxelCount()));
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  std::uint64_t bad = 0;
  for (float v : voxels_) {
    if (!std::isfinite(v)) {
      ++bad;
      continue;
    }
    lo = std::min(lo, v);
    hi = std::max(hi, v);
  }
  if (bad == voxels_.size()) lo = hi = 0.0f;
  if (bad > 0)
    for (float& v : voxels_)
      if (!std::isfinite(v)) v = lo;
  info_.minValue = lo;
  info_.maxValue = hi;
  info_.nonFinite = bad;
}

void MemoryVolume::read(const VoxelBox& box, float* out) const {
  const glm::ivec3 d = info_.dims;
  const glm::ivec3 s = box.size();
  for (int z = 0; z < s.z; ++z)
    for (int y = 0; y < s.y; ++y) {
      const std::size_t src = (std::size_t(box.lo.z + z) * d.y + (box.lo.y + y)) * d.x + box.lo.x;
      std::memcpy(out + (std::size_t(z) * s.y + y) * s.x, voxels_.data() + src, sizeof(float) * s.x);
    }
}

}  // namespace kdswap
