// Voxel storage: the choice of format and the compact format's quantisation.
#include "core/volume/voxel_storage.h"

#include <algorithm>
#include <cmath>

#include "core/util/error.h"
#include "core/volume/volume_source.h"

namespace kdswap {

VoxelChoice parseVoxelChoice(const std::string& text, const std::string& what) {
  if (text == "auto") return VoxelChoice::Auto;
  if (text == "float") return VoxelChoice::Float;
  if (text == "compact") return VoxelChoice::Compact;
  throw Error(what + " \"" + text + "\": expected auto, float or compact");
}

const char* voxelChoiceName(VoxelChoice choice) {
  switch (choice) {
    case VoxelChoice::Float: return "float";
    case VoxelChoice::Compact: return "compact";
    case VoxelChoice::Auto: break;
  }
  return "auto";
}

VoxelStorage VoxelStorage::forVolume(const VolumeInfo& info, VoxelChoice choice) {
  const bool compactOne =
      choice == VoxelChoice::Compact || (choice == VoxelChoice::Auto && info.voxelCount() > kCompactAboveVoxels);
  if (!compactOne) return VoxelStorage{};
  return compact(info.minValue, info.maxValue, info.spacing);
}

VoxelStorage VoxelStorage::compact(float minValue, float maxValue, const glm::vec3& spacing) {
  VoxelStorage s;
  s.format = VoxelFormat::Compact;
  const double lo = minValue, span = double(maxValue) - double(minValue);
  // 65536 levels over the range, whatever the data's type says: a type name does not prove the
  // values are whole numbers (data quantised for a benchmark keep their float range). Integer data
  // spanning 255 or 65535 units land exactly on levels (255 divides 65535); others lie within half a
  // level, 1/131070 of the range.
  if (!(span > 0.0))
    s.valueStep = 1.0f, s.valueOrigin = minValue;  // one value: every voxel stores 0
  else
    s.valueStep = float(span / 65535.0), s.valueOrigin = float(lo + 32768.0 * span / 65535.0);
  // The largest gradient component stored values allow: a one-sided difference across the whole
  // range over the smallest spacing (central differences are half that), one level of slack.
  const double smallest = std::min({double(spacing.x), double(spacing.y), double(spacing.z)});
  const double largest = (std::max(span, 0.0) + double(s.valueStep)) / (smallest > 0.0 ? smallest : 1.0);
  s.gradientScale = float(32767.0 / largest);
  return s;
}

std::int16_t VoxelStorage::quantiseValue(float v) const {
  const float q = (v - valueOrigin) / valueStep;
  if (!(q > -32768.0f)) return -32768;  // and NaN
  if (q >= 32767.0f) return 32767;
  return std::int16_t(std::lround(q));
}

std::int16_t VoxelStorage::quantiseGradient(float g) const {
  const float q = g * gradientScale;
  if (!(q > -32767.0f)) return q == q ? -32767 : 0;
  if (q >= 32767.0f) return 32767;
  return std::int16_t(std::lround(q));
}

}  // namespace kdswap
