// `kdswap export`: write a built-in data set or a volume file as one .nrrd file, optionally
// quantised to 8 or 16 bits, so other renderers (VTK, ParaView) can be run on the same voxels.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "app/commands.h"
#include "app/output_files.h"
#include "app/raw_layout_options.h"
#include "app/scene_options.h"
#include "core/bench/quantised_source.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"
#include "core/volume/respaced_source.h"
#include "core/volume/writers/nrrd_writer.h"

namespace kdswap {
namespace {

struct ExportOptions {
  std::string dataset, volume, spacing, type, out;
  RawLayoutOptions raw;
  int quantise = 0;
};

void runExport(const ExportOptions& o) {
  if (o.volume.empty() == o.dataset.empty()) throw Error("export: give either --dataset NAME[:SIZE] or --volume FILE");
  if (o.quantise != 0 && o.quantise != 8 && o.quantise != 16) throw Error("--quantise must be 0, 8 or 16");
  if (o.out.size() < 6 || o.out.compare(o.out.size() - 5, 5, ".nrrd") != 0)
    throw Error("--out \"" + o.out + "\": expected a file name ending in .nrrd");
  // 8-bit samples cannot keep 16-bit levels: one of the two options would be silently ignored.
  if (o.quantise == 16 && o.type == "uint8")
    throw Error("--type uint8 cannot hold --quantise 16's levels; use --type uint16 or float32, or --quantise 8");
  if (!o.dataset.empty()) checkNoRawLayout(o.raw, "--dataset " + o.dataset);
  const RawLayout layout = parseRawLayout(o.raw);
  checkOutputFiles({{"--out", o.out}}, {});  // the input may be replaced: the file is written beside it, then renamed
  std::unique_ptr<VolumeSource> source =
      o.volume.empty() ? openDatasetOption(o.dataset) : openVolumeFile(o.volume, layout);
  if (!o.spacing.empty()) source = std::make_unique<RespacedSource>(std::move(source), parseSpacing(o.spacing, "--spacing"));
  if (o.quantise) source = std::make_unique<QuantisedSource>(std::move(source), o.quantise);
  // Default type: the quantised width (exact: the values are those levels), else float32 (exact
  // for every source, whatever it stores).
  const std::string type = !o.type.empty() ? o.type
                           : o.quantise == 8 ? "uint8"
                           : o.quantise == 16 ? "uint16"
                                              : "float32";
  const NrrdSample sample = parseNrrdSample(type, "--type");
  const VolumeInfo& info = source->info();
  static const bool tty = isatty(2);
  const NrrdWritten written = writeNrrd(o.out, *source, sample, [&](int done, int total) {
    if (tty && (done % 16 == 0 || done == total)) std::fprintf(stderr, "\rexport: slice %d of %d", done, total);
  });
  if (tty) std::fprintf(stderr, "\n");
  std::printf("wrote %s (%d x %d x %d %s, spacing %g %g %g, values %g .. %g)\n", o.out.c_str(), info.dims.x, info.dims.y,
              info.dims.z, type.c_str(), double(info.spacing.x), double(info.spacing.y), double(info.spacing.z),
              double(info.minValue), double(info.maxValue));
  // A built-in data set declares its range (0 .. 1) and is rendered over it; a file's range is
  // what its voxels span. Where the two differ the same transfer function would map differently.
  if (written.voxelMin != written.rangeMin || written.voxelMax != written.rangeMax)
    std::printf("note: the voxels span %g .. %g of the range %g .. %g that %s is rendered over; render this "
                "file with --range %g,%g for the same picture\n",
                double(written.voxelMin), double(written.voxelMax), double(written.rangeMin),
                double(written.rangeMax), info.name.c_str(), double(written.rangeMin), double(written.rangeMax));
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto options = std::make_shared<ExportOptions>();
  CLI::App* cmd = app.add_subcommand("export", "Write a data set or volume as a .nrrd file (to open it in other tools)");
  cmd->add_option("--dataset", options->dataset, "Built-in data set NAME[:N|:WxHxD], e.g. phantom:256")->check(nonEmpty());
  cmd->add_option("--volume", options->volume,
                  "Volume file instead of a data set: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, legacy .vtk, or .raw "
                  "(layout from --raw-* or a name like head_256x256x113_uint16.raw)")
      ->check(nonEmpty());
  addRawLayoutOptions(cmd, options->raw);
  cmd->add_option("--spacing", options->spacing, "Voxel spacing SX,SY,SZ instead of the data's")->check(nonEmpty());
  cmd->add_option("--quantise", options->quantise, "Round the data to 8 or 16 bits first (0: as stored)")
      ->capture_default_str();
  cmd->add_option("--type", options->type,
                  "Sample type: float32, uint8 or uint16 (levels of the value range, kept as 'old min/max'); "
                  "default: the --quantise width, else float32 (uint8 with --quantise 16 is refused)")
      ->check(nonEmpty());
  cmd->add_option("-o,--out", options->out, "Output file (.nrrd, raw data attached; may be the input file, replaced when complete)")
      ->required()
      ->check(nonEmpty());
  cmd->footer(
      "Examples:\n"
      "  kdswap export --dataset phantom:256 --quantise 8 --out phantom256.nrrd\n"
      "  kdswap export --dataset turbulence:256 --quantise 16 --out turbulence256.nrrd\n"
      "  kdswap export --volume scan.raw --raw-dims 256x256x113 --raw-type uint16 --raw-endian big --out scan.nrrd");
  cmd->callback([options] { runExport(*options); });
}

}  // namespace kdswap
