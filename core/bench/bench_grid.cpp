// Bench grid runner: clusters reused across sizes and frames, warm-up frame excluded, medians.
#include "core/bench/bench_grid.h"

#include <algorithm>
#include <map>

#include "core/bench/statistics.h"
#include "core/util/clock.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

// Work estimate for the time-left figure: ray casting scales with pixels, and every cell runs
// frames + 1 frames. Node count matters little (the same voxels are sampled in total).
double cellWeight(int size, int frames) { return double(size) * size * (frames + 1) + 1e4; }

struct FrameFigures {
  std::vector<double> render, composite, wall, modelled, samples, bytes, comm, imbalance;
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
  c.bytesSent = std::uint64_t(median(f.bytes));
  c.peakRssBytes = rss;
  c.distributeSeconds = distribute;
  return c;
}

}  // namespace

BenchResult runBenchGrid(const VolumeSource& source, const BenchGridOptions& o,
                         const std::function<void(const BenchProgress&)>& progress, const std::atomic<bool>* stop) {
  if (o.sizes.empty() || o.nodes.empty() || o.strategies.empty() || o.balances.empty() || o.bricksPerNode.empty())
    throw Error("bench: empty grid");
  if (o.frames < 1) throw Error("bench: --frames must be at least 1");
  BenchResult result;
  BenchProgress p;
  p.cellsTotal = int(o.strategies.size() * o.balances.size() * o.bricksPerNode.size() * o.nodes.size() *
                     o.sizes.size());
  double totalWeight = 0, doneWeight = 0;
  for (int size : o.sizes) totalWeight += cellWeight(size, o.frames);
  totalWeight *= double(o.strategies.size() * o.balances.size() * o.bricksPerNode.size() * o.nodes.size());
  const double start = nowSeconds();
  auto stopped = [&] { return stop && stop->load(std::memory_order_relaxed); };

  for (const std::string& base : o.strategies)
  for (const std::string& balance : o.balances)
  for (int bricks : o.bricksPerNode) {
    const std::string strategy = base + (balance == "space" ? "" : "+" + balance) +
                                 (bricks > 1 ? "+bricks" + std::to_string(bricks) : "") +
                                 (o.base.settings.frontToBackWaves ? "+waves" : "");
    for (int nodes : o.nodes) {
      ClusterOptions co = o.cluster;
      co.nodes = nodes;
      co.strategy = base;
      co.balance = balance;
      co.bricksPerNode = bricks;
      co.balanceTransfer = o.base.transfer;
      co.speeds.clear();
      for (std::size_t r = 0; !o.speedPattern.empty() && r < std::size_t(nodes); ++r)
        co.speeds.push_back(o.speedPattern[r % o.speedPattern.size()]);
      VirtualCluster cluster(source, co);
      for (int size : o.sizes) {
        FrameRequest request = o.base;
        request.width = request.height = size;
        request.recordPhases = false;
        p.current = std::to_string(size) + "x" + std::to_string(size) + ", P=" + std::to_string(nodes) + ", " +
                    strategy;
        FrameFigures f;
        std::uint64_t rss = 0;
        // Frame 0 is the warm-up (first touch of image buffers, caches); it is not measured.
        for (int frame = 0; frame <= o.frames && !stopped(); ++frame) {
          request.view.azimuthDeg = o.base.view.azimuthDeg + o.degreesPerFrame * float(frame);
          const FrameResult r = cluster.renderFrame(request);
          doneWeight += cellWeight(size, o.frames) / double(o.frames + 1);
          if (frame > 0) {
            f.render.push_back(r.stats.renderMax());
            f.composite.push_back(r.stats.compositeMax());
            f.wall.push_back(r.stats.wallSeconds);
            f.modelled.push_back(r.stats.modelledParallelSeconds());
            f.comm.push_back(r.stats.modelledCommSeconds());
            f.imbalance.push_back(r.stats.renderMean() > 0 ? r.stats.renderMax() / r.stats.renderMean() : 1.0);
            f.samples.push_back(double(r.stats.samples()));
            f.bytes.push_back(double(r.stats.bytesSent()));
            rss = r.stats.peakRssBytes;
          }
          p.elapsedSeconds = nowSeconds() - start;
          // Clamped: the per-frame weights are fractions whose rounded sum can pass the total.
          p.remainingSeconds = doneWeight > 0 ? std::max(0.0, p.elapsedSeconds * (totalWeight - doneWeight) / doneWeight) : 0.0;
          if (progress) progress(p);
        }
        if (!f.wall.empty()) {
          result.cells.push_back(summarise(strategy, nodes, size, f, rss, cluster.distributeSeconds()));
          result.cells.back().balance = balance;
          result.cells.back().bricksPerNode = bricks;
        }
        if (stopped()) {
          result.interrupted = true;
          computeSpeedups(result.cells);
          return result;
        }
        ++p.cellsDone;
        if (progress) progress(p);
      }
    }
  }
  computeSpeedups(result.cells);
  return result;
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
