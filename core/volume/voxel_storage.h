// How a brick stores its voxels (value and central-difference gradient). Float: four floats, 16
// bytes, as read. Compact: four signed 16-bit integers, 8 bytes: half the memory and half the
// memory traffic per sample, which pays where a volume is too large to stay in cache (measured:
// phantom 256^3 at P = 64 ~7% faster), while on cache-sized volumes widening the integers costs
// more than the traffic saves (default scene ~5% slower in a probe). So the default picks Compact
// only above 2^23 voxels. Every brick of a volume must store alike, or split rays would not equal
// whole ones: the choice and its quantisation come from the volume (VolumeInfo), never from a
// brick's own data.
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace kdswap {

struct VolumeInfo;

//! One stored voxel in the compact format: value and gradient as 16-bit integers (VoxelStorage
//! says what they stand for).
struct CompactVoxel {
  std::int16_t value;
  std::int16_t gradient[3];
};

enum class VoxelFormat { Float, Compact };

//! What users ask for: Auto picks Compact above kCompactAboveVoxels voxels.
enum class VoxelChoice { Auto, Float, Compact };

//! "auto", "float" or "compact"; throws kdswap::Error naming `what` otherwise.
VoxelChoice parseVoxelChoice(const std::string& text, const std::string& what = "--voxels");
const char* voxelChoiceName(VoxelChoice choice);

struct VoxelStorage {
  static constexpr std::int64_t kCompactAboveVoxels = std::int64_t(1) << 23;

  VoxelFormat format = VoxelFormat::Float;
  //! Compact: stored value q stands for q * valueStep + valueOrigin: 65536 levels over the
  //! volume's range (integer data spanning 0..255 or 0..65535 fall exactly on levels).
  float valueOrigin = 0.0f, valueStep = 1.0f;
  //! Compact: a stored gradient component is the gradient (value per world unit) times this,
  //! rounded. Chosen so the largest gradient the range allows fits; shading reads only the
  //! gradient's direction, so the scale itself never shows in an image.
  float gradientScale = 1.0f;

  //! The storage every brick of `info`'s volume uses under `choice`.
  static VoxelStorage forVolume(const VolumeInfo& info, VoxelChoice choice = VoxelChoice::Auto);
  //! Compact storage for values in [minValue, maxValue] and voxel `spacing`.
  static VoxelStorage compact(float minValue, float maxValue, const glm::vec3& spacing);

  bool compactFormat() const { return format == VoxelFormat::Compact; }
  //! The stored integer nearest to v (clamped to 16 bits; NaN to the lowest level).
  std::int16_t quantiseValue(float v) const;
  float value(std::int16_t q) const { return float(q) * valueStep + valueOrigin; }
  //! The mapping of stored values to [0, 1] (what the shader interpolates) from the mapping of
  //! values, normalised = value * scale + bias: unchanged for float storage, folded with the
  //! quantisation for compact.
  glm::vec2 storedScaleBias(float scale, float bias) const {
    return compactFormat() ? glm::vec2(scale * valueStep, scale * valueOrigin + bias) : glm::vec2(scale, bias);
  }
  std::int16_t quantiseGradient(float g) const;
  //! 8 or 16.
  int bytesPerVoxel() const { return compactFormat() ? 8 : 16; }

  bool operator==(const VoxelStorage&) const = default;
};

}  // namespace kdswap
