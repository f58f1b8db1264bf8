// Issue 6's speed targets: each measured with the bench grid (one cell) or the micro harness.
#include "core/bench/speed_targets.h"

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "core/bench/bench_grid.h"
#include "core/bench/micro_bench.h"
#include "core/bench/paper_comparison.h"
#include "core/bench/paper_tables.h"
#include "core/bench/quantised_source.h"
#include "core/bench/statistics.h"
#include "core/camera/view.h"
#include "core/volume/respaced_source.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/util/memory.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/reader.h"
#include "core/volume/voxel_storage.h"

namespace kdswap {
namespace {

constexpr double kVoxelBytes = 16.0;  // float value + float3 gradient, per voxel

struct CellSpec {
  int nodes = 64, size = 512;
  float step = 1.0f;
  std::string strategy = "binary-swap";
  //! The VTK comparison's transfer function (grey ramp, opacity 0 up to 10% rising to 0.8);
  //! empty: the data set's own preset (the default scene).
  std::string transfer = "grayscale";
  bool waves = false;  //!< front-to-back waves (--waves) instead of independent nodes
  //! Eye distance in bounding-sphere radii: the benchmark's closer view (as VTK's baseline), or
  //! the default view's where a target is about the default scene as users first see it.
  float distance = kBenchViewDistance;
};

//! `spec` with front-to-back waves, and the label its targets carry.
CellSpec withWaves(CellSpec spec) {
  spec.waves = true;
  return spec;
}
constexpr const char* kWavesLabel = " with --waves (front-to-back waves, beyond the paper)";

//! The cells of `spec` at node counts `nodes` (default: spec.nodes alone); with `interleave`
//! measured in rounds (BenchGridOptions::interleave), so their ratio is free of the machine's drift.
std::vector<BenchCell> measureCells(const VolumeSource& source, const CellSpec& spec, int frames,
                                    const std::atomic<bool>* stop, bool& interrupted, std::vector<int> nodes = {},
                                    bool interleave = false) {
  BenchGridOptions o;
  o.sizes = {spec.size};
  o.nodes = nodes.empty() ? std::vector<int>{spec.nodes} : nodes;
  o.interleave = interleave;
  o.strategies = {spec.strategy};
  o.frames = frames;
  o.base.settings.stepVoxels = spec.step;
  o.base.settings.shading = true;
  o.base.settings.frontToBackWaves = spec.waves;
  o.base.view.distance = spec.distance;
  const VolumeInfo& info = source.info();
  o.base.transfer = loadTransferFunction(!spec.transfer.empty() ? spec.transfer
                                                                 : (info.preset.empty() ? "grayscale" : info.preset));
  const BenchResult r = runBenchGrid(source, o, {}, stop);
  interrupted = r.interrupted || r.cells.size() != o.nodes.size();
  std::vector<BenchCell> cells = r.cells;
  cells.resize(o.nodes.size());  // an interrupted run's missing cells read 0
  return cells;
}

BenchCell measure(const VolumeSource& source, const CellSpec& spec, int frames, const std::atomic<bool>* stop,
                  bool& interrupted) {
  return measureCells(source, spec, frames, stop, interrupted).front();
}

//! Wall time at P = spec.nodes over wall time at P = 1, the two cells measured in turns.
struct WallRatio {
  double ratio = 0, p1Seconds = 0, pSeconds = 0;
  double p1Samples = 0, pSamples = 0;  //!< per frame: where P nodes take more, they sample behind
};
WallRatio interleavedWallRatio(const VolumeSource& source, const CellSpec& spec, int frames,
                               const std::atomic<bool>* stop, bool& interrupted) {
  const std::vector<BenchCell> c = measureCells(source, spec, frames, stop, interrupted, {1, spec.nodes}, true);
  return {c[0].wallSeconds > 0 ? c[1].wallSeconds / c[0].wallSeconds : 0.0, c[0].wallSeconds, c[1].wallSeconds,
          c[0].samples, c[1].samples};
}

std::string gridCommand(const std::string& data, const CellSpec& s, int frames, const char* extra = "") {
  char buf[512];
  std::snprintf(buf, sizeof buf, "kdswap bench %s%s%s --sizes %d --nodes %d --step %g --shading on --frames %d%s",
                data.c_str(), s.transfer.empty() ? "" : " --tf ", s.transfer.c_str(), s.size, s.nodes, double(s.step),
                frames, s.waves ? (std::string(" --waves") + extra).c_str() : extra);
  return buf;
}

std::string ms(double seconds) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f ms", seconds * 1e3);
  return buf;
}

std::string fixed(double value) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", value);
  return buf;
}

