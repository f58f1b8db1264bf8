// Value histogram of a volume, slab by slab.
#include "ui/histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace kdswap {
namespace {

std::vector<float> logScaled(const std::vector<std::uint64_t>& counts) {
  std::vector<float> out(counts.size());
  float peak = 0;
  for (std::size_t i = 0; i < counts.size(); ++i) peak = std::max(peak, out[i] = std::log1p(float(counts[i])));
  if (peak > 0)
    for (float& v : out) v /= peak;
  return out;
}

}  // namespace

Histogram computeHistogram(const VolumeSource& source, int bins) {
  bins = std::max(bins, 1);
  const VolumeInfo& info = source.info();
  const float lo = info.minValue, range = std::max(info.maxValue - info.minValue, 1e-20f);
  std::vector<std::uint64_t> counts(std::size_t(bins), 0);
  // Integer candidates: whole minimum and maximum, a span floats hold exactly. Whether every
  // voxel is whole is found while counting; integer bins are counted alongside until one is not.
  const double span = double(info.maxValue) - double(info.minValue);
  bool integers = std::floor(info.minValue) == info.minValue && std::floor(info.maxValue) == info.maxValue &&
                  span >= 1 && span < double(1 << 24);
  const std::int64_t values = integers ? std::int64_t(span) + 1 : 0;
  const std::int64_t perBin = integers ? (values + bins - 1) / bins : 1;
  std::vector<std::uint64_t> integerCounts(integers ? std::size_t((values + perBin - 1) / perBin) : 0, 0);
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
      if (integers) {
        if (std::floor(v) != v) {
          integers = false;
          continue;
        }
        const std::int64_t k = std::clamp<std::int64_t>(std::int64_t(v - lo), 0, values - 1) / perBin;
        ++integerCounts[std::size_t(k)];
      }
    }
  }
  Histogram h;
  if (integers) {
    // Bin k holds the values lo + k * perBin .. lo + (k + 1) * perBin - 1; its edges lie half a
    // value outside them.
    h.bins = logScaled(integerCounts);
    h.valuesPerBin = int(perBin);
    h.x0 = float(-0.5 / span);
    h.x1 = float((double(integerCounts.size()) * double(perBin) - 0.5) / span);
  } else {
    h.bins = logScaled(counts);
  }
  return h;
}

}  // namespace kdswap
