// Shared validation of what readers and data sets report, so every path refuses the same things.
#include "core/volume/volume_source.h"

#include <cmath>
#include <string>

#include "core/util/error.h"
#include "core/util/memory.h"
#include "core/volume/voxel_storage.h"

namespace kdswap {

void validateVolumeInfo(const VolumeInfo& info, const std::string& where) {
  const glm::ivec3& d = info.dims;
  for (int a = 0; a < 3; ++a) {
    if (d[a] < 2)
      throw Error(where + ": dimensions " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                  std::to_string(d.z) + ": every dimension must be at least 2 voxels");
    if (!(std::isfinite(info.spacing[a]) && info.spacing[a] > 0.0f))
      throw Error(where + ": spacing along axis " + std::to_string(a) + " must be a positive number");
  }
  // The storage the volume gets by default (a user asking for floats is checked again); counted in
  // double, as absurd dimensions overflow 64-bit integers (VolumeInfo::voxelCount).
  const double voxels = double(d.x) * double(d.y) * double(d.z);
  checkBrickMemory(info, voxels > double(VoxelStorage::kCompactAboveVoxels) ? 8 : 16, where);
}

void checkBrickMemory(const VolumeInfo& info, int bytesPerVoxel, const std::string& where, const std::string& hint) {
  const glm::ivec3& d = info.dims;
  const double voxels = double(d.x) * double(d.y) * double(d.z);
  const double need = voxels * double(bytesPerVoxel);
  const double have = double(availableMemoryBytes());
  if (voxels > 9.0e15 || (have > 0 && need > have))
    throw Error(where + ": dimensions " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                std::to_string(d.z) + " need " + formatBytes(std::uint64_t(std::min(need, 1.8e19))) +
                " for voxels and gradients, but only " + formatBytes(std::uint64_t(have)) + " is available" +
                (hint.empty() ? "" : " (" + hint + ")"));
}

}  // namespace kdswap
