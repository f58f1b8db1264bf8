// `kdswap info`: describe a volume file or built-in data set (dims, type, spacing, range,
// histogram, memory), as text or JSON. The numbers come from core/volume/volume_summary.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/scene_options.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"
#include "core/volume/volume_summary.h"

namespace kdswap {
namespace {

struct InfoOptions {
  std::string file, dataset;
  std::string rawDims, rawType, rawEndian, rawSpacing;
  std::int64_t rawSkip = 0;  // signed, so that -1 is refused rather than wrapped
  int bins = 16;
  bool json = false;
};

std::vector<double> numbers(const std::string& text, char separator, const std::string& option, const char* expected) {
  std::vector<double> values;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, separator)) {
    std::size_t used = 0;
    double v = 0.0;
    try {
      v = std::stod(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || !std::isfinite(v))
      throw Error(option + " \"" + text + "\": expected " + expected);
    values.push_back(v);
  }
  return values;
}

RawLayout rawLayout(const InfoOptions& o) {
  RawLayout layout;
  if (!o.rawDims.empty()) {
    const auto d = numbers(o.rawDims, 'x', "--raw-dims", "WxHxD");
    if (d.size() != 3) throw Error("--raw-dims \"" + o.rawDims + "\": expected WxHxD");
    for (double v : d)
      if (v < 2 || v > 1e6 || v != std::floor(v))
        throw Error("--raw-dims \"" + o.rawDims + "\": each size must be a whole number from 2 to 1000000");
    layout.dims = glm::ivec3(int(d[0]), int(d[1]), int(d[2]));
  }
  if (!o.rawType.empty()) layout.type = o.rawType;
  if (!o.rawEndian.empty()) {
    if (o.rawEndian != "little" && o.rawEndian != "big")
      throw Error("--raw-endian \"" + o.rawEndian + "\": expected little or big");
    layout.bigEndian = o.rawEndian == "big";
  }
  if (!o.rawSpacing.empty()) {
    const auto s = numbers(o.rawSpacing, ',', "--raw-spacing", "SX,SY,SZ");
    if (s.size() != 3) throw Error("--raw-spacing \"" + o.rawSpacing + "\": expected SX,SY,SZ");
    layout.spacing = glm::vec3(float(s[0]), float(s[1]), float(s[2]));
  }
  if (o.rawSkip < 0) throw Error("--raw-skip " + std::to_string(o.rawSkip) + ": expected a number of bytes >= 0");
  layout.headerBytes = std::uint64_t(o.rawSkip);
  layout.rawOptions = true;
  return layout;
}

void runInfo(const InfoOptions& o) {
  if (o.file.empty() == o.dataset.empty()) throw Error("info: give either a volume FILE or --dataset NAME[:SIZE]");
  if (o.bins < 1 || o.bins > 1024) throw Error("--bins " + std::to_string(o.bins) + ": expected 1 to 1024");
  // The --raw-* options describe a file: with a data set they would be silently ignored.
  if (!o.dataset.empty())
    for (const auto& [option, given] : {std::pair{"--raw-dims", !o.rawDims.empty()}, {"--raw-type", !o.rawType.empty()},
                                        {"--raw-endian", !o.rawEndian.empty()}, {"--raw-spacing", !o.rawSpacing.empty()},
                                        {"--raw-skip", o.rawSkip != 0}})
      if (given) throw Error(std::string(option) + " describes a raw volume file; it does not apply to --dataset " + o.dataset);
  const std::unique_ptr<VolumeSource> source = o.file.empty() ? openDataset(o.dataset) : openVolumeFile(o.file, rawLayout(o));
  const VolumeSummary summary = summarizeVolume(*source, o.bins);
  if (o.json)
    std::printf("%s\n", summaryToJson(summary).dump(2).c_str());
  else
    std::printf("%s", formatSummary(summary).c_str());
}

}  // namespace

void addInfoCommand(CLI::App& app) {
  auto options = std::make_shared<InfoOptions>();
  CLI::App* cmd = app.add_subcommand(
      "info", "Describe a volume: dimensions, type, spacing, value range, histogram, memory for bricks");
  // Positional or --volume, as every other subcommand names its volume.
  cmd->add_option("file,--volume", options->file,
                  "Volume file (positional or --volume FILE): .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, legacy .vtk, or .raw "
                  "(layout from --raw-* or a name like head_256x256x113_uint16.raw)")
      ->check(nonEmpty());
  cmd->add_option("--dataset", options->dataset, "Built-in data set NAME[:N|:WxHxD] instead of a file, e.g. phantom:64")
      ->check(nonEmpty());
  cmd->add_option("--raw-dims", options->rawDims, "Raw files: dimensions WxHxD");
  cmd->add_option("--raw-type", options->rawType, "Raw files: int8 uint8 int16 uint16 int32 uint32 float32 float64");
  cmd->add_option("--raw-endian", options->rawEndian, "Raw files: little (default) or big");
  cmd->add_option("--raw-spacing", options->rawSpacing, "Raw files: voxel spacing SX,SY,SZ");
  cmd->add_option("--raw-skip", options->rawSkip, "Raw files: header bytes to skip")
      ->check(wholeNumber(std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()));
  cmd->add_option("--bins", options->bins, "Histogram bins, 1..1024")->check(wholeNumber())->capture_default_str();
  cmd->add_flag("--json", options->json, "Print JSON: dims, type, spacing, range, histogram, bytes");
  cmd->callback([options] { runInfo(*options); });
}

}  // namespace kdswap
