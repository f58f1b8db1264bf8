// Value histogram of a volume, slab by slab.
#include "ui/histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace kdswap {

std::vector<float> computeHistogram(const VolumeSource& source, int bins) {
  const VolumeInfo& info = source.info();
  std::vector<std::uint64_t> counts(std::size_t(std::max(bins, 1)), 0);
  const float lo = info.minValue, range = std::max(info.maxValue - info.minValue, 1e-20f);
  // About 4M voxels a slab keeps the buffer small for any volume shape.
  const std::int64_t slice = std::int64_t(info.dims.x) * info.dims.y;
  const int slabDepth = int(std::clamp<std::int64_t>((std::int64_t(1) << 22) / std::max<std::int64_t>(slice, 1), 1, info.dims.z));
  std::vector<float> buffer;
  for (int z = 0; z < info.dims.z; z += slabDepth) {
    VoxelBox box;
    box.lo = glm::ivec3(0, 0, z);
    box.hi = glm::ivec3(info.dims.x, info.dims.y, std::min(info.dims.z, z + slabDepth));
    buffer.resize(std::size_t(box.count()));
    source.read(box, buffer.data());
    for (float v : buffer) {
      const int b = int((v - lo) / range * float(bins));
      ++counts[std::size_t(std::clamp(b, 0, bins - 1))];
    }
  }
  std::vector<float> out(counts.size());
  float peak = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) peak = std::max(peak, out[i] = std::log1p(float(counts[i])));
  if (peak > 0)
    for (float& v : out) v /= peak;
  return out;
}

}  // namespace kdswap
