// Streaming summary of a volume for `kdswap info`.
#include "core/volume/volume_summary.h"

#include <algorithm>
#include <cstdio>

#include <oneapi/tbb/parallel_for.h>

#include "core/util/memory.h"
#include "core/volume/readers/scalar_type.h"
#include "core/volume/voxel_storage.h"

namespace kdswap {
namespace {

constexpr std::int64_t kSlabVoxels = 1 << 20;  // 4 MiB of floats per slab in flight

struct Partial {
  std::vector<std::uint64_t> histogram;
  std::uint64_t zeros = 0, atMinimum = 0;
  double sum = 0.0;
};

std::string number(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", v);
  return text;
}

std::string percent(std::uint64_t part, std::uint64_t whole) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f%%", whole ? 100.0 * double(part) / double(whole) : 0.0);
  return text;
}

}  // namespace

VolumeSummary summarizeVolume(const VolumeSource& source, int bins) {
  VolumeSummary s;
  s.info = source.info();
  const glm::ivec3 d = s.info.dims;
  s.voxels = std::uint64_t(s.info.voxelCount());
  const auto type = parseScalarType(s.info.type);
  s.storedBytes = s.voxels * (type ? scalarTypeSize(*type) : sizeof(float));
  s.bytesPerVoxel = VoxelStorage::forVolume(s.info).bytesPerVoxel();
  s.brickBytes = s.voxels * std::uint64_t(s.bytesPerVoxel);
  bins = std::max(bins, 1);

  const int slabDepth = int(std::clamp<std::int64_t>(kSlabVoxels / (std::int64_t(d.x) * d.y), 1, d.z));
  const int slabs = (d.z + slabDepth - 1) / slabDepth;
  std::vector<Partial> partials(slabs);
  const float lo = s.info.minValue, span = s.info.maxValue - s.info.minValue;
  tbb::parallel_for(0, slabs, [&](int i) {
    const VoxelBox box{{0, 0, i * slabDepth}, {d.x, d.y, std::min(d.z, (i + 1) * slabDepth)}};
    std::vector<float> values(box.count());
    source.read(box, values.data());
    Partial& p = partials[i];
    p.histogram.assign(bins, 0);
    for (float v : values) {
      const int bin = span > 0.0f ? std::clamp(int((v - lo) / span * float(bins)), 0, bins - 1) : 0;
      ++p.histogram[bin];
      p.zeros += v == 0.0f;
      p.atMinimum += v == lo;
      p.sum += v;
    }
  });
  s.histogram.assign(bins, 0);
  double sum = 0.0;
  for (const Partial& p : partials) {
    for (int b = 0; b < bins; ++b) s.histogram[b] += p.histogram[b];
    s.zeros += p.zeros;
    s.atMinimum += p.atMinimum;
    sum += p.sum;
  }
  s.mean = s.voxels ? sum / double(s.voxels) : 0.0;
  return s;
}

std::string formatSummary(const VolumeSummary& s) {
  const VolumeInfo& i = s.info;
  const glm::vec3 extent = i.worldMax();
  std::string out;
  out += "volume      " + i.name + "\n";
  out += "dimensions  " + std::to_string(i.dims.x) + " x " + std::to_string(i.dims.y) + " x " + std::to_string(i.dims.z) +
         " (" + std::to_string(s.voxels) + " voxels)\n";
  out += "type        " + i.type + "\n";
  out += "spacing     " + number(i.spacing.x) + " " + number(i.spacing.y) + " " + number(i.spacing.z) + " (extent " +
         number(extent.x) + " x " + number(extent.y) + " x " + number(extent.z) + ")\n";
  out += "range       " + number(i.minValue) + " .. " + number(i.maxValue) + " (mean " + number(s.mean) + ")\n";
  if (i.nonFinite > 0) out += "non-finite  " + std::to_string(i.nonFinite) + " NaN/Inf voxels, read as the minimum\n";
  out += "at minimum  " + percent(s.atMinimum, s.voxels) + " of voxels; exactly 0: " + percent(s.zeros, s.voxels) + "\n";
  out += "memory      " + formatBytes(s.storedBytes) + " as stored; " + formatBytes(s.brickBytes) +
         " in bricks with gradients (" + std::to_string(s.bytesPerVoxel) + " bytes per voxel" +
         (s.bytesPerVoxel == 8 ? ", compact 16-bit storage" : "") + ")\n";
  if (!i.preset.empty()) out += "preset      " + i.preset + "\n";
  out += "histogram   " + std::to_string(s.histogram.size()) + " bins over the range\n";
  const std::uint64_t peak = std::max<std::uint64_t>(1, *std::max_element(s.histogram.begin(), s.histogram.end()));
  const double width = double(i.maxValue - i.minValue) / double(s.histogram.size());
  for (std::size_t b = 0; b < s.histogram.size(); ++b) {
    char line[160];
    const int bar = int(40.0 * double(s.histogram[b]) / double(peak) + 0.5);
    std::snprintf(line, sizeof line, "  %12.6g .. %-12.6g %8s %s\n", double(i.minValue) + width * double(b),
                  double(i.minValue) + width * double(b + 1), percent(s.histogram[b], s.voxels).c_str(),
                  std::string(std::size_t(bar), '#').c_str());
    out += line;
  }
  return out;
}

nlohmann::json summaryToJson(const VolumeSummary& s) {
  const VolumeInfo& i = s.info;
  nlohmann::json edges = nlohmann::json::array();
  for (std::size_t b = 0; b <= s.histogram.size(); ++b)
    edges.push_back(double(i.minValue) + double(i.maxValue - i.minValue) * double(b) / double(s.histogram.size()));
  const double n = s.voxels ? double(s.voxels) : 1.0;
  return {
      {"name", i.name},
      {"dims", {i.dims.x, i.dims.y, i.dims.z}},
      {"type", i.type},
      {"spacing", {i.spacing.x, i.spacing.y, i.spacing.z}},
      {"range", {i.minValue, i.maxValue}},
      {"nonFinite", i.nonFinite},
      {"voxels", s.voxels},
      {"mean", s.mean},
      {"zeroFraction", double(s.zeros) / n},
      {"minFraction", double(s.atMinimum) / n},
      {"histogram", {{"edges", edges}, {"counts", s.histogram}}},
      {"bytes", {{"stored", s.storedBytes}, {"bricks", s.brickBytes}}},
      {"preset", i.preset},
  };
}

}  // namespace kdswap
