// `kdswap info`: describe a volume file or built-in data set (dims, type, spacing, range,
// histogram, memory), as text or JSON. The numbers come from core/volume/volume_summary.
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/raw_layout_options.h"
#include "app/scene_options.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"
#include "core/volume/volume_summary.h"

namespace kdswap {
namespace {

struct InfoOptions {
  std::string file, dataset;
  RawLayoutOptions raw;
  int bins = 16;
  bool json = false;
};

void runInfo(const InfoOptions& o) {
  if (o.file.empty() == o.dataset.empty()) throw Error("info: give either a volume FILE or --dataset NAME[:SIZE]");
  if (o.bins < 1 || o.bins > 1024) throw Error("--bins " + std::to_string(o.bins) + ": expected 1 to 1024");
  if (!o.dataset.empty()) checkNoRawLayout(o.raw, "--dataset " + o.dataset);
  const std::unique_ptr<VolumeSource> source =
      o.file.empty() ? openDatasetOption(o.dataset) : openVolumeFile(o.file, parseRawLayout(o.raw));
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
  addRawLayoutOptions(cmd, options->raw);
  cmd->add_option("--bins", options->bins, "Histogram bins, 1..1024")->check(wholeNumber())->capture_default_str();
  cmd->add_flag("--json", options->json, "Print JSON: dims, type, spacing, range, histogram, bytes");
  cmd->callback([options] { runInfo(*options); });
}

}  // namespace kdswap
