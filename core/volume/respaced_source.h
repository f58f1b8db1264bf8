// RespacedSource: another source with its voxel spacing replaced: for files whose header spacing is
// missing or wrong, and to match a renderer that used another spacing (issue 6's VTK figure for the
// CT head was taken with unit spacing, while headsq.nhdr says 3.2 x 3.2 x 1.5).
#pragma once

#include <memory>

#include <glm/vec3.hpp>

#include "core/volume/volume_source.h"

namespace kdswap {

class RespacedSource : public VolumeSource {
 public:
  //! Throws Error unless `spacing` passes checkSpacing for the volume and its values still pass
  //! checkValueRange (whose gradient bound depends on the spacing).
  RespacedSource(std::unique_ptr<VolumeSource> inner, const glm::vec3& spacing);

  const VolumeInfo& info() const override { return info_; }
  void read(const VoxelBox& box, float* out) const override { inner_->read(box, out); }

 private:
  std::unique_ptr<VolumeSource> inner_;
  VolumeInfo info_;
};

//! "SX,SY,SZ" as a spacing, each from kMinSpacing to kMaxSpacing; Error naming `option` otherwise.
glm::vec3 parseSpacing(const std::string& text, const std::string& option);

}  // namespace kdswap
