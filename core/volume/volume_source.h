// VolumeSource: where voxels come from (a file reader, a decoded buffer or a procedural data set).
// The host's data distributor reads one brick at a time through it, so a source never has to
// hold the whole volume unless its format forces that (compressed files).
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "core/volume/voxel_box.h"

namespace kdswap {

struct VolumeInfo {
  glm::ivec3 dims{0};           //!< voxels along x, y, z (each >= 2)
  glm::vec3 spacing{1.0f};      //!< world size of one voxel step along each axis
  std::string type = "float32"; //!< scalar type as stored: int8 uint8 int16 uint16 int32 uint32 float32 float64
  float minValue = 0.0f;        //!< smallest finite value
  float maxValue = 1.0f;        //!< largest finite value
  std::uint64_t nonFinite = 0;  //!< NaN/Inf voxels, read back as minValue (empty)
  std::string name;             //!< file path or data set spec, for messages
  std::string preset;           //!< suggested transfer-function preset, may be empty

  std::int64_t voxelCount() const { return std::int64_t(dims.x) * dims.y * dims.z; }
  glm::vec3 worldMax() const { return glm::vec3(dims - 1) * spacing; }
};

class VolumeSource {
 public:
  virtual ~VolumeSource() = default;
  virtual const VolumeInfo& info() const = 0;
  //! Writes the voxels of `box` (inside [0, dims)) to `out` as floats, x fastest, then y, then z;
  //! `out` holds box.count() floats. Non-finite values are written as info().minValue.
  //! Safe to call from several threads at once. Throws kdswap::Error on I/O failure.
  virtual void read(const VoxelBox& box, float* out) const = 0;
};

//! Checks dims and spacing a reader found; throws kdswap::Error naming `where`. Also refuses a
//! volume whose voxels and gradients would not fit in available memory, before any allocation.
void validateVolumeInfo(const VolumeInfo& info, const std::string& where);
//! Refuses, naming `where`, a volume whose bricks at `bytesPerVoxel` (value and gradient: 16 as
//! floats, 8 compact) would not fit in available memory; `hint` ends the message if not empty.
void checkBrickMemory(const VolumeInfo& info, int bytesPerVoxel, const std::string& where,
                      const std::string& hint = "");

}  // namespace kdswap
