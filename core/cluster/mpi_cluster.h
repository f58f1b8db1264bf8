// One frame of the node program on MPI ranks (issue 7): each rank computes the same k-d tree,
// reads its own nodes' bricks straight from the volume source (parallel I/O, no volume broadcast),
// renders and composites them with the unchanged node program; rank 0 is also the host and
// gathers the tiles and every node's report. Two steps: prepareRankFrame (collective calls while
// no network runs: the ranks agree on the job, load their bricks and merge the culling summary),
// then renderFrameOverMpi (the frame, over an MpiNetwork).
#pragma once

#if KDSWAP_HAVE_MPI

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json_fwd.hpp>

#include "core/cluster/brick_schedule.h"
#include "core/cluster/culling_rest.h"
#include "core/cluster/node_arena.h"
#include "core/cluster/virtual_cluster.h"
#include "core/comm/mpi_network.h"
#include "core/partition/cost_field.h"
#include "core/render/occlusion_grid.h"
#include "core/render/occlusion_map.h"

namespace kdswap {

//! Message tags of the MPI frame protocol (beside kTileTag): node -> host "ready" (its brick's load
//! time and its rank's culling-map time), host -> node "start the frame", node -> host "my
//! NodeReport" (JSON text). Apart from the node program's tags (10 to 12).
inline constexpr int kReadyTag = 20;
inline constexpr int kGoTag = 21;
inline constexpr int kReportTag = 22;

//! One rank's part of a frame, ready to render: the partition and plan every rank computes alike,
//! this rank's nodes with their bricks loaded, and, with occlusion culling, the whole volume's cell
//! summary (merged from every rank's bricks) and the current frame's map. Bricks stay loaded across
//! frames; setView prepares the next frame. Not copyable: the plan refers to the request, the
//! strategy and the map.
struct MpiRankFrame {
  //! `cost`: the work estimate for --balance cost (null: planes halve space).
  MpiRankFrame(const VolumeSource& source, const FrameRequest& request, const ClusterOptions& options,
               int ranks, int nodesPerRank, std::shared_ptr<const CostField> cost);
  MpiRankFrame(const MpiRankFrame&) = delete;
  MpiRankFrame& operator=(const MpiRankFrame&) = delete;

  //! Local, the same on every rank: the next frame looks from `view` (a new plan, and with culling
  //! a new occlusion map, timed in mapSeconds, unless culling rests: CullingRest, whose counts
  //! renderFrameOverMpi sums over the ranks, as the virtual cluster decides it), its lattice
  //! shifted by `phaseShift` (RenderSettings::phaseShift: pass i of --passes gives
  //! latticePassShift(i)). Once per frame.
  void setView(const View& view, float phaseShift);

  const VolumeSource& source;
  FrameRequest request;             //!< the current frame's (view and phase shift change with setView)
  const ClusterOptions& options;
  int nodesPerRank;
  NodeArena arena;
  std::unique_ptr<Strategy> strategy;
  KdTree tree;
  //! Over-decomposition (--bricks-per-node M; perNode 1 when off): every rank keeps the same book
  //! (the next frame's cost estimates and who holds which brick), so every rank plans the same
  //! hand-out; the costs measured where each brick was rendered are summed over the ranks after
  //! every frame.
  BrickLayout layout;
  std::vector<double> brickCost;      //!< per brick: estimated work for the next frame
  std::vector<std::set<int>> held;    //!< per node: foreign bricks it holds
  BrickSchedule schedule;             //!< the current frame's hand-out (when perNode > 1)
  std::vector<double> brickWorkHere;  //!< per brick: this frame's work if this rank's node rendered it, else 0
  std::optional<FramePlan> plan;
  VoxelStorage storage;
  std::vector<NodeState> states;    //!< this rank's nodes, firstLocalNode() + i
  std::vector<double> loadSeconds;  //!< each of this rank's nodes: its bricks' read + gradients
  std::optional<OcclusionGrid> occlusionGrid;  //!< culling's per-transfer-function grid, when active
  std::optional<OcclusionMap> occlusionMap;
  CullingRest cullingRest;
  std::atomic<std::uint64_t> raysHere{0}, occludedHere{0};  //!< this frame's, over this rank's nodes
  double mapSeconds = 0;            //!< this rank's occlusion map, computed before the frame starts
};

//! Collective over MPI_COMM_WORLD, on the main thread while no MpiNetwork runs; every rank calls
//! it with its own volume and the request and options of its own command line. The ranks check
//! that they describe the same job (JobDescription); with --balance cost each estimates the work
//! of a share of the volume's block layers and the shares are summed (MPI_Allreduce) into the
//! field the virtual cluster estimates whole; each loads its nodes' bricks, and with culling
//! they merge the cell summary (MPI_Allreduce) and each computes the frame's occlusion map, as the
//! virtual cluster does. A problem on any rank throws kdswap::Error on every rank with the same
//! one-line message (naming the rank), so all stop together.
std::unique_ptr<MpiRankFrame> prepareRankFrame(const VolumeSource& source, const FrameRequest& request,
                                               const ClusterOptions& options, int nodesPerRank);

struct MpiFrameOutcome {
  bool ok = false;          //!< rank 0: the frame completed; other ranks: no failure seen locally
  std::string error;        //!< rank 0, when !ok: the first failure, naming its node and rank
  FrameResult result;       //!< rank 0, when ok: image, stats (per node), tiles
  int ranks = 1, nodesPerRank = 1;
  std::vector<std::uint64_t> rankPeakRss;  //!< rank 0: peak resident bytes of each rank
  std::vector<double> nodeLoadSeconds;     //!< rank 0: each node's brick read + gradients

  //! FrameStats::toJson() plus "ranks", "nodes_per_rank" and "per_rank" (rank, nodes, memory).
  nlohmann::json statsJson() const;
};

//! Collective: every rank calls it once per frame with its prepared frame. Finishes `network` (no
//! MPI traffic may follow through it). With over-decomposition it plans the frame's hand-out first
//! and afterwards sums the bricks' measured work over the ranks for the next frame's plan. Never
//! throws for a node's failure: it is in the outcome on rank 0.
MpiFrameOutcome renderFrameOverMpi(MpiNetwork& network, MpiRankFrame& frame);

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