//! P nodes that take at most this many times one node's samples take "the same" (rounding of
//! segment ends, ray phases): the notes then blame the per-brick costs, not samples behind.
constexpr double kSameSamples = 1.05;

std::string megaSamples(double samples) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f M", samples / 1e6);
  return buf;
}

}  // namespace

std::vector<SpeedTarget> runSpeedTargets(const TargetOptions& o, const std::function<void(const std::string&)>& log,
                                         const std::atomic<bool>* stop) {
  std::vector<SpeedTarget> out;
  auto stopped = [&] { return stop && stop->load(); };
  auto say = [&](const std::string& s) { if (log) log(s); };
  bool interrupted = false;

  // 1, 6, 4: phantom 256^3 as uint8, 512x512, step 1, shading; P=64 first so peak RSS is its own.
  say("phantom:256 uint8, P=64 ...");
  QuantisedSource phantom(openDataset("phantom:256"), 8);
  const CellSpec p64;
  const BenchCell a = measure(phantom, p64, o.frames, stop, interrupted);
  const std::uint64_t rss = peakResidentBytes();
  const std::string phantomData = "--dataset phantom:256 --quantise 8";
  SpeedTarget t1{"phantom 256^3 uint8, 512x512, P=64, step 1, shading: wall per frame",
                 gridCommand(phantomData, p64, o.frames), a.wallSeconds * 1e3, 29.0, "ms", false, !interrupted, ""};
  out.push_back(t1);
  const bool vtkHere = o.vtkMs.size() == 3;
  if (vtkHere) out.push_back(halfOfVtkHere(t1, "phantom 256^3 uint8, P=64", o.vtkMs[1]));
  const double budget = 1.25 * kVoxelBytes * 256.0 * 256.0 * 256.0;
  out.push_back({"peak RSS with P=64, 256^3 (<= 1.25 x volume + gradients, 16 B/voxel)",
                 gridCommand(phantomData, p64, o.frames) + "   (peak_rss_bytes in bench.json)", double(rss) / 1e6,
                 budget / 1e6, "MB", false, !interrupted,
                 std::string("process peak (VmHWM), includes the program itself; bricks in ") +
                     (VoxelStorage::forVolume(phantom.info()).compactFormat() ? "compact (8 B/voxel)" : "float (16 B/voxel)") +
                     " storage",
                 /*firstRunOnly=*/true});
  if (stopped()) return out;

  // The ratio's two cells are measured in turns (--interleave), so the machine's drift between
  // minutes, which moves single figures by tens of percent, cancels out of it.
  say("phantom:256 uint8, P=1 and P=64 in turns ...");
  const WallRatio ratio = interleavedWallRatio(phantom, p64, o.frames, stop, interrupted);
  out.push_back({"P=64 wall <= 1.15 x P=1 wall (phantom 256^3 uint8, 512x512, step 1)",
                 "kdswap bench " + phantomData + " --tf grayscale --sizes 512 --nodes 1,64 --step 1 --interleave --frames " +
                     std::to_string(o.frames),
                 ratio.ratio, 1.15, "x", false, !interrupted,
                 wallRatioNote(ratio.p1Seconds, ratio.pSeconds, ratio.p1Samples, ratio.pSamples)});
  if (stopped()) return out;

  say("phantom:256 uint8, P=64, front-to-back waves ...");
  {
    const CellSpec w64 = withWaves(p64);
    const BenchCell w = measure(phantom, w64, o.frames, stop, interrupted);
    out.push_back({std::string("phantom 256^3 uint8, 512x512, P=64, step 1, shading: wall per frame") + kWavesLabel,
                   gridCommand(phantomData, w64, o.frames), w.wallSeconds * 1e3, 29.0, "ms", false, !interrupted, ""});
    if (vtkHere) out.push_back(halfOfVtkHere(out.back(), "phantom 256^3 uint8, P=64, --waves", o.vtkMs[1]));
    if (stopped()) return out;
    const WallRatio wavesRatio = interleavedWallRatio(phantom, w64, o.frames, stop, interrupted);
    out.push_back({std::string("P=64 wall <= 1.15 x P=1 wall (phantom 256^3 uint8, 512x512, step 1)") + kWavesLabel,
                   "kdswap bench " + phantomData +
                       " --tf grayscale --sizes 512 --nodes 1,64 --step 1 --waves --interleave --frames " +
                       std::to_string(o.frames),
                   wavesRatio.ratio, 1.15, "x", false, !interrupted,
                   wallRatioNote(wavesRatio.p1Seconds, wavesRatio.pSeconds, wavesRatio.p1Samples, wavesRatio.pSamples,
                                 " (P=1 has no waves: one node)")});
  }
  if (stopped()) return out;

  say("turbulence:256, P=64 ...");
  {
    auto turbulence = openDataset("turbulence:256");
    const BenchCell c = measure(*turbulence, p64, o.frames, stop, interrupted);
    out.push_back({"turbulence 256^3, 512x512, P=64, step 1, shading: wall per frame",
                   gridCommand("--dataset turbulence:256", p64, o.frames), c.wallSeconds * 1e3, 88.0, "ms", false,
                   !interrupted, ""});
    if (vtkHere) out.push_back(halfOfVtkHere(out.back(), "turbulence 256^3, P=64", o.vtkMs[0]));
    if (stopped()) return out;
    say("turbulence:256, P=64, front-to-back waves ...");
    const CellSpec w64 = withWaves(p64);
    const BenchCell w = measure(*turbulence, w64, o.frames, stop, interrupted);
    out.push_back({std::string("turbulence 256^3, 512x512, P=64, step 1, shading: wall per frame") + kWavesLabel,
                   gridCommand("--dataset turbulence:256", w64, o.frames), w.wallSeconds * 1e3, 88.0, "ms", false,
                   !interrupted, ""});
    if (vtkHere) out.push_back(halfOfVtkHere(out.back(), "turbulence 256^3, P=64, --waves", o.vtkMs[0]));
  }
  if (stopped()) return out;

  say("CT head " + o.headPath + ", P=64 ...");
  CellSpec head = p64;
  head.step = 0.5f;
  // Unit spacing, as the VTK figure (the file says 3.2 x 3.2 x 1.5, which at "0.5 voxel"
  // of the smallest spacing would take twice the samples along x and y).
  const CellSpec headWaves = withWaves(head);
  SpeedTarget t3{"CT head (headsq, unit spacing), 512x512, P=64, step 0.5, shading: wall per frame",
                 gridCommand("--volume " + o.headPath + " --spacing 1,1,1", head, o.frames), 0, 42.0, "ms", false,
                 false, ""};
  SpeedTarget t3w{std::string(t3.name) + kWavesLabel,
                  gridCommand("--volume " + o.headPath + " --spacing 1,1,1", headWaves, o.frames), 0, 42.0, "ms",
                  false, false, ""};
  if (std::filesystem::exists(o.headPath)) {
    const RespacedSource volume(openVolumeFile(o.headPath), glm::vec3(1.0f));
    const BenchCell c = measure(volume, head, o.frames, stop, interrupted);
    t3.measured = c.wallSeconds * 1e3;
    t3.ran = !interrupted;
    t3.note = megaSamples(c.samples) + " samples a frame";
    if (!stopped()) {
      say("CT head, P=64, front-to-back waves ...");
      const BenchCell w = measure(volume, headWaves, o.frames, stop, interrupted);
      t3w.measured = w.wallSeconds * 1e3;
      t3w.ran = !interrupted;
      t3w.note = megaSamples(w.samples) + " samples a frame (none behind the single-node ray's end)";
      // Waves take the single-node ray's samples: the excess without them is sampled behind.
      if (t3w.ran && w.samples > 0)
        t3.note += ", " + fixed(c.samples / w.samples) + " x those with --waves (the excess lies behind matter " +
                   "that ends the single-node ray)";
    }
  } else {
    t3.note = t3w.note = o.headPath + " not found (pass --head FILE)";
  }
  out.push_back(t3);
  if (vtkHere && t3.ran) out.push_back(halfOfVtkHere(t3, "CT head, P=64", o.vtkMs[2]));
  out.push_back(t3w);
  if (vtkHere && t3w.ran) out.push_back(halfOfVtkHere(t3w, "CT head, P=64, --waves", o.vtkMs[2]));
  if (stopped()) return out;

  say("binary-swap alone, 1024x1024, P=8 ...");
  const BinarySwapFigure swap = measureBinarySwap(8, 1024, 1024, MicroOptions{}.compositingRepeats);
  // "At most 2 x the time of copying the same number of bytes": the whole exchange (wall) against
  // a memcpy of as many bytes as all nodes send, timed in the same run.
  out.push_back({"binary-swap 1024^2, P=8: whole exchange <= 2 x copying the bytes it sends", "kdswap bench --micro",
                 swap.copySentSeconds > 0 ? swap.wallSeconds / swap.copySentSeconds : 0.0, 2.0, "x", false, true,
                 "copying " + std::to_string(swap.bytesSent >> 20) + " MiB: " + ms(swap.copySentSeconds) +
                     "; one node's composite time / copy of one image: " +
                     fixed(swap.copySeconds > 0 ? swap.compositeMaxSeconds / swap.copySeconds : 0.0) + " x"});
  // miniGraphics' 32 ms is the wall time of 8 ranks sharing the 2 cores: compare wall with wall.
  out.push_back({"binary-swap 1024^2, P=8: whole exchange, wall <= 16 ms (half of miniGraphics)",
                 "kdswap bench --micro", swap.wallSeconds * 1e3, 16.0, "ms", false, true,
                 "max over nodes " + ms(swap.compositeMaxSeconds)});
  if (stopped()) return out;

  say("default scene, 512x512, P=8 ...");
  {
    auto scene = openDataset(kDefaultDataset);
    CellSpec d;
    d.nodes = 8;
    d.step = 0.5f;       // the default scene's settings (render's defaults)
    d.transfer.clear();  // and its own preset
    // As the scene opens (kdswap render, kdswap-gui): the default view, which frames the whole
    // volume; then at the benchmark's closer view, where the head fills more of the frame and
    // takes ~1.8 x the samples, so that both figures are on record.
    const View defaultView;
    d.distance = defaultView.distance;
    const BenchCell c = measure(*scene, d, o.frames, stop, interrupted);
    char distance[16];
    std::snprintf(distance, sizeof distance, "%g", double(defaultView.distance));
    out.push_back({"default scene (phantom:128), 512x512, P=8, default view: frames per second",
                   "kdswap bench --sizes 512 --nodes 8 --distance " + std::string(distance) + " --frames " +
                       std::to_string(o.frames),
                   c.wallSeconds > 0 ? 1.0 / c.wallSeconds : 0.0, 20.0, "fps", true, !interrupted,
                   std::to_string(std::lround(c.samples / 1e3)) + " k samples a frame"});
    if (stopped()) return out;
    d.distance = kBenchViewDistance;
    const BenchCell close = measure(*scene, d, o.frames, stop, interrupted);
    out.push_back({"default scene (phantom:128), 512x512, P=8, the benchmark's closer view: frames per second",
                   "kdswap bench --sizes 512 --nodes 8 --frames " + std::to_string(o.frames),
                   close.wallSeconds > 0 ? 1.0 / close.wallSeconds : 0.0, 20.0, "fps", true, !interrupted,
                   std::to_string(std::lround(close.samples / 1e3)) + " k samples a frame"});
  }

  // The paper, ten times over: every sourced CM-5 cell with P = 32..512, our whole frame (all P
  // virtual nodes on this machine, wall) against a tenth of the paper's render + composite.
  for (const PaperCell& cell : paperCells()) {
    if (stopped()) return out;
    if (!cell.renderSeconds || !cell.compositeSeconds || cell.nodes < 32 || cell.nodes > 512) continue;
    if (cell.table.find("CM-5") == std::string::npos) continue;
    say(cell.table + ": " + cell.standIn + ", " + std::to_string(cell.imageSize) + "^2, P=" + std::to_string(cell.nodes) +
        " ...");
    const auto standIn = openDataset(cell.standIn);  // generated once for both modes
    const BenchCell c = measurePaperCell(cell, *standIn, o.frames, stop, interrupted);
    const double paper = *cell.renderSeconds + *cell.compositeSeconds;
    char name[256];
    std::snprintf(name, sizeof name, "%s, %s as %s, %d^2, P=%d: wall <= paper (render + composite) / 10",
                  cell.table.c_str(), cell.paperData.c_str(), cell.standIn.c_str(), cell.imageSize, cell.nodes);
    const std::string command = "kdswap bench --dataset " + cell.standIn + " --sizes " + std::to_string(cell.imageSize) +
                                " --nodes " + std::to_string(cell.nodes) + " --frames " + std::to_string(o.frames);
    out.push_back({name, "kdswap bench --paper   (or " + command + ")", c.wallSeconds * 1e3, paper * 1e3 / 10.0, "ms",
                   false, !interrupted,
                   "paper " + ms(paper) + " (" + cell.source + "); our modelled parallel time " +
                       ms(c.modelledSeconds)});
    if (stopped()) return out;
    // The same P nodes and binary swap, each node stopping its rays where the bricks in front
    // stopped the light: no node takes a sample the single-node ray would not (turbulence 256^3 at
    // P = 512: 52 M samples a frame instead of 74 M with the occlusion map).
    say(cell.table + ": " + cell.standIn + ", P=" + std::to_string(cell.nodes) + ", front-to-back waves ...");
    const BenchCell w = measurePaperCell(cell, *standIn, o.frames, stop, interrupted, /*waves=*/true);
    out.push_back({std::string(name) + kWavesLabel, "kdswap bench --paper --waves   (or " + command + " --waves)",
                   w.wallSeconds * 1e3, paper * 1e3 / 10.0, "ms", false, !interrupted,
                   "paper " + ms(paper) + "; our modelled parallel time " + ms(w.modelledSeconds)});
  }
  return out;
}

