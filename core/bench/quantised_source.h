// QuantisedSource: a VolumeSource that rounds another source's values to 8 or 16 bits over its
// range, so a procedural data set can stand in for 8-bit or 16-bit scanner data. Bricks still
// hold floats (the renderer's only format): only the values change, not the memory layout.
#pragma once

#include <memory>

#include "core/volume/volume_source.h"

namespace kdswap {

class QuantisedSource : public VolumeSource {
 public:
  //! `bits` is 8 or 16; values become min + k * (max - min) / (2^bits - 1). Throws Error otherwise.
  QuantisedSource(std::unique_ptr<VolumeSource> inner, int bits);

  const VolumeInfo& info() const override { return info_; }
  void read(const VoxelBox& box, float* out) const override;

 private:
  std::unique_ptr<VolumeSource> inner_;
  VolumeInfo info_;
  float levels_;  //!< 2^bits - 1
};

}  // namespace kdswap
