// Bench grid runner: clusters reused across sizes and frames, warm-up frame excluded, medians.
#include "core/bench/bench_grid.h"

#include <algorithm>
#include <map>
#include <memory>

#include "core/bench/statistics.h"
#include "core/util/clock.h"
#include "core/util/error.h"
#include "core/util/memory.h"

namespace kdswap {
namespace {

// Work estimate for the time-left figure: ray casting scales with pixels, and every cell runs
// frames + 1 frames. Node count matters little (the same voxels are sampled in total).
double cellWeight(int size, int frames) { return double(size) * size * (frames + 1) + 1e4; }

struct FrameFigures {
  std::vector<double> render, composite, wall, modelled, samples, rays, occluded, bytes, comm, imbalance, map;
};

BenchCell summarise(const std::string& strategy, int nodes, int size, const FrameFigures& f, std::uint64_t rss,
                    double distribute) {
  BenchCell c;
  c.strategy = strategy;
  c.nodes = nodes;
  c.width = c.height = size;
  c.frames = int(f.wall.size());
  c.renderSeconds = median(f.render);
  c.compositeSeconds = median(f.composite);
  c.wallSeconds = median(f.wall);
  c.modelledSeconds = median(f.modelled);
  c.commSeconds = median(f.comm);
  c.renderImbalance = median(f.imbalance);
  c.samples = median(f.samples);
  c.samplesPerSecond = c.wallSeconds > 0 ? c.samples / c.wallSeconds : 0.0;
  c.rays = median(f.rays);
  c.raysOccluded = median(f.occluded);
  c.occlusionMapSeconds = median(f.map);
  c.bytesSent = std::uint64_t(median(f.bytes));
  c.peakRssBytes = rss;
  c.distributeSeconds = distribute;
  return c;
}

//! A cluster of the grid: one per (strategy, balance, bricks per node, P), shared by its sizes.
struct ClusterPlan {
  ClusterOptions options;
  std::unique_ptr<VirtualCluster> cluster;  //!< built when first needed
};

//! One cell under way: its request and the figures of the frames measured so far.
struct CellRun {
  std::string strategy, balance;
  int bricks = 1, nodes = 1, size = 0;
  std::size_t plan = 0;  //!< index of its ClusterPlan
  FrameRequest request;
  FrameFigures figures;
  std::uint64_t rss = 0;
  double distribute = 0;
};

//! Renders frame `frame` of `cell` and, when `measured`, records its figures.
void renderCellFrame(CellRun& cell, VirtualCluster& cluster, const BenchGridOptions& o, int frame, bool measured) {
  cell.request.view.azimuthDeg = o.base.view.azimuthDeg + o.degreesPerFrame * float(frame);
  const FrameResult r = cluster.renderFrame(cell.request);
  cell.distribute = cluster.distributeSeconds();
  if (!measured) return;
  FrameFigures& f = cell.figures;
  f.render.push_back(r.stats.renderMax());
  f.composite.push_back(r.stats.compositeMax());
  f.wall.push_back(r.stats.wallSeconds);
  f.modelled.push_back(r.stats.modelledParallelSeconds());
  f.comm.push_back(r.stats.modelledCommSeconds());
  f.imbalance.push_back(r.stats.renderMean() > 0 ? r.stats.renderMax() / r.stats.renderMean() : 1.0);
  f.samples.push_back(double(r.stats.samples()));
  f.rays.push_back(double(r.stats.rays()));
  f.occluded.push_back(double(r.stats.raysOccluded()));
  f.map.push_back(r.stats.occlusionMapSeconds);
  f.bytes.push_back(double(r.stats.bytesSent()));
  cell.rss = r.stats.peakRssBytes;
}

//! The cell's summary, when at least one frame was measured.
void keepCell(const CellRun& cell, BenchResult& result) {
  if (cell.figures.wall.empty()) return;
  result.cells.push_back(summarise(cell.strategy, cell.nodes, cell.size, cell.figures, cell.rss, cell.distribute));
  result.cells.back().balance = cell.balance;
  result.cells.back().bricksPerNode = cell.bricks;
}

//! Builds every plan's cluster, refusing (before the memory runs out) a grid whose clusters will
//! not fit together: each new one needs about as much as the largest so far.
void buildAllClusters(const VolumeSource& source, std::vector<ClusterPlan>& plans) {
  std::uint64_t largest = 0;
  for (std::size_t i = 0; i < plans.size(); ++i) {
    const std::uint64_t available = availableMemoryBytes();
    if (i > 0 && available > 0 && available < largest + largest / 2)
      throw Error("bench --interleave: the grid's " + std::to_string(plans.size()) +
                  " clusters (one per strategy, balance, bricks per node and node count) do not fit in memory "
                  "together (" + std::to_string(i) + " built, " + formatBytes(available) +
                  " left); run without --interleave or with fewer node counts");
    const std::uint64_t before = currentResidentBytes();
    plans[i].cluster = std::make_unique<VirtualCluster>(source, plans[i].options);
    const std::uint64_t after = currentResidentBytes();
    largest = std::max(largest, after > before ? after - before : std::uint64_t(0));
  }
}

}  // namespace

BenchResult runBenchGrid(const VolumeSource& source, const BenchGridOptions& o,
                         const std::function<void(const BenchProgress&)>& progress, const std::atomic<bool>* stop) {
  if (o.sizes.empty() || o.nodes.empty() || o.strategies.empty() || o.balances.empty() || o.bricksPerNode.empty())
    throw Error("bench: empty grid");
  if (o.frames < 1) throw Error("bench: --frames must be at least 1");

  // The cells in report order, each pointing at its cluster's plan.
  std::vector<ClusterPlan> plans;
  std::vector<CellRun> cells;
  for (const std::string& base : o.strategies)
  for (const std::string& balance : o.balances)
  for (int bricks : o.bricksPerNode)
  for (int nodes : o.nodes) {
    ClusterPlan plan;
    ClusterOptions& co = plan.options;
    co = o.cluster;
    co.nodes = nodes;
    co.strategy = base;
    co.balance = balance;
    co.bricksPerNode = bricks;
    co.balanceTransfer = o.base.transfer;
    co.speeds.clear();
    for (std::size_t r = 0; !o.speedPattern.empty() && r < std::size_t(nodes); ++r)
      co.speeds.push_back(o.speedPattern[r % o.speedPattern.size()]);
    const std::string strategy = base + (balance == "space" ? "" : "+" + balance) +
                                 (bricks > 1 ? "+bricks" + std::to_string(bricks) : "") +
                                 (o.base.settings.frontToBackWaves ? "+waves" : "");
    for (int size : o.sizes) {
      CellRun cell{strategy, balance, bricks, nodes, size, plans.size(), o.base, {}, 0, 0};
      cell.request.width = cell.request.height = size;
      cell.request.recordPhases = false;
      cells.push_back(std::move(cell));
    }
    plans.push_back(std::move(plan));
  }

  BenchResult result;
  BenchProgress p;
  p.cellsTotal = int(cells.size());
  p.interleaved = o.interleave;
  double totalWeight = 0, doneWeight = 0;
  for (const CellRun& cell : cells) totalWeight += cellWeight(cell.size, o.frames);
  const int rendersPerCell = o.interleave ? 2 * o.frames : o.frames + 1;
  const double start = nowSeconds();
  auto stopped = [&] { return stop && stop->load(std::memory_order_relaxed); };
  auto frameDone = [&](const CellRun& cell) {
    doneWeight += cellWeight(cell.size, o.frames) / double(rendersPerCell);
    p.current = std::to_string(cell.size) + "x" + std::to_string(cell.size) + ", P=" + std::to_string(cell.nodes) +
                ", " + cell.strategy;
    p.elapsedSeconds = nowSeconds() - start;
    // Clamped: the per-frame weights are fractions whose rounded sum can pass the total.
    p.remainingSeconds = doneWeight > 0 ? std::max(0.0, p.elapsedSeconds * (totalWeight - doneWeight) / doneWeight) : 0.0;
    if (progress) progress(p);
  };
  auto finish = [&](bool interrupted) {
    result.interrupted = interrupted;
    computeSpeedups(result.cells);
    return result;
  };

  if (o.interleave) {
    // Rounds: every cell's frame k before any cell's frame k + 1, so a machine whose speed drifts
    // between minutes slows every cell alike and the cells compare fairly. Each measured frame k
    // follows the same cell's frame k - 1, rendered again unmeasured: the caches are then as warm
    // as cell after cell (without it the other cells' voxels evicted the cell's own: the phantom's
    // P = 64 / P = 1 ratio read 1.62-1.77 against 1.53-1.62 cell after cell, four runs each).
    // All clusters live for the whole run.
    buildAllClusters(source, plans);
    for (int frame = 1; frame <= o.frames && !stopped(); ++frame)
      for (std::size_t c = 0; c < cells.size() && !stopped(); ++c) {
        CellRun& cell = cells[c];
        VirtualCluster& cluster = *plans[cell.plan].cluster;
        renderCellFrame(cell, cluster, o, frame - 1, false);
        frameDone(cell);
        if (stopped()) break;
        renderCellFrame(cell, cluster, o, frame, true);
        if (frame == o.frames) ++p.cellsDone;
        frameDone(cell);
      }
    for (const CellRun& cell : cells) keepCell(cell, result);
    return finish(stopped());
  }

  // Cell after cell, one cluster in memory at a time.
  for (CellRun& cell : cells) {
    ClusterPlan& plan = plans[cell.plan];
    if (!plan.cluster) {
      if (cell.plan > 0) plans[cell.plan - 1].cluster.reset();
      plan.cluster = std::make_unique<VirtualCluster>(source, plan.options);
    }
    // Frame 0 is the warm-up (first touch of image buffers and caches); it is not measured.
    for (int frame = 0; frame <= o.frames && !stopped(); ++frame) {
      renderCellFrame(cell, *plan.cluster, o, frame, frame > 0);
      frameDone(cell);
    }
    keepCell(cell, result);
    if (stopped()) return finish(true);
    ++p.cellsDone;
    if (progress) progress(p);
  }
  return finish(false);
}

void computeSpeedups(std::vector<BenchCell>& cells) {
  // Baseline per (strategy, size): the smallest node count measured. With P0 = 1 this is the
  // paper's T(1) / T(P); otherwise it assumes perfect scaling up to P0 and says so in the output.
  std::map<std::pair<std::string, int>, const BenchCell*> base;
  for (const BenchCell& c : cells) {
    auto& b = base[{c.strategy, c.width}];
    if (!b || c.nodes < b->nodes) b = &c;
  }
  for (BenchCell& c : cells) {
    const BenchCell* b = base[{c.strategy, c.width}];
    c.speedup = c.modelledSeconds > 0 ? double(b->nodes) * b->modelledSeconds / c.modelledSeconds : 0.0;
  }
}

}  // namespace kdswap