std::vector<SpeedTarget> medianOfRuns(const std::vector<std::vector<SpeedTarget>>& runs) {
  if (runs.empty()) return {};
  if (runs.size() == 1) return runs.front();
  std::vector<SpeedTarget> out = runs.front();
  for (std::size_t i = 0; i < out.size(); ++i) {
    SpeedTarget& t = out[i];
    if (t.firstRunOnly) {
      t.note += (t.note.empty() ? "" : "; ") + std::string("first of the runs only (a fresh process)");
      continue;
    }
    std::vector<double> values;
    std::string each;
    for (const std::vector<SpeedTarget>& run : runs) {
      if (i >= run.size() || run[i].name != t.name || !run[i].ran) continue;
      values.push_back(run[i].measured);
      each += (each.empty() ? "" : ", ") + fixed(run[i].measured);
    }
    t.ran = !values.empty();
    t.measured = median(values);
    const std::string runsNote =
        "median of " + std::to_string(values.size()) + (values.size() == 1 ? " run: " : " runs: ") + each;
    t.note = t.note.empty() ? runsNote : runsNote + "; first run: " + runs[0][i].note;
    if (!t.ran) t.note = runs[0][i].note;  // why it was not run
  }
  return out;
}

std::string wallRatioNote(double p1Seconds, double pSeconds, double p1Samples, double pSamples,
                          const std::string& p1Label) {
  std::string note = "P=1 wall " + ms(p1Seconds) + p1Label + ", P=64 wall " + ms(pSeconds) +
                     ", measured in turns; samples a frame " + megaSamples(p1Samples) + " and " + megaSamples(pSamples);
  if (!(p1Samples > 0) || !(pSamples > 0)) return note;
  const double more = pSamples / p1Samples;
  note += " (" + fixed(more) + " x: " +
          (more > kSameSamples ? "the nodes sample behind matter that ends one node's rays)"
                               : "the rest is the cost of 64 bricks and 6 compositing phases)");
  return note;
}

