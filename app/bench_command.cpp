// `kdswap bench`: the paper's timing tables over a grid, kernel micro benchmarks (--micro), the
// paper comparison (--paper) and issue 6's speed targets (--targets). Ctrl-C keeps the results.
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <optional>

#include <nlohmann/json.hpp>

#include "app/commands.h"
#include "app/raw_layout_options.h"
#include "app/scene_options.h"
#include "core/bench/bench_grid.h"
#include "core/bench/bench_report.h"
#include "core/bench/machine_info.h"
#include "core/bench/micro_bench.h"
#include "core/bench/paper_comparison.h"
#include "core/bench/quantised_source.h"
#include "core/volume/respaced_source.h"
#include "core/bench/speed_targets.h"
#include "core/bench/speedup_chart.h"
#include "core/cluster/front_to_back_waves.h"
#include "core/image/image_io.h"
#include "core/transfer/presets.h"
#include "core/util/text_items.h"
#include "core/util/error.h"
#include "core/util/file_writer.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"

namespace kdswap {
namespace {

struct BenchOptions {
  std::string dataset, volume, spacing, sizes = "64,128,256,512", nodes = "1,2,4,8,16,32,64,128,256,512";
  std::string composite = "binary-swap", tf, shading = "on", partition = "kd", outDir = "bench-out";
  std::string head = "../shared/data/headsq.nhdr", view = "30,15";
  std::string vtkMs;
  RawLayoutOptions raw;  //!< --raw-*, with --volume only
  int repeat = 1;
  std::string balance = "space", speeds, network = "ideal", bricksPerNode = "1", voxels = "auto";
  int frames = 5, quantise = 0, threads = 0;
  float step = 0.5f, degrees = 1.0f, ert = 0.99f, distance = kBenchViewDistance;
  bool sparse = false, waves = false, interleave = false, micro = false, paper = false, targets = false;
  bool headGiven = false;  //!< --head on the command line: then it must exist (the default may be absent)
  std::string gridOption;  //!< the first grid-only option given (--dataset, --sizes, ...), or ""
  bool framesGiven = false;
};

// Set by SIGINT; polled after every frame (lock-free atomic: safe in a signal handler).
std::atomic<bool> gStop{false};
void onBenchInterrupt(int) { gStop.store(true); }

template <typename T>
std::vector<T> parseList(const std::string& text, const char* option, T lo, T hi) {
  std::vector<T> out;
  for (const std::string& item : splitItems(text, ',')) {
    const std::optional<std::int64_t> v = parseWholeNumber(item);
    if (!v || *v < lo || *v > hi)
      throw Error(std::string(option) + " \"" + text + "\": \"" + item + "\" is not a whole number from " +
                  std::to_string(lo) + " to " + std::to_string(hi));
    out.push_back(T(*v));
  }
  if (out.empty()) throw Error(std::string(option) + ": empty list");
  return out;
}

std::vector<std::string> parseNames(const std::string& text, const char* option) {
  std::vector<std::string> out = splitItems(text, ',');
  if (out.empty()) throw Error(std::string(option) + ": empty list");
  for (const std::string& name : out)
    if (name.empty()) throw Error(std::string(option) + " \"" + text + "\": empty item (a ',' too many)");
  return out;
}

bool stderrIsTerminal() {
  static const bool tty = isatty(2);
  return tty;
}

// A terminal shows one line rewritten after every frame; a log (a file, CI) gets a line when a
// cell starts and when it ends, not one per frame. Interleaved runs change cell every frame: there
// a log gets a line when cells end and otherwise at most one every 5 s.
void progressLine(const BenchProgress& p) {
  const bool tty = stderrIsTerminal();
  static int lastDone = -1;
  static std::string lastCurrent;
  static double lastLine = -1e9;
  const bool sameCell = p.current == lastCurrent || (p.interleaved && p.elapsedSeconds - lastLine < 5.0);
  if (!tty && p.cellsDone == lastDone && sameCell) return;
  lastDone = p.cellsDone;
  lastCurrent = p.current;
  lastLine = p.elapsedSeconds;
  std::fprintf(stderr, "%s[%d/%d cells] %-32s %5.0f s elapsed, about %.0f s left%s", tty ? "\r" : "", p.cellsDone,
               p.cellsTotal, p.current.c_str(), p.elapsedSeconds, p.remainingSeconds, tty ? "   " : "\n");
}

std::string commandLine(const BenchOptions& o) {
  std::string c = "kdswap bench " + (o.volume.empty() ? "--dataset " + (o.dataset.empty() ? std::string(kDefaultDataset) : o.dataset)
                                                      : "--volume " + o.volume + rawLayoutArguments(o.raw));
  if (!o.spacing.empty()) c += " --spacing " + o.spacing;
  if (o.quantise) c += " --quantise " + std::to_string(o.quantise);
  char buf[512];
  std::snprintf(buf, sizeof buf, " --sizes %s --nodes %s --composite %s --frames %d --degrees %g --step %g --shading %s --ert %g --view %s --distance %g --partition %s%s --threads %d",
                o.sizes.c_str(), o.nodes.c_str(), o.composite.c_str(), o.frames, double(o.degrees), double(o.step),
                o.shading.c_str(), double(o.ert), o.view.c_str(), double(o.distance), o.partition.c_str(), o.sparse ? " --sparse" : "",
                o.threads);
  if (o.waves) c += " --waves";
  if (o.interleave) c += " --interleave";
  return c + buf + (o.tf.empty() ? "" : " --tf " + o.tf) + " --balance " + o.balance +
         (o.speeds.empty() ? "" : " --speeds " + o.speeds) + " --bricks-per-node " + o.bricksPerNode +
         " --network " + o.network + " --voxels " + o.voxels + " --out-dir " + o.outDir;
}

void runGrid(const BenchOptions& o, const MachineInfo& machine) {
  if (!o.volume.empty() && !o.dataset.empty()) throw Error("give either --volume or --dataset, not both");
  // Every option is checked (with render's checks, app/scene_options.h) before the volume is
  // opened or any cell runs.
  BenchGridOptions g;
  g.sizes = parseList<int>(o.sizes, "--sizes", 1, 16384);
  g.nodes = parseList<int>(o.nodes, "--nodes", 1, kMaxNodes);
  g.strategies = parseNames(o.composite, "--composite");
  for (const std::string& s : g.strategies) checkStrategyName(s);  // unknown names fail before any work
  g.frames = o.frames;
  if (!std::isfinite(o.degrees) || std::abs(o.degrees) > 360.0f)
    throw Error("--degrees must be a number from -360 to 360");
  g.degreesPerFrame = o.degrees;
  const glm::vec2 view = parseViewAngles(o.view, "--view");
  g.base.view.azimuthDeg = view.x, g.base.view.elevationDeg = view.y;
  checkDistance(o.distance);
  g.base.view.distance = o.distance;
  checkStep(o.step);
  checkErt(o.ert);
  g.base.settings.stepVoxels = o.step;
  g.base.settings.shading = parseOnOff(o.shading, "--shading");
  g.base.settings.earlyTermination = o.ert;
  g.base.settings.frontToBackWaves = o.waves;
  g.interleave = o.interleave;
  g.cluster.partition = parsePartition(o.partition, "--partition");
  g.cluster.composite.sparse = o.sparse;
  checkThreads(o.threads);
  g.cluster.threads = o.threads;
  g.cluster.network = networkModel(o.network);
  g.cluster.voxels = parseVoxelChoice(o.voxels);
  g.balances = parseNames(o.balance, "--balance");
  g.bricksPerNode = parseList<int>(o.bricksPerNode, "--bricks-per-node", 1, 64);
  for (int m : g.bricksPerNode) checkWavesWithBricksPerNode(o.waves, m);
  for (const std::string& b : g.balances)
    if (b != "space" && b != "cost") throw Error("--balance \"" + o.balance + "\": expected space, cost or space,cost");
  g.speedPattern = parseSpeeds(o.speeds);
  checkOutputFolder(o.outDir, "--out-dir");
  std::optional<TransferFunction> transfer;
  if (!o.tf.empty()) transfer = loadTransferOption(o.tf);
  std::optional<glm::vec3> spacing;
  if (!o.spacing.empty()) spacing = parseSpacing(o.spacing, "--spacing");
  const std::string dataset = o.dataset.empty() ? kDefaultDataset : o.dataset;
  if (o.volume.empty()) checkNoRawLayout(o.raw, "--dataset " + dataset + (o.dataset.empty() ? " (the default)" : ""));
  const RawLayout layout = parseRawLayout(o.raw);

  std::unique_ptr<VolumeSource> source =
      o.volume.empty() ? openDatasetOption(dataset) : openVolumeFile(o.volume, layout);
  if (spacing) source = std::make_unique<RespacedSource>(std::move(source), *spacing);
  if (o.quantise) source = std::make_unique<QuantisedSource>(std::move(source), o.quantise);
  const VolumeInfo& info = source->info();
  g.base.transfer = transfer ? *transfer : loadTransferFunction(info.preset.empty() ? "grayscale" : info.preset);
  std::error_code ec;
  std::filesystem::create_directories(o.outDir, ec);
  if (ec) throw Error("--out-dir " + o.outDir + ": cannot create the folder (" + ec.message() + ")");

  const BenchResult result = runBenchGrid(*source, g, progressLine, &gStop);
  if (stderrIsTerminal()) std::fprintf(stderr, "\n");  // ends the rewritten line
  const VoxelStorage storage = VoxelStorage::forVolume(info, g.cluster.voxels);
  BenchContext ctx{commandLine(o), o.volume.empty() ? dataset : o.volume,
                   info.type, {info.dims.x, info.dims.y, info.dims.z}, o.step, o.shading == "on", o.frames, o.degrees,
                   storage.compactFormat() ? "compact" : "float", o.distance, o.interleave, machine};
  std::printf("%s", formatMachine(machine).c_str());
  std::printf("%s (%dx%dx%d %s, %s voxels), step %g, shading %s, eye at %g radii, median of %d frames turning %g "
              "deg/frame%s\n\n",
              ctx.dataset.c_str(), info.dims.x, info.dims.y, info.dims.z, info.type.c_str(), ctx.voxels.c_str(),
              double(o.step), o.shading.c_str(), double(o.distance), o.frames, double(o.degrees),
              o.interleave ? ", cells interleaved frame by frame" : "");
  std::printf("%s%s", formatPaperLayout(result.cells).c_str(), formatCellDetails(result.cells).c_str());
  const std::filesystem::path dir(o.outDir);
  writeFileAtomically((dir / "bench.csv").string(), benchCsv(ctx, result.cells));
  writeFileAtomically((dir / "bench.json").string(), benchJson(ctx, result).dump(2) + "\n");
  std::printf("wrote %s and %s\n", (dir / "bench.csv").c_str(), (dir / "bench.json").c_str());
  // One chart per measured strategy label ("binary-swap", "binary-swap+cost", ...), in run order.
  std::vector<std::string> labels;
  for (const BenchCell& c : result.cells)
    if (std::find(labels.begin(), labels.end(), c.strategy) == labels.end()) labels.push_back(c.strategy);
  for (std::size_t i = 0; i < labels.size(); ++i) {
    const std::string name = i == 0 ? "speedup.png" : "speedup-" + labels[i] + ".png";
    writeImage((dir / name).string(), drawSpeedupChart(result.cells, labels[i]));
    std::printf("wrote %s (modelled speedup, %s)\n", (dir / name).c_str(), labels[i].c_str());
  }
  if (result.interrupted) {
    std::fprintf(stderr, "kdswap bench: interrupted; kept the %zu cells measured so far\n", result.cells.size());
    throw CommandExit{130};
  }
}

void run(const BenchOptions& o) {
  if (o.frames < 1 || o.frames > 1000) throw Error("--frames must be from 1 to 1000");
  if (o.quantise != 0 && o.quantise != 8 && o.quantise != 16) throw Error("--quantise must be 0, 8 or 16");
  if (int(o.micro) + int(o.paper) + int(o.targets) > 1) throw Error("give at most one of --micro, --paper, --targets");
  if (!o.vtkMs.empty() && !o.targets) throw Error("--vtk-ms goes with --targets");
  if (o.repeat != 1 && !o.targets) throw Error("--repeat goes with --targets");
  if (o.headGiven && !o.targets) throw Error("--head goes with --targets");
  if (o.waves && (o.micro || o.targets))
    throw Error(std::string("--waves goes with a grid run or --paper; ") +
                (o.micro ? "--micro times kernels alone" : "--targets measures each scene with and without waves itself"));
  if (o.repeat < 1 || o.repeat > 20) throw Error("--repeat must be from 1 to 20");
  // These modes run fixed cells on their own data sets: the grid's options would be silently ignored.
  if (o.micro || o.paper || o.targets) {
    const std::string mode = o.micro ? "--micro" : o.paper ? "--paper" : "--targets";
    checkNoRawLayout(o.raw, mode);
    if (!o.gridOption.empty())
      throw Error(o.gridOption + " sets up a grid run; " + mode + " runs its own fixed cells (see kdswap bench --help)");
    if (o.micro && o.framesGiven) throw Error("--frames does not apply to --micro (its kernels repeat on their own)");
  }
  gStop.store(false);
  auto previous = std::signal(SIGINT, onBenchInterrupt);
  struct Restore {
    decltype(previous) handler;
    ~Restore() { std::signal(SIGINT, handler); }
  } restore{previous};
  auto log = [](const std::string& line) { std::fprintf(stderr, "bench: %s\n", line.c_str()); };
  // Figures mean little without the machine (Benchmark in README.md): every mode prints it first.
  const MachineInfo machine = describeMachine(o.threads);

  if (o.micro) {
    MicroOptions m;
    log("ray casting on one core ...");
    const auto rays = measureRayCasting(m);
    log("over vs memcpy, 1024x1024 ...");
    const CompositeFigure over = measureOver(1024, 1024, m.compositingRepeats);
    log("binary-swap alone, 1024x1024, P=8 ...");
    const BinarySwapFigure swap = measureBinarySwap(8, 1024, 1024, m.compositingRepeats);
    std::printf("%s%s", formatMachine(machine).c_str(), formatMicro(rays, over, swap, m).c_str());
    std::vector<BinarySwapFigure> strategies;
    for (const CompositingReference& r : compositingReferences()) {
      if (gStop.load()) break;
      log(r.strategy + " alone, 1024x1024, P=" + std::to_string(r.nodes) + " ...");
      strategies.push_back(r.strategy == "binary-swap" && r.nodes == 8 ? swap
                                                                       : measureCompositing(r.strategy, r.nodes, 1024, 1024, m.compositingRepeats));
    }
    std::printf("\n%s", formatCompositingTable(strategies).c_str());
  } else if (o.paper) {
    const std::string comparison = runPaperComparison(o.frames, log, &gStop, o.waves);
    std::printf("%s%s", formatMachine(machine).c_str(), comparison.c_str());
  } else if (o.targets) {
    // The CT head target runs after minutes of others: a wrong --head must fail before them.
    if (o.headGiven) {
      std::error_code ec;
      if (!std::filesystem::is_regular_file(o.head, ec))
        throw Error("--head " + o.head + ": " +
                    (std::filesystem::exists(o.head, ec) ? "not a regular file" : "no such file"));
      openVolumeFile(o.head);  // validates the header: a broken file fails here too
    }
    TargetOptions t;
    t.frames = o.frames;
    t.headPath = o.head;
    // The default is relative to the repository (its data sets lie beside it, in ../shared/data):
    // found from any folder when this build's source tree has it.
    std::error_code ec;
    const std::filesystem::path besideSource = std::filesystem::path(KDSWAP_SOURCE_DIR) / o.head;
    if (!o.headGiven && !std::filesystem::exists(o.head, ec) && std::filesystem::is_regular_file(besideSource, ec))
      t.headPath = besideSource.lexically_normal().string();
    if (!o.vtkMs.empty()) {
      t.vtkMs = parseNumbers(o.vtkMs, ',', "--vtk-ms");
      if (t.vtkMs.size() != 3 ||
          !std::all_of(t.vtkMs.begin(), t.vtkMs.end(), [](double ms) { return ms > 0 && ms < 1e7; }))
        throw Error("--vtk-ms \"" + o.vtkMs + "\": expected three times in ms, TURBULENCE,PHANTOM,CT_HEAD");
    }
    std::vector<std::vector<SpeedTarget>> runs;
    for (int r = 1; r <= o.repeat && !gStop.load(); ++r) {
      if (o.repeat > 1) log("run " + std::to_string(r) + " of " + std::to_string(o.repeat));
      runs.push_back(runSpeedTargets(t, log, &gStop));
    }
    std::printf("%s%s", formatMachine(machine).c_str(), formatSpeedTargets(medianOfRuns(runs)).c_str());
  } else {
    runGrid(o, machine);
    return;
  }
  if (gStop.load()) throw CommandExit{130};
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto o = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand("bench", "Time render and composite over a grid (the paper's Tables 1-8)");
  cmd->footer(
      "Examples:\n"
      "  kdswap bench --dataset phantom:128 --sizes 64,128,256 --nodes 1,2,4,8,16\n"
      "  kdswap bench --dataset turbulence:256 --composite binary-swap,binary-tree --frames 3\n"
      "  kdswap bench --dataset vessels:128 --sizes 256 --nodes 1,8,64 --balance space,cost\n"
      "  kdswap bench --dataset phantom:128 --sizes 256 --nodes 1,8,64 --network ethernet10\n"
      "  kdswap bench --dataset vessels:128 --sizes 256 --nodes 8 --speeds 1,0.25 --bricks-per-node 1,4\n"
      "  kdswap bench --dataset phantom:256 --quantise 8 --sizes 512 --nodes 1,64 --interleave\n"
      "  kdswap bench --volume scan.raw --raw-dims 256x256x113 --raw-type uint16 --sizes 256 --nodes 1,8\n"
      "  kdswap bench --micro      kernels alone: ray casting per core, over vs memcpy, binary-swap\n"
      "  kdswap bench --paper      the paper's sourced cells beside ours (add --waves: with front-to-back waves)\n"
      "  kdswap bench --targets    issue 6's speed targets, MET or MISSED\n"
      "Ctrl-C stops after the current frame and writes what was measured (exit 130).\n");
  cmd->add_option("--dataset", o->dataset,
                  "Built-in data set NAME[:N|:WxHxD]: phantom (head), vessels, turbulence (vorticity)")
      ->check(nonEmpty());
  cmd->add_option("--volume", o->volume,
                  "Volume file instead of a data set: .nrrd/.nhdr, .mhd/.mha, .nii/.nii.gz, legacy .vtk, or .raw "
                  "(layout from --raw-* or a name like head_256x256x113_uint16.raw)")
      ->check(nonEmpty());
  addRawLayoutOptions(cmd, o->raw);
  cmd->add_option("--spacing", o->spacing, "Voxel spacing SX,SY,SZ instead of the data's (e.g. 1,1,1)")->check(nonEmpty());
  cmd->add_option("--quantise", o->quantise, "Round the data to 8 or 16 bits first (0: as stored)")
      ->check(wholeNumber());
  cmd->add_option("--sizes", o->sizes, "Square image sides, comma-separated, each 1..16384")->capture_default_str();
  cmd->add_option("--nodes", o->nodes, "Node counts, comma-separated, each 1..4096")->capture_default_str();
  cmd->add_option("--composite", o->composite, "Strategies, comma-separated")->capture_default_str();
  cmd->add_option("--frames", o->frames, "Measured frames per cell, 1..1000 (one warm-up frame more)")
      ->check(wholeNumber())
      ->capture_default_str();
  cmd->add_option("--degrees", o->degrees, "Azimuth turn per frame, -360..360 degrees")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--view", o->view, "Starting view AZIMUTH,ELEVATION in degrees (azimuth -36000..36000, elevation in (-90, 90))")
      ->capture_default_str();
  cmd->add_option("--distance", o->distance,
                  "Eye distance in bounding-sphere radii, in (0, 1000); closer than render's default 3.4, so the "
                  "volume fills more of the frame, as in the README's figures")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--step", o->step, "Sample spacing in voxels, 0.01..16")->check(number())->capture_default_str();
  cmd->add_option("--shading", o->shading, "on or off")->capture_default_str();
  cmd->add_option("--ert", o->ert, "Early ray termination threshold, in (0, 1] (1 disables)")
      ->check(number())
      ->capture_default_str();
  cmd->add_option("--tf", o->tf, "Transfer function preset or file (default: the data set's)")->check(nonEmpty());
  cmd->add_option("--partition", o->partition, "kd or slab")->capture_default_str();
  cmd->add_flag("--sparse", o->sparse, "Send only bounding rectangles of non-empty pixels");
  cmd->add_flag("--waves", o->waves, "Front-to-back waves: nodes render nearest first, stopping where those in front stopped the light (see kdswap "
                "render --help); cells read STRATEGY+waves. With --paper: the paper's cells with waves");
  cmd->add_flag("--interleave", o->interleave,
                "Measure in rounds, every cell's frame k before any cell's frame k+1, so drift in the machine's speed "
                "hits every cell alike (for comparing cells on a shared machine); each measured frame follows its "
                "cell's previous one, rendered again (twice the frames), and every cell's cluster stays in memory");
  cmd->add_option("--balance", o->balance,
                  "Plane placements to compare: space, cost or space,cost (cost cells read STRATEGY+cost)")
      ->capture_default_str();
  cmd->add_option("--speeds", o->speeds, "Relative node speeds, each 0.01..100, repeated over each cell's nodes, e.g. 1,0.5")
      ->check(nonEmpty());
  cmd->add_option("--bricks-per-node", o->bricksPerNode,
                  "Over-decomposition levels to compare, each 1..64, e.g. 1,4 (cells with M > 1 read STRATEGY+bricksM)")
      ->capture_default_str();
  cmd->add_option("--network", o->network, "Network model for modelled time: ideal, cm5 or ethernet10")
      ->capture_default_str();
  cmd->add_option("--voxels", o->voxels, "Voxel storage: auto (compact above 2^23 voxels), float or compact")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads, 0..1024 (0 = every core)")
      ->check(wholeNumber())
      ->capture_default_str();
  cmd->add_option("--out-dir", o->outDir, "Folder for bench.csv, bench.json, speedup.png")
      ->check(nonEmpty())
      ->capture_default_str();
  cmd->add_flag("--micro", o->micro, "Measure the kernels alone");
  cmd->add_flag("--paper", o->paper, "Run the paper's sourced cells and compare");
  cmd->add_flag("--targets", o->targets, "Measure issue 6's speed targets");
  CLI::Option* head = cmd->add_option("--head", o->head,
                                      "CT head for --targets (must exist when given; the default is relative to "
                                      "the working folder or, failing that, to this build's source tree; "
                                      "where neither has it, that target is not run)")
                           ->check(nonEmpty())
                           ->capture_default_str();
  cmd->add_option("--repeat", o->repeat,
                  "With --targets: run them all N times (1..20) and judge each by the median over the runs "
                  "(this machine's speed drifts between minutes)")
      ->check(wholeNumber())
      ->capture_default_str();
  cmd->add_option("--vtk-ms", o->vtkMs,
                  "With --targets: VTK's times on this machine for turbulence, phantom and CT head "
                  "(scripts/vtk_baseline.py), e.g. 250,110,230; adds 'half of VTK here' targets")
      ->check(nonEmpty());
  // Options that only shape a grid run (--micro, --paper and --targets refuse them).
  const std::vector<CLI::Option*> gridOnly = [cmd] {
    std::vector<CLI::Option*> options;
    for (const char* name : {"--dataset", "--volume", "--spacing", "--quantise", "--sizes", "--nodes", "--composite",
                             "--degrees", "--view", "--distance", "--step", "--shading", "--ert", "--tf", "--partition", "--sparse",
                             "--interleave", "--balance", "--speeds", "--bricks-per-node", "--network", "--voxels", "--threads",
                             "--out-dir"})
      options.push_back(cmd->get_option(name));
    return options;
  }();
  CLI::Option* frames = cmd->get_option("--frames");
  cmd->callback([o, head, gridOnly, frames] {
    o->headGiven = head->count() > 0;
    o->framesGiven = frames->count() > 0;
    o->gridOption.clear();
    for (CLI::Option* option : gridOnly)
      if (option->count() > 0 && o->gridOption.empty()) o->gridOption = option->get_name();
    run(*o);
  });
}

}  // namespace kdswap
