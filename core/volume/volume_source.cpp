// Shared validation of what readers and data sets report, so every path refuses the same things.
#include "core/volume/volume_source.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "core/util/error.h"
#include "core/util/memory.h"
#include "core/volume/voxel_storage.h"

namespace kdswap {
namespace {

std::string number(double v) {
  if (std::isnan(v)) return "nan";  // not "-nan" for a NaN whose sign bit fabs or a format set
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

}  // namespace

void validateVolumeInfo(const VolumeInfo& info, const std::string& where) {
  const glm::ivec3& d = info.dims;
  for (int a = 0; a < 3; ++a)
    if (d[a] < 2)
      throw Error(where + ": dimensions " + std::to_string(d.x) + "x" + std::to_string(d.y) + "x" +
                  std::to_string(d.z) + ": every dimension must be at least 2 voxels");
  checkSpacing(d, glm::dvec3(info.spacing), where);
  // The storage the volume gets by default (a user asking for floats is checked again); counted in
  // double, as absurd dimensions overflow 64-bit integers (VolumeInfo::voxelCount).
  const double voxels = double(d.x) * double(d.y) * double(d.z);
  checkBrickMemory(info, voxels > double(VoxelStorage::kCompactAboveVoxels) ? 8 : 16, where);
}

void checkSpacing(const glm::ivec3& dims, const glm::dvec3& spacing, const std::string& where, const std::string& field) {
  const std::string prefix = where + ": " + (field.empty() ? "" : field + ": ");
  int smallest = 0, longest = 0;
  for (int a = 0; a < 3; ++a) {
    const double s = spacing[a];
    if (!(std::isfinite(s) && s > 0.0))
      throw Error(prefix + "spacing along axis " + std::to_string(a) + " must be a positive number, not " + number(s));
    if (float(s) < float(kMinSpacing) || float(s) > float(kMaxSpacing))  // as floats: 1e-6f is below 1e-6
      throw Error(prefix + "spacing along axis " + std::to_string(a) + " is " + number(s) + ", outside " +
                  number(kMinSpacing) + " .. " + number(kMaxSpacing) + ": give it in other units");
    if (s < spacing[smallest]) smallest = a;
    if (double(dims[a] - 1) * s > double(dims[longest] - 1) * spacing[longest]) longest = a;
  }
  const double side = double(dims[longest] - 1) * spacing[longest];
  if (side > kMaxSideSteps * spacing[smallest])
    throw Error(prefix + "the longest side (" + number(side) + " along axis " + std::to_string(longest) + ") is " +
                number(side / spacing[smallest]) + " times the smallest spacing (" + number(spacing[smallest]) +
                " along axis " + std::to_string(smallest) + "), more than " + number(kMaxSideSteps) +
                ": the spacings differ too much to render");
}

void checkValueRange(const VolumeInfo& info, const std::string& where) {
  if (info.nonFinite > 0 && info.nonFinite >= std::uint64_t(info.voxelCount()))
    throw Error(where + ": no finite voxel values: all " + std::to_string(info.nonFinite) + " voxels are NaN or Inf");
  const std::string values = "finite values " + number(info.minValue) + " .. " + number(info.maxValue);
  const double span = double(info.maxValue) - double(info.minValue);
  if (span > kMaxValueSpan)
    throw Error(where + ": " + values + ": max - min = " + number(span) + " is too wide for float arithmetic (at most " +
                number(kMaxValueSpan) + ")");
  if (span > 0.0 && span < kMinValueSpan)
    throw Error(where + ": " + values + ": max - min = " + number(span) + " is too narrow for float arithmetic (at least " +
                number(kMinValueSpan) + ")");
  const double smallest = std::min({double(info.spacing.x), double(info.spacing.y), double(info.spacing.z)});
  if (span / smallest > kMaxGradient)
    throw Error(where + ": " + values + " over spacing " + number(smallest) + ": gradients up to " + number(span / smallest) +
                " per unit of length are too steep for float shading (at most " + number(kMaxGradient) +
                "): scale the values down");
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
