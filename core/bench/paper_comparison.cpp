// Paper comparison: our stand-in cells beside the published CM-5 / workstation figures.
#include "core/bench/paper_comparison.h"

#include <cstdio>

#include "core/transfer/presets.h"
#include "core/volume/datasets/dataset.h"

namespace kdswap {
namespace {

std::string seconds(const std::optional<double>& v) {
  char buf[32];
  if (!v) return "n/a";
  std::snprintf(buf, sizeof buf, "%.3f", *v);
  return buf;
}

std::string ratio(double ours, const std::optional<double>& paper) {
  char buf[32];
  if (!paper || *paper <= 0) return "n/a";
  std::snprintf(buf, sizeof buf, "%.4f", ours / *paper);
  return buf;
}

}  // namespace

BenchCell measurePaperCell(const PaperCell& cell, const VolumeSource& standIn, int frames,
                           const std::atomic<bool>* stop, bool& interrupted, bool waves) {
  BenchGridOptions o;
  o.sizes = {cell.imageSize};
  o.nodes = {cell.nodes};
  o.frames = frames;
  o.base.settings.frontToBackWaves = waves;
  o.base.transfer = loadTransferFunction(standIn.info().preset.empty() ? "grayscale" : standIn.info().preset);
  const BenchResult r = runBenchGrid(standIn, o, {}, stop);
  interrupted = r.interrupted || r.cells.empty();
  return r.cells.empty() ? BenchCell{} : r.cells.front();
}

std::string runPaperComparison(int frames, const std::function<void(const std::string&)>& log,
                               const std::atomic<bool>* stop, bool waves) {
  std::string out = std::string("Paper cells with stand-in data") +
                    (waves ? ", front-to-back waves (--waves, beyond the paper: the same nodes and binary swap)" : "") +
                    " (ours: median of frames, maximum over nodes; ratio = ours / paper):\n";
  char buf[512];
  std::snprintf(buf, sizeof buf, "  %-15s %-16s %-15s %6s %5s | %9s %9s | %9s %9s | %8s %8s\n", "table", "paper data",
                "stand-in", "image", "P", "render s", "comp. s", "paper r.", "paper c.", "r ratio", "c ratio");
  out += buf;
  for (const PaperCell& cell : paperCells()) {
    if (stop && stop->load()) {
      out += "  (interrupted: remaining cells not run)\n";
      break;
    }
    if (log) log(cell.table + ": " + cell.standIn + ", " + std::to_string(cell.imageSize) + "^2, P=" +
                 std::to_string(cell.nodes) + " ...");
    bool interrupted = false;
    const BenchCell c = measurePaperCell(cell, *openDataset(cell.standIn), frames, stop, interrupted, waves);
    if (interrupted) continue;
    std::snprintf(buf, sizeof buf, "  %-15s %-16s %-15s %6d %5d | %9.4f %9.4f | %9s %9s | %8s %8s\n",
                  cell.table.c_str(), cell.paperData.c_str(), cell.standIn.c_str(), cell.imageSize, cell.nodes,
                  c.renderSeconds, c.compositeSeconds, seconds(cell.renderSeconds).c_str(),
                  seconds(cell.compositeSeconds).c_str(), ratio(c.renderSeconds, cell.renderSeconds).c_str(),
                  ratio(c.compositeSeconds, cell.compositeSeconds).c_str());
    out += buf;
    std::snprintf(buf, sizeof buf, "  %-15s source: %s; our wall %.4f s, modelled %.4f s\n", "", cell.source.c_str(),
                  c.wallSeconds, c.modelledSeconds);
    out += buf;
  }
  return out + paperCoverageNote();
}

}  // namespace kdswap
