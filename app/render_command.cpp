// `kdswap render`: one frame on P virtual nodes; image, Figure-6 stages, stats, verification.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <optional>

#include <unistd.h>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/frame_progress.h"
#include "app/output_files.h"
#include "app/scene_options.h"
#include "core/animation/progress_meter.h"
#include "core/cluster/lattice_passes.h"
#include "core/cluster/phase_grid.h"
#include "core/image/image_average.h"
#include "core/image/image_io.h"
#include "core/render/reference_render.h"
#include "core/util/error.h"
#include "core/util/file_writer.h"

namespace kdswap {
namespace {

struct RenderOptions {
  SceneOptions scene;
  std::string out = "render.png";
  std::string stats;
  std::string phases;
  std::string phasesDir;
  std::string background = "0,0,0";
  int passes = 1;
  bool verify = false;
  bool quiet = false;
};

constexpr float kVerifyTolerance = 1e-5f;

ImageWriteOptions parseBackground(const std::string& text) {
  ImageWriteOptions w;
  if (text == "none") {
    w.background.reset();
    return w;
  }
  const std::string expected = "--background \"" + text + "\": expected R,G,B in [0,1] or none";
  std::vector<double> rgb;
  try {
    rgb = parseNumbers(text, ',', "--background");  // refuses nan and inf, which sscanf's %f reads
  } catch (const Error&) {
    throw Error(expected);
  }
  if (rgb.size() != 3) throw Error(expected);
  for (double c : rgb)
    if (!(c >= 0.0 && c <= 1.0)) throw Error(expected);
  w.background = glm::vec3(float(rgb[0]), float(rgb[1]), float(rgb[2]));
  return w;
}

// The extensions isSupportedImagePath accepts, as writeImage's message lists them.
constexpr const char* kImageExtensions = ".png, .exr, .tif, .tiff or .jpg";

void checkImageExtension(const std::string& path, const char* option) {
  if (!isSupportedImagePath(path))
    throw Error(std::string(option) + " " + path + ": unsupported image extension (expected " + kImageExtensions + ")");
}

//! JPEG has no alpha channel: "--background none" would be dropped without a word.
void checkBackgroundFits(const ImageWriteOptions& w, const std::string& out) {
  if (!w.background && !imageFormatHasAlpha(out))
    throw Error("--background none: " + out + " is a JPEG, which has no alpha channel; write .png, .tif or .exr "
                "for a transparent background, or give a colour");
}

void writeStats(const std::string& path, const nlohmann::json& j) { writeFileAtomically(path, j.dump(2) + "\n"); }

void run(const RenderOptions& o) {
  checkImageExtension(o.out, "--out");
  if (!o.phases.empty()) checkImageExtension(o.phases, "--phases");
  checkOutputFiles({{"--out", o.out}, {"--stats", o.stats}, {"--phases", o.phases}},
                   {o.scene.volume, existingFileOrEmpty(o.scene.tf)});
  if (!o.phasesDir.empty()) checkOutputFolder(o.phasesDir, "--phases-dir");
  const ImageWriteOptions writeOptions = parseBackground(o.background);
  checkBackgroundFits(writeOptions, o.out);
  Scene scene = buildScene(o.scene);
  scene.request.recordPhases = !o.phases.empty() || !o.phasesDir.empty();

  VirtualCluster cluster(*scene.source, scene.cluster);
  if (scene.fault.armed()) cluster.injectFault(scene.fault);
  // Pass i samples the lattice shifted by latticePassShift(i); the image is the passes' mean. The
  // table, stats and stages are the first pass's (an ordinary frame).
  PassesResult passes;
  if (o.passes == 1) {
    const FrameProgress progress(cluster, !o.quiet);
    passes = renderPasses(cluster, scene.request, 1);
  } else {
    // Passes done, on a terminal (as a long frame's progress: not in logs, not with --quiet).
    std::optional<ProgressMeter> meter;
    if (!o.quiet && ::isatty(fileno(stderr))) meter.emplace(stderr, true, o.passes, 0, "pass", "passes");
    passes = renderPasses(cluster, scene.request, o.passes, [&](int, const FrameResult&, const ImageAverage&) {
      if (meter) meter->frameDone();
      return true;
    });
    if (meter) meter->finish();
  }
  const FrameResult& frame = passes.frame;
  const Image& image = frame.image;
  const double passesWall = passes.wallSeconds;
  writeImage(o.out, image, writeOptions);
  if (!o.quiet) std::printf("%s", formatFrameTable(frame.stats).c_str());
  if (!o.quiet && o.passes > 1)
    std::printf("  %d passes averaged, lattice shifted by the R1 sequence; wall %.2f s in all (the table: pass 1)\n",
                o.passes, passesWall);
  if (!o.quiet) std::printf("wrote %s\n", o.out.c_str());
  if (frame.phases) {
    if (!o.phases.empty()) {
      writeImage(o.phases, drawPhaseGrid(*frame.phases, frame.image));
      if (!o.quiet) std::printf("wrote %s (compositing stages: %zu nodes x %d phases)\n", o.phases.c_str(),
                                frame.phases->cells.size(), frame.phases->phaseCount());
    }
    if (!o.phasesDir.empty()) {
      writePhaseCells(o.phasesDir, *frame.phases, frame.image);
      if (!o.quiet) std::printf("wrote the stages as PNG files in %s\n", o.phasesDir.c_str());
    }
  }

  nlohmann::json stats = frame.stats.toJson();
  if (o.passes > 1) stats["passes"] = {{"count", o.passes}, {"wall_s", passesWall}};
  bool verified = true;
  if (o.verify) {
    // The single-node reference of every pass, averaged as the passes are.
    const Brick whole = wholeVolumeBrick(*scene.source, Brick::kCellShiftByVolume, scene.cluster.voxels);
    const Image reference = referencePasses(whole, scene.request,
                                            resolveValueRange(scene.request.settings, scene.source->info()), o.passes);
    const float diff = maxAbsDifference(image, reference, image.rect());
    // Early ray termination is local to each brick, so below a threshold of 1 a distributed ray
    // may keep up to (1 - threshold) more light than the whole ray: that is the bound then.
    const float ert = scene.request.settings.earlyTermination;
    const float tolerance = ert < 1.0f ? kVerifyTolerance + (1.0f - ert) : kVerifyTolerance;
    verified = diff <= tolerance;
    stats["verify"] = {{"max_abs_diff", diff}, {"tolerance", tolerance}, {"passed", verified}};
    std::printf("verify: max |distributed - single node| = %.4g (tolerance %.4g%s): %s\n", diff, tolerance,
                ert < 1.0f ? ", early ray termination on; --ert 1 for the exact 1e-5 check" : "",
                verified ? "OK" : "FAILED");
  }
  if (!o.stats.empty()) writeStats(o.stats, stats);
  if (!verified) throw CommandExit{1};
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render one frame on P virtual nodes and write the image");
  cmd->footer(
      "Examples:\n"
      "  kdswap render --out head.png\n"
      "  kdswap render --nodes 8 --phases stages.png --out head.png --stats frame.json\n"
      "  kdswap render --passes 16 --size 1024x1024 --out still.png\n"
      "  kdswap render --volume ../shared/data/cthead.nhdr --up -z --tf ct-bone --nodes 16 --verify\n");
  addSceneOptions(cmd, options->scene);
  addClusterOptions(cmd, options->scene);
  cmd->add_option("--out,-o", options->out,
                  std::string("Output image, by extension: ") + kImageExtensions +
                      " (.exr: float RGBA; the others 8-bit, over --background)")
      ->check(nonEmpty())
      ->capture_default_str();
  cmd->add_option("--background", options->background, "Background R,G,B in [0,1] for 8-bit images, or none for RGBA")
      ->check(nonEmpty())
      ->capture_default_str();
  cmd->add_option("--stats", options->stats, "Write the frame's figures as JSON (stable keys, see README)")->check(nonEmpty());
  cmd->add_option("--phases", options->phases, "Write the compositing stages as one picture (paper Figure 6)")
      ->check(nonEmpty());
  cmd->add_option("--phases-dir", options->phasesDir, "Write every stage of every node as its own PNG in DIR")
      ->check(nonEmpty());
  cmd->add_option("--passes", options->passes,
                  "Average N frames whose sampling lattices are shifted (R1 sequence) against rings and grain: "
                  "a still image's quality for N times the time")
      ->check(CLI::Range(1, kMaxLatticePasses))
      ->capture_default_str();
  cmd->add_flag("--verify", options->verify,
                "Also render the single-node reference; exit 1 if they differ by more than 1e-5 (plus the "
                "early-termination bound when --ert < 1)");
  cmd->add_flag("--quiet,-q", options->quiet, "Print nothing but errors and the verify line");
  cmd->callback([options] { run(*options); });
}

}  // namespace kdswap
