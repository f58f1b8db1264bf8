// The bench grid: the paper's timing tables (Tables 1-8) measured over image sizes x node
// counts x compositing strategies, K frames per cell with the view turning, median reported.
// One VirtualCluster per (strategy, node count) is reused across sizes and frames, so data
// distribution (paper Table 5) is paid once and never enters a cell. Cells run one after another,
// or interleaved frame by frame (BenchGridOptions::interleave).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "core/cluster/frame_request.h"
#include "core/cluster/virtual_cluster.h"
#include "core/volume/volume_source.h"

namespace kdswap {

//! The benchmark's eye distance in bounding-sphere radii: the volume fills more of the frame
//! (its corners may leave it) than at the default distance; the issue-6 figures use it.
constexpr float kBenchViewDistance = 2.5f;

struct BenchGridOptions {
  std::vector<int> sizes{64, 128, 256, 512};  //!< square images, side in pixels
  std::vector<int> nodes{1, 2, 4, 8, 16, 32, 64, 128, 256, 512};
  std::vector<std::string> strategies{"binary-swap"};
  //! Plane placements to compare ("space", "cost"); a cost cell's strategy reads "NAME+cost".
  std::vector<std::string> balances{"space"};
  //! Over-decomposition levels to compare; a cell with M > 1 reads "NAME+bricksM".
  std::vector<int> bricksPerNode{1};
  //! Relative node speeds, repeated over each cell's P nodes (empty: all 1).
  std::vector<double> speedPattern;
  int frames = 5;                //!< measured frames per cell; one warm-up frame more is excluded
  float degreesPerFrame = 1.0f;  //!< the azimuth turns this much between frames
  //! Rounds instead of cell after cell: every cell's frame k before any cell's frame k + 1, so
  //! that drift in the machine's speed (shared machines drift by tens of percent within minutes)
  //! hits every cell alike. Every cell's cluster then stays in memory for the whole run.
  bool interleave = false;
  //! View, transfer function, settings (width/height ignored). The view is closer than kdswap's
  //! default framing, as in every figure the README records and in scripts/vtk_baseline.py.
  FrameRequest base = [] {
    FrameRequest r;
    r.view.distance = kBenchViewDistance;
    return r;
  }();
  ClusterOptions cluster;        //!< partition, threads, sparse, network (nodes, strategy, balance ignored)
};

//! One cell: medians over the measured frames (maximum over nodes, as the paper reports).
struct BenchCell {
  std::string strategy;           //!< with "+cost", "+bricksM", "+waves" appended where they apply
  int nodes = 0, width = 0, height = 0;
  int frames = 0;                 //!< frames measured (fewer than asked if interrupted)
  double renderSeconds = 0;       //!< FrameStats::renderMax
  double compositeSeconds = 0;    //!< FrameStats::compositeMax
  double wallSeconds = 0;         //!< whole frame on this machine
  double modelledSeconds = 0;     //!< FrameStats::modelledParallelSeconds
  double samples = 0;             //!< ray samples per frame
  double samplesPerSecond = 0;    //!< samples / wall time
  double rays = 0;                //!< ray-brick pairs per frame (FrameStats::rays)
  double raysOccluded = 0;        //!< of them, skipped: matter in front ends them (culled)
  double occlusionMapSeconds = 0; //!< FrameStats::occlusionMapSeconds (part of the wall time)
  std::uint64_t bytesSent = 0;    //!< per frame, all nodes
  std::uint64_t peakRssBytes = 0; //!< process peak so far
  double distributeSeconds = 0;   //!< the cluster's one-off data distribution
  double speedup = 0;             //!< modelled: P0 * T(P0) / T(P), P0 the grid's smallest P; 0 if unknown
  double commSeconds = 0;         //!< FrameStats::modelledCommSeconds (0 on the ideal network)
  double renderImbalance = 0;     //!< render max / mean over nodes: 1 is perfect balance
  std::string balance = "space";  //!< plane placement of the cell's partition
  int bricksPerNode = 1;          //!< over-decomposition of the cell's cluster
};

struct BenchProgress {
  int cellsDone = 0, cellsTotal = 0;
  double elapsedSeconds = 0, remainingSeconds = 0;  //!< remaining: estimated from work done
  std::string current;                                //!< "256x256, P=8, binary-swap"
  bool interleaved = false;  //!< rounds over the cells: `current` changes every frame
};

struct BenchResult {
  std::vector<BenchCell> cells;
  bool interrupted = false;
};

//! Runs the grid. `progress` is called after every frame; `stop` (may be null) is polled after
//! every frame: when set, the run ends and keeps every frame measured so far. Throws Error.
BenchResult runBenchGrid(const VolumeSource& source, const BenchGridOptions& options,
                         const std::function<void(const BenchProgress&)>& progress, const std::atomic<bool>* stop);

//! Fills BenchCell::speedup from the modelled times (per strategy and image size).
void computeSpeedups(std::vector<BenchCell>& cells);

}  // namespace kdswap
