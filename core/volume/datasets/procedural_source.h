// ProceduralSource: a VolumeSource that computes voxels on demand, brick by brick, from a
// deterministic field. Built-in data sets (phantom, vessels, turbulence) are instances.
#pragma once

#include <functional>
#include <memory>
#include <string>

#include "core/volume/volume_source.h"

namespace kdswap {

class ProceduralSource : public VolumeSource {
 public:
  //! Fills `out` for `box` exactly as VolumeSource::read; must be deterministic and thread-safe.
  using Generator = std::function<void(const VoxelBox& box, float* out)>;

  ProceduralSource(VolumeInfo info, Generator generate);
  const VolumeInfo& info() const override { return info_; }
  void read(const VoxelBox& box, float* out) const override { generate_(box, out); }

 private:
  VolumeInfo info_;
  Generator generate_;
};

//! Normalised coordinate in [-1, 1] of voxel index i along an axis of n voxels.
inline float unitCoordinate(int i, int n) { return n > 1 ? 2.0f * float(i) / float(n - 1) - 1.0f : 0.0f; }

}  // namespace kdswap