SpeedTarget halfOfVtkHere(const SpeedTarget& fixed, const std::string& scene, double vtkMs) {
  SpeedTarget t = fixed;
  t.name = scene + ": wall <= half of VTK measured on this machine";
  t.limit = vtkMs / 2.0;
  t.note = "VTK here " + std::to_string(int(std::lround(vtkMs))) +
           " ms (scripts/vtk_baseline.py: same voxels, camera and settings)";
  return t;
}

std::string formatSpeedTargets(const std::vector<SpeedTarget>& targets) {
  std::string out = "Speed targets (issue 6), medians of the measured frames:\n";
  char buf[1024];
  int met = 0, ran = 0;
  for (const SpeedTarget& t : targets) {
    const char* verdict = !t.ran ? "NOT RUN" : (t.met() ? "MET" : "MISSED");
    ran += t.ran;
    met += t.met();
    if (!t.ran) {
      std::snprintf(buf, sizeof buf, "  %-8s %s\n           not measured%s%s; target %s %.2f %s\n           command: %s\n",
                    verdict, t.name.c_str(), t.note.empty() ? "" : ": ", t.note.c_str(), t.atLeast ? ">=" : "<=",
                    t.limit, t.unit.c_str(), t.command.c_str());
    } else {
      std::snprintf(buf, sizeof buf, "  %-8s %s\n           measured %.2f %s, target %s %.2f %s%s%s\n           command: %s\n",
                    verdict, t.name.c_str(), t.measured, t.unit.c_str(), t.atLeast ? ">=" : "<=", t.limit,
                    t.unit.c_str(), t.note.empty() ? "" : "; ", t.note.c_str(), t.command.c_str());
    }
    out += buf;
  }
  std::snprintf(buf, sizeof buf, "%d of %zu targets met (%d run)\n", met, targets.size(), ran);
  return out + buf;
}

}  // namespace kdswap
