// VolumeSummary: what `kdswap info` reports about a volume (dims, type, spacing, range, a
// histogram, memory), computed by streaming the source in slabs of z, never the whole volume.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/volume/volume_source.h"

namespace kdswap {

struct VolumeSummary {
  VolumeInfo info;
  std::vector<std::uint64_t> histogram;  //!< equal bins over [minValue, maxValue]; max in the last
  std::uint64_t voxels = 0;
  std::uint64_t zeros = 0;               //!< voxels equal to 0
  std::uint64_t atMinimum = 0;           //!< voxels equal to minValue (NaN/Inf read back as it)
  double mean = 0.0;
  std::uint64_t storedBytes = 0;         //!< voxels in their stored type
  std::uint64_t brickBytes = 0;          //!< voxels with gradients in the bricks (default storage)
  int bytesPerVoxel = 16;                //!< in the bricks: 16 (float storage) or 8 (compact)
};

//! Reads `source` slab by slab (a few MiB each, slabs in parallel) and fills a summary with
//! `bins` histogram bins. Throws what source.read() throws.
VolumeSummary summarizeVolume(const VolumeSource& source, int bins = 16);

//! Several lines of text: the fields, then one line per histogram bin with a bar.
std::string formatSummary(const VolumeSummary& summary);
//! {"name", "dims": [x,y,z], "type", "spacing": [x,y,z], "range": [min,max], "nonFinite", "voxels",
//!  "mean", "zeroFraction", "minFraction", "histogram": {"edges", "counts"}, "bytes": {...}, "preset"}
nlohmann::json summaryToJson(const VolumeSummary& summary);

}  // namespace kdswap
