// VirtualCluster: P virtual nodes in one process (any P from 1 to 4096). Each node is a oneTBB
// task running the node program over its own private NodeState; nodes talk only through the
// in-process network's mailboxes. Waiting nodes suspend their tasks, so P far above the core
// count neither deadlocks nor oversubscribes threads.
#pragma once

#include <atomic>
#include <functional>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <glm/vec4.hpp>

#include "core/cluster/culling_rest.h"
#include "core/cluster/fault_plan.h"
#include "core/cluster/frame_request.h"
#include "core/cluster/node_arena.h"
#include "core/cluster/node_program.h"
#include "core/cluster/phase_record.h"
#include "core/comm/inproc_network.h"
#include "core/composite/registry.h"
#include "core/metrics/frame_stats.h"
#include "core/metrics/network_model.h"
#include "core/partition/brick_layout.h"
#include "core/partition/kd_tree.h"
#include "core/render/occlusion_grid.h"
#include "core/transfer/transfer_function.h"
#include "core/volume/volume_source.h"

namespace kdswap {

inline constexpr int kMaxNodes = 4096;

//! How virtual nodes run. Tasks: one oneTBB task per node; a waiting node suspends its task
//! (swapcontext), so thousands of nodes share the worker threads. Threads: one OS thread per node
//! and blocking mailboxes; same node program and messages, but no stack switching, which
//! AddressSanitizer and ThreadSanitizer cannot follow: sanitizer builds use it by default.
enum class NodeExecution { Tasks, Threads };
NodeExecution parseNodeExecution(const std::string& text);  //!< "tasks" | "threads"; throws Error
#if defined(KDSWAP_SANITIZED)
inline constexpr NodeExecution kDefaultNodeExecution = NodeExecution::Threads;
#else
inline constexpr NodeExecution kDefaultNodeExecution = NodeExecution::Tasks;
#endif

struct ClusterOptions {
  int nodes = 8;
  PartitionKind partition = PartitionKind::KdTree;
  int slabAxis = 2;                      //!< for slab partitions: the axis the slabs are stacked along
  std::string strategy = "binary-swap";
  CompositeOptions composite;
  int threads = 0;                       //!< worker threads; 0 = every core
  double stallSeconds = 60.0;            //!< a frame whose nodes all wait, with no message for this long, is aborted
  bool checksums = kChecksumsByDefault;  //!< checksum every message; a corrupted one is refused
  NodeExecution execution = kDefaultNodeExecution;

  // Load balancing and the modelled machine (issue 8).
  //! Plane placement: "space" halves space (the paper); "cost" balances estimated work, a
  //! CostField of `balanceTransfer` over `balanceRange` (the data's range when empty).
  std::string balance = "space";
  TransferFunction balanceTransfer;
  glm::vec2 balanceRange{0.0f};
  //! Relative processor speed per node (empty: all 1). Partitions follow it: a node twice as fast
  //! gets twice the work; modelled times divide each node's measured work by its speed.
  std::vector<double> speeds;
  NetworkModel network;  //!< costs each phase's messages in the modelled time
  //! Over-decomposition: each node's brick is cut into this many sub-bricks (1 = off, up to 64),
  //! handed out on demand each frame (see BrickSchedule) and composited at their home node.
  int bricksPerNode = 1;
  //! How nodes store voxels: Auto is compact 16-bit above 2^23 voxels (voxel_storage.h).
  VoxelChoice voxels = VoxelChoice::Auto;
#if defined(KDSWAP_CHECKS) && KDSWAP_CHECKS
  static constexpr bool kChecksumsByDefault = true;
#else
  static constexpr bool kChecksumsByDefault = false;
#endif
};

struct FrameResult {
  Image image;                  //!< the finished frame (premultiplied RGBA)
  FrameStats stats;
  std::vector<Rect> tiles;      //!< tiles[node]: the region each node finished
  std::shared_ptr<PhaseRecord> phases;  //!< when the request asked for it
};

class VirtualCluster {
 public:
  //! Partitions the volume and distributes the bricks (the host reads one brick at a time).
  //! Throws kdswap::Error for a bad option.
  VirtualCluster(const VolumeSource& source, const ClusterOptions& options);
  ~VirtualCluster();

  //! Renders one frame on all nodes. Throws kdswap::Error naming the node if a node fails or the
  //! frame stalls; the cluster stays usable for the next frame.
  FrameResult renderFrame(const FrameRequest& request);

  //! Over-decomposition: per brick, the estimated work (samples + a cost per ray) the next hand-out starts from.
  const std::vector<double>& brickCosts() const { return brickCost_; }
  //! Test-only: replaces those estimates (e.g. to force work stealing).
  void setBrickCosts(std::vector<double> costs);
  const BrickLayout& layout() const { return layout_; }

  //! Test-only: the next frame suffers `fault` (one frame only).
  void injectFault(const FaultPlan& fault) { fault_ = fault; }

  const KdTree& tree() const { return tree_; }
  const VolumeInfo& info() const { return info_; }
  const ClusterOptions& options() const { return options_; }
  double distributeSeconds() const { return distributeSeconds_; }
  //! Nodes whose render step of the current (or last) frame has ended; any thread may read it
  //! while renderFrame runs, to show progress.
  int nodesRendered() const { return nodesRendered_.load(std::memory_order_relaxed); }

 private:
  InprocCommunicator::SendFilter faultFilter(int rank);
  template <typename Body>
  void runOnNodes(Body&& body, bool withHostTask, const std::function<void()>& hostTask);

  ClusterOptions options_;
  VolumeInfo info_;
  std::shared_ptr<const CostField> cost_;  //!< work estimate when balancing by cost, else null
  KdTree tree_;
  BrickLayout layout_;                     //!< over-decomposition (perNode 1 when off)
  std::vector<double> brickCost_;          //!< per brick: estimated work for the next frame
  std::vector<std::set<int>> held_;        //!< per node: foreign bricks it holds (host's bookkeeping)
  std::unique_ptr<Strategy> strategy_;
  NodeArena arena_;
  InprocNetwork network_;
  std::vector<NodeState> nodes_;  //!< nodes_[r] is touched only by node r's task
  double distributeSeconds_ = 0;
  //! Value range of every macro cell of the whole volume, gathered once from the nodes' bricks:
  //! the replicated summary occlusion culling reads (1/64 of the voxel count).
  CellRangeGrid cellRanges_;
  //! Occlusion culling's optical depths per cell depend on the transfer table, the value mapping and
  //! the termination opacity only: kept while those stay, so an orbiting view rebuilds nothing
  //! (5.7 ms a frame at 256^3, one thread).
  struct OcclusionGridCache {
    std::vector<glm::vec4> entries;
    float scale = 0.0f, bias = 0.0f, stopAt = 0.0f;
    std::optional<OcclusionGrid> grid;
  };
  const OcclusionGrid& occlusionGridFor(const TransferTable& table, float scale, float bias, float stopAt);
  OcclusionGridCache occlusionGrid_;
  CullingRest cullingRest_;  //!< occlusion culling rests where its map saved little
  std::atomic<int> nodesRendered_{0};
  FaultPlan fault_;  //!< armed for the next frame only
};

}  // namespace kdswap
