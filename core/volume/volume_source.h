// VolumeSource: where voxels come from (a file reader, a decoded buffer or a procedural data set).
// The host's data distributor reads one brick at a time through it, so a source never has to
// hold the whole volume unless its format forces that (compressed files).
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>
#include <glm/ext/vector_double3.hpp>

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

//! Checks dims and spacing a reader found (checkSpacing); throws kdswap::Error naming `where`. Also
//! refuses a volume whose voxels and gradients would not fit in available memory, before any allocation.
void validateVolumeInfo(const VolumeInfo& info, const std::string& where);

//! Spacing bounds, the same for every file format and option. The renderer works in float world
//! units with a few absolute tolerances (camera, ray setup): images of a volume are unchanged with
//! its spacing scaled from 1e-6 to 1e15, blank at 1e-9 and 1e18 (an extent squared overflows), and
//! a ray march over 1e-7 x 1 x 1 spacings crashed (its sample index outgrew float precision). So
//! each spacing lies in [kMinSpacing, kMaxSpacing] and the longest side of the volume is at most
//! kMaxSideSteps of its smallest spacing (for equal spacings: at most 1e6 + 1 voxels a side).
constexpr double kMinSpacing = 1e-6, kMaxSpacing = 1e6, kMaxSideSteps = 1e6;

//! Throws kdswap::Error unless each component of `spacing` is finite, > 0 and within the bounds
//! above for a volume of `dims` (each >= 2). The message is "WHERE: [FIELD: ]PROBLEM"; `field`
//! names the header field or option with its text, e.g. `spacings "1 0 1"`, or is empty.
void checkSpacing(const glm::ivec3& dims, const glm::dvec3& spacing, const std::string& where,
                  const std::string& field = "");

//! Value range bounds for float arithmetic: max - min must be a float well inside FLT_MAX, and
//! 1 / (max - min) and its 16-bit compact step normal floats (65535 * FLT_MIN is 7.7e-34). Shading
//! takes the squared length of a gradient (value change per unit of length, at most max - min over
//! the smallest spacing) in float: above 1.8e19 it overflows and the image goes dark (measured: data
//! 0 or 2e19 at unit spacing shade wrong, 0 or 1e19 right; components near FLT_MAX made a NaN that
//! crashed a table lookup).
constexpr double kMaxValueSpan = 1e37, kMinValueSpan = 1e-33, kMaxGradient = 1e19;

//! Throws kdswap::Error naming `where` when a volume's finite values cannot be rendered: there are
//! none (every voxel NaN or Inf), max - min is above kMaxValueSpan or above 0 but below
//! kMinValueSpan, or max - min over the smallest spacing is above kMaxGradient. A constant volume
//! is allowed.
void checkValueRange(const VolumeInfo& info, const std::string& where);

//! Refuses, naming `where`, a volume whose bricks at `bytesPerVoxel` (value and gradient: 16 as
//! floats, 8 compact) would not fit in available memory; `hint` ends the message if not empty.
void checkBrickMemory(const VolumeInfo& info, int bytesPerVoxel, const std::string& where,
                      const std::string& hint = "");

}  // namespace kdswap
