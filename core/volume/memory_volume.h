// MemoryVolume: a VolumeSource over voxels already decoded into memory (compressed files, tests).
#pragma once

#include <vector>

#include "core/volume/volume_source.h"

namespace kdswap {

class MemoryVolume : public VolumeSource {
 public:
  //! Takes `voxels` (dims.x*dims.y*dims.z floats, x fastest). Computes the finite value range and
  //! replaces NaN/Inf by the smallest finite value (counted in info().nonFinite).
  MemoryVolume(VolumeInfo info, std::vector<float> voxels);

  const VolumeInfo& info() const override { return info_; }
  void read(const VoxelBox& box, float* out) const override;
  const std::vector<float>& voxels() const { return voxels_; }

 private:
  VolumeInfo info_;
  std::vector<float> voxels_;
};

}  // namespace kdswap
