// Opening a format's voxel array: streamed when uncompressed, decoded once when compressed.
#include "core/volume/readers/stored_data.h"

#include <cstdio>
#include <filesystem>
#include <limits>
#include <vector>

#include "core/util/error.h"
#include "core/volume/memory_volume.h"
#include "core/volume/readers/inflate_stream.h"
#include "core/volume/readers/raw_file_source.h"

namespace kdswap {
namespace {

//! Refuses values the renderer cannot map (checkValueRange); warns, one line each, of NaN/Inf voxels
//! and of a constant volume, which is valid data (info, export) but renders as a single value.
void checkValues(const VolumeInfo& info) {
  checkValueRange(info, info.name);
  if (info.nonFinite > 0)
    std::fprintf(stderr, "kdswap: warning: %s: %llu NaN/Inf voxels, excluded from the range and read as %g\n",
                 info.name.c_str(), static_cast<unsigned long long>(info.nonFinite), double(info.minValue));
  // Types a float cannot hold exactly may differ only beyond float precision: say so.
  const bool inexact = info.type == "float64" || info.type == "int32" || info.type == "uint32";
  if (info.minValue == info.maxValue)
    std::fprintf(stderr, "kdswap: warning: %s: every %svoxel has the value %g%s: a constant volume has no value "
                 "range, so every voxel maps to the start of the transfer function\n",
                 info.name.c_str(), info.nonFinite > 0 ? "finite " : "", double(info.minValue),
                 inexact ? " at float precision" : "");
}

std::string fileProblem(const std::string& path) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) return "no such file";
  if (std::filesystem::is_directory(status)) return "is a directory, not a file of voxels";
  if (!std::filesystem::is_regular_file(status)) return "is not a regular file (a device, FIFO or socket)";
  return "";
}

std::unique_ptr<VolumeSource> decodeCompressed(VolumeInfo info, const StoredData& data) {
  const std::size_t typeSize = scalarTypeSize(data.type);
  const std::uint64_t total = std::uint64_t(info.voxelCount());
  const std::string layout = dimsText(info.dims) + " " + std::string(scalarTypeName(data.type));
  const std::string label = dataLabel(data, info);
  InflateStream stream(data.path, data.offset, label);
  stream.skip(data.skipDecoded, "compressed data");
  std::vector<float> voxels(total);
  constexpr std::uint64_t kChunk = 1 << 20;
  std::vector<unsigned char> bytes(std::min(total, kChunk) * typeSize);
  for (std::uint64_t first = 0; first < total; first += kChunk) {
    const std::uint64_t n = std::min(kChunk, total - first);
    const std::size_t got = stream.read(bytes.data(), n * typeSize);
    if (got != n * typeSize)
      throw Error(label + ": truncated: compressed data holds " + std::to_string(first * typeSize + got) +
                  " bytes, " + layout + " needs " + std::to_string(total * typeSize));
    convertToFloat(bytes.data(), n, data.type, data.bigEndian, voxels.data() + first, data.scale, data.shift);
  }
  unsigned char extra = 0;
  if (!data.allowTrailing && stream.read(&extra, 1) != 0)
    throw Error(label + ": header and data size disagree: compressed data holds more than the " +
                std::to_string(total * typeSize) + " bytes " + layout + " needs");
  return std::make_unique<MemoryVolume>(std::move(info), std::move(voxels));
}

}  // namespace

std::uint64_t trailingDataOffset(const VolumeInfo& info, const StoredData& data) {
  validateVolumeInfo(info, info.name);  // before the size product below can overflow
  const std::uint64_t need = std::uint64_t(info.voxelCount()) * scalarTypeSize(data.type);
  std::error_code ec;
  const std::uint64_t size = std::filesystem::file_size(data.path, ec);
  if (ec) throw Error(dataLabel(data, info) + ": cannot read its size: " + ec.message());
  if (size < need)
    throw Error(dataLabel(data, info) + ": truncated: " + dimsText(info.dims) + " " + std::string(scalarTypeName(data.type)) +
                " needs " + std::to_string(need) + " bytes, the file has " + std::to_string(size));
  return size - need;
}

void checkDataFile(const std::string& dataPath, const std::string& where, const std::string& field) {
  const std::string problem = fileProblem(dataPath);
  if (!problem.empty()) throw Error(where + ": " + field + " (" + dataPath + "): " + problem);
}

std::string dataLabel(const StoredData& data, const VolumeInfo& info) {
  return data.path == info.name ? data.path : data.path + " (data file of " + info.name + ")";
}

std::string dimsText(const glm::ivec3& dims) {
  return std::to_string(dims.x) + "x" + std::to_string(dims.y) + "x" + std::to_string(dims.z);
}

glm::ivec3 dimsFromSizes(const std::vector<std::int64_t>& sizes, const std::string& where, const std::string& field) {
  std::string text;
  for (std::int64_t v : sizes) {
    if (!text.empty()) text += ' ';
    text += std::to_string(v);
  }
  if (sizes.size() != 3)
    throw Error(where + ": " + field + " \"" + text + "\": expected 3 sizes");
  for (std::int64_t v : sizes)
    if (v < 2 || v > std::numeric_limits<int>::max())
      throw Error(where + ": " + field + " \"" + text + "\": every size must be a whole number from 2 to " +
                  std::to_string(std::numeric_limits<int>::max()));
  return glm::ivec3(int(sizes[0]), int(sizes[1]), int(sizes[2]));
}

std::unique_ptr<VolumeSource> openStoredData(VolumeInfo info, const StoredData& data) {
  info.type = std::string(scalarTypeName(data.type));
  validateVolumeInfo(info, info.name);
  std::unique_ptr<VolumeSource> source;
  if (data.compressed)
    source = decodeCompressed(std::move(info), data);
  else
    source = std::make_unique<RawFileSource>(std::move(info), data);
  checkValues(source->info());
  return source;
}

std::unique_ptr<VolumeSource> openDecoded(VolumeInfo info, std::vector<float> voxels) {
  auto source = std::make_unique<MemoryVolume>(std::move(info), std::move(voxels));
  checkValues(source->info());
  return source;
}

}  // namespace kdswap
