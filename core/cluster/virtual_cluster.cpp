// Virtual cluster: runs the node program as P oneTBB tasks; a watchdog ends stalled frames.
#include "core/cluster/virtual_cluster.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdio>
#include <mutex>
#include <optional>
#include <thread>

#include <oneapi/tbb/task_group.h>

#include "core/cluster/front_to_back_waves.h"
#include "core/cluster/host.h"
#include "core/render/reference_render.h"
#include "core/util/clock.h"
#include "core/util/error.h"
#include "core/util/memory.h"

namespace kdswap {
namespace {

std::string formatSeconds(double seconds) {
  char text[32];
  std::snprintf(text, sizeof text, "%g s", seconds);
  return text;
}

// Aborts the frame when no message moves and no node finishes for `limit` seconds, naming who
// waits on whom: every wait can end.
class StallWatchdog {
 public:
  //! `participants`: the tasks of the frame (nodes, and the host task when there is one).
  StallWatchdog(InprocNetwork& network, const std::atomic<int>& finished, int participants, double limit)
      : network_(network), finished_(finished), participants_(participants), limit_(limit), thread_([this] { watch(); }) {}
  ~StallWatchdog() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    wake_.notify_all();
    thread_.join();
  }

 private:
  // A stall: someone waits for a message, nobody is working (every unfinished participant waits
  // or is held in the transport), and no message has moved for the limit. A node still rendering
  // a large brick is progress, however long it takes: only waiting with nothing to wait on ends
  // a frame.
  bool nobodyWorking() const {
    const int waiting = network_.waitingCount();
    return waiting > 0 && waiting + network_.inTransport() >= participants_ - finished_.load();
  }

  void watch() {
    std::uint64_t lastDelivered = network_.delivered();
    int lastFinished = finished_.load();
    double lastProgress = nowSeconds();
    std::unique_lock<std::mutex> lock(mutex_);
    while (!done_) {
      wake_.wait_for(lock, std::chrono::milliseconds(50));
      if (done_) break;
      const std::uint64_t delivered = network_.delivered();
      const int finished = finished_.load();
      if (delivered != lastDelivered || finished != lastFinished || !nobodyWorking()) {
        lastDelivered = delivered, lastFinished = finished, lastProgress = nowSeconds();
      } else if (nowSeconds() - lastProgress > limit_ && !network_.aborted()) {
        network_.abort("stalled: no message for " + formatSeconds(limit_) + " while no node works; " +
                       network_.describeWaits());
      }
    }
  }

  InprocNetwork& network_;
  const std::atomic<int>& finished_;
  int participants_;
  double limit_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool done_ = false;
  std::thread thread_;
};

Mailbox::WaitMode waitModeFor(NodeExecution execution) {
  return execution == NodeExecution::Threads ? Mailbox::WaitMode::BlockThread : Mailbox::WaitMode::SuspendTask;
}

int validatedNodes(int nodes) {
  if (nodes < 1 || nodes > kMaxNodes)
    throw Error("nodes " + std::to_string(nodes) + ": must be between 1 and " + std::to_string(kMaxNodes));
  return nodes;
}

//! The partition in the shape the strategy groups nodes in (radix-k, 2-3 swap and telescoping
//! need subtrees other than pairs), so every group a strategy composites is a k-d subtree.
//! The work estimate for --balance cost (null for space).
std::shared_ptr<const CostField> costFieldFor(const VolumeSource& source, const ClusterOptions& options) {
  if (options.balance == "space") return nullptr;
  if (options.balance != "cost") throw Error("balance \"" + options.balance + "\": expected space or cost");
  const VolumeInfo& info = source.info();
  const glm::vec2 range = options.balanceRange.y > options.balanceRange.x ? options.balanceRange
                                                                          : glm::vec2(info.minValue, info.maxValue);
  return std::make_shared<CostField>(CostField::estimate(source, TransferTable(options.balanceTransfer, 1.0f), range));
}

KdTree buildTree(const VolumeInfo& info, const ClusterOptions& options, std::shared_ptr<const CostField> cost) {
  const TreeShape shape = createStrategy(options.strategy, options.composite)->treeShape(validatedNodes(options.nodes));
  return KdTree::build(info.dims, options.nodes, options.partition, options.slabAxis, shape,
                       PartitionBalance{std::move(cost), options.speeds});
}

}  // namespace

NodeExecution parseNodeExecution(const std::string& text) {
  if (text == "tasks") return NodeExecution::Tasks;
  if (text == "threads") return NodeExecution::Threads;
  throw Error("node execution '" + text + "': expected tasks or threads");
}

VirtualCluster::VirtualCluster(const VolumeSource& source, const ClusterOptions& options)
    : options_(options),
      info_(source.info()),
      cost_(costFieldFor(source, options)),
      tree_(buildTree(info_, options, cost_)),
      layout_(tree_, options.bricksPerNode, PartitionBalance{cost_, {}}),
      strategy_(createStrategy(options.strategy, options.composite)),
      arena_(options.threads, options.nodes),
      network_(options.nodes, waitModeFor(options.execution)),
      nodes_(std::size_t(options.nodes)) {
  const double start = nowSeconds();
  InprocCommunicator host(network_, Communicator::kHost);
  const bool pieces = layout_.perNode() > 1;
  runOnNodes(
      [&](int rank, Communicator& comm) {
        for (int i = 0; i < layout_.perNode(); ++i) receiveBrick(nodes_[std::size_t(rank)], comm);
      },
      true, [&] {
        const VoxelStorage storage = VoxelStorage::forVolume(info_, options.voxels);
        pieces ? distributePieces(source, layout_, storage, host) : distributeBricks(source, tree_, storage, host);
      });
  if (pieces) {
    // First frame's estimate: the cost field's, or the cells of each brick; later frames use the
    // work measured per brick (see brickWork).
    brickCost_ = firstBrickCosts(layout_, cost_.get(), info_.dims);
    held_.assign(std::size_t(options.nodes), {});
  }
  std::vector<const Brick*> bricks;
  for (const NodeState& node : nodes_) {
    bricks.push_back(&node.brick);
    for (const auto& [id, piece] : node.pieces) bricks.push_back(&piece);
  }
  cellRanges_ = CellRangeGrid::fromBricks(info_.dims, bricks);
  distributeSeconds_ = nowSeconds() - start;
}

VirtualCluster::~VirtualCluster() = default;

void VirtualCluster::setBrickCosts(std::vector<double> costs) {
  if (costs.size() != brickCost_.size())
    throw Error(std::to_string(costs.size()) + " brick costs for " + std::to_string(brickCost_.size()) + " bricks");
  brickCost_ = std::move(costs);
}

InprocCommunicator::SendFilter VirtualCluster::faultFilter(int rank) {
  const FaultPlan fault = fault_;
  if (!fault.armed() || fault.node != rank || fault.kind == FaultPlan::Kind::ThrowInRender) return {};
  auto sent = std::make_shared<int>(0);
  return [fault, sent, rank](Message& m) {
    const int index = (*sent)++;
    switch (fault.kind) {
      case FaultPlan::Kind::ThrowInComposite:
        throw Error("injected fault: failed while compositing (tag " +
                    std::to_string(m.tag) + ")");
      case FaultPlan::Kind::DropMessage:
        return index != fault.message;
      case FaultPlan::Kind::DelayMessage:
        if (index == fault.message) std::this_thread::sleep_for(std::chrono::duration<double>(fault.delaySeconds));
        return true;
      case FaultPlan::Kind::CorruptMessage:
        if (index == fault.message) {
          m.flatten();  // corrupt the message's own copy, never the sender's lent pixels
          if (!m.payload.empty()) m.payload[m.payload.size() / 2] += 0.5f;
        }
        return true;
      default:
        return true;
    }
  };
}

template <typename Body>
void VirtualCluster::runOnNodes(Body&& body, bool withHostTask, const std::function<void()>& hostTask) {
  network_.reset();
  std::atomic<int> finished{0};
  auto runHost = [&] {
    try {
      hostTask();
    } catch (const std::exception& e) {
      network_.abort(std::string("host: ") + e.what());
    }
    finished.fetch_add(1);
  };
  auto runNode = [&](int r) {
    InprocCommunicator comm(network_, r, options_.checksums, faultFilter(r));
    try {
      body(r, comm);
    } catch (const std::exception& e) {
      // The first failure names the node; the others then fail with "aborted" and lose.
      network_.abort("node " + std::to_string(r) + ": " + e.what());
    }
    finished.fetch_add(1);
  };
  {
    StallWatchdog watchdog(network_, finished, options_.nodes + (withHostTask ? 1 : 0), options_.stallSeconds);
    if (options_.execution == NodeExecution::Threads) {
      // Not inside arena_: a thread without a free arena slot would be queued as a task there, and
      // blocked nodes holding the slots would starve the rest. The ray caster's parallel loops run
      // in each thread's implicit arena instead.
      std::vector<std::thread> threads;
      threads.reserve(std::size_t(options_.nodes) + 1);
      if (withHostTask) threads.emplace_back(runHost);
      for (int r = 0; r < options_.nodes; ++r) threads.emplace_back(runNode, r);
      for (std::thread& t : threads) t.join();
    } else {
      arena_.execute([&] {
        tbb::task_group group;
        if (withHostTask) group.run(runHost);
        for (int r = 0; r < options_.nodes; ++r) group.run([&, r] { runNode(r); });
        group.wait();
      });
    }
  }
  if (network_.aborted()) throw Error(network_.abortReason());
}

const OcclusionGrid& VirtualCluster::occlusionGridFor(const TransferTable& table, float scale, float bias, float stopAt) {
  OcclusionGridCache& c = occlusionGrid_;
  const glm::vec4* entries = table.entries();
  const std::size_t count = std::size_t(TransferTable::kSize) + 1;
  const bool same = c.grid && c.scale == scale && c.bias == bias && c.stopAt == stopAt && c.entries.size() == count &&
                    std::equal(c.entries.begin(), c.entries.end(), entries);
  if (!same) {
    c.grid.emplace(cellRanges_, table, scale, bias, stopAt);
    c.entries.assign(entries, entries + count);
    c.scale = scale, c.bias = bias, c.stopAt = stopAt;
  }
  return *c.grid;
}

FrameResult VirtualCluster::renderFrame(const FrameRequest& request) {
  if (request.width < 1 || request.height < 1 || request.width > 16384 || request.height > 16384)
    throw Error("image size " + std::to_string(request.width) + "x" + std::to_string(request.height) +
                ": each side must be between 1 and 16384");
  const double start = nowSeconds();
  FramePlan plan(request, tree_, info_.spacing, resolveValueRange(request.settings, info_), *strategy_);
  nodesRendered_ = 0;
  plan.nodesRendered = &nodesRendered_;
  std::optional<OcclusionMap> occlusion;
  // Culling never moves an image away from the single-node one (with --ert 1 it changes nothing;
  // with early termination it removes light that local termination keeps): it saves work, and
  // rests where it saved little (CullingRest).
  // Front-to-back waves replace the map (one brick per node; over-decomposed bricks are scheduled
  // on demand, so they keep the map).
  const bool waves = request.settings.frontToBackWaves && options_.nodes > 1 && layout_.perNode() == 1;
  const bool culling = !waves && request.settings.cullOccluded && options_.nodes * layout_.perNode() > 1;
  double mapSeconds = 0;
  if (culling && cullingRest_.mapThisFrame()) {
    const double mapStart = nowSeconds();
    const glm::vec2 map = normalisingScaleBias(plan.valueRange);
    const OcclusionGrid& grid = occlusionGridFor(plan.table, map.x, map.y, request.settings.earlyTermination);
    if (grid.active())
      arena_.execute([&] {
        occlusion.emplace(grid, plan.camera, glm::vec3(info_.dims - 1) * info_.spacing, info_.spacing,
                          request.settings);
      });
    if (occlusion) {
      plan.occlusion = &*occlusion;
      mapSeconds = nowSeconds() - mapStart;  // with the grid for a new transfer function, where it was built
    }
  }
  // Waves: every brick rendered, nearest first where they overlap, by a task beside the nodes';
  // each node composites as soon as its brick is done (bricks behind may still be rendering).
  std::vector<RenderedBrick> rendered;
  if (waves) {
    rendered.resize(nodes_.size());
    plan.waves = &rendered;
  }
  BrickSchedule schedule;
  std::vector<std::set<int>> heldBefore;
  if (layout_.perNode() > 1) {
    heldBefore = held_;
    schedule = scheduleBricks(layout_, brickCost_, options_.speeds, held_);
    plan.bricks = &schedule;
  }
  struct RestoreHeld {  // a failed frame may not have shipped its bricks: ship them again next time
    std::vector<std::set<int>>& held;
    std::vector<std::set<int>>& before;
    bool done = false;
    ~RestoreHeld() {
      if (!done && !before.empty()) held = std::move(before);
    }
  } restoreHeld{held_, heldBefore};

  FrameResult result;
  if (request.recordPhases) {
    result.phases = std::make_shared<PhaseRecord>();
    result.phases->frame = plan.frame();
    result.phases->cells.resize(std::size_t(options_.nodes));
  }
  std::vector<NodeReport> reports(std::size_t(options_.nodes));
  const FaultPlan fault = fault_;
  struct Disarm {  // the plan is for this frame only, whether it fails or not
    FaultPlan& plan;
    ~Disarm() { plan = FaultPlan{}; }
  } disarm{fault_};
  runOnNodes(
      [&](int rank, Communicator& comm) {
        if (fault.kind == FaultPlan::Kind::ThrowInRender && fault.node == rank)
          throw Error("injected fault: failed while rendering");  // the frame's error names the node
        reports[std::size_t(rank)] = runNodeFrame(nodes_[std::size_t(rank)], comm, plan, result.phases.get());
      },
      waves, [&] {
        arena_.execute([&] {
          renderInWaves(nodes_, plan, rendered, [&](int rank) {
            // One communicator per message: bricks finish on several threads at once.
            InprocCommunicator(network_, Communicator::kHost).send(rank, kBrickRenderedTag, Message{});
          });
        });
      });

  if (plan.occlusion) {
    std::uint64_t rays = 0, occluded = 0;
    for (const NodeReport& r : reports) rays += r.rays, occluded += r.occluded;
    cullingRest_.afterFrame(rays, occluded);
  }

  // Gather: every tile is in the host's mailbox by now.
  const double gatherStart = nowSeconds();
  std::vector<Message> tiles;
  tiles.reserve(std::size_t(options_.nodes));
  for (Message tile; network_.mailbox(Communicator::kHost).tryTake(Mailbox::kAnySource, kTileTag, tile);)
    tiles.push_back(std::move(tile));
  if (int(tiles.size()) != options_.nodes) {
    std::vector<bool> arrived(std::size_t(options_.nodes), false);
    for (const Message& t : tiles)
      if (t.source >= 0 && t.source < options_.nodes) arrived[std::size_t(t.source)] = true;
    std::string missing;
    for (int r = 0; r < options_.nodes; ++r)
      if (!arrived[std::size_t(r)]) missing += (missing.empty() ? "" : ", ") + std::to_string(r);
    throw Error("gather: no tile arrived from node " + missing + " (the message was lost)");
  }
  arena_.execute([&] { result.image = assembleTiles(tiles, plan.frame(), &result.tiles); });
  const double end = nowSeconds();

  FrameStats& s = result.stats;
  s.nodes = options_.nodes;
  s.width = request.width;
  s.height = request.height;
  s.strategy = std::string(strategy_->name());
  s.partition = toString(options_.partition);
  s.wallSeconds = end - start;
  s.gatherSeconds = end - gatherStart;
  s.occlusionMapSeconds = mapSeconds;
  s.distributeSeconds = distributeSeconds_;
  s.peakRssBytes = peakResidentBytes();
  restoreHeld.done = true;
  for (const NodeReport& n : reports)
    for (const NodeReport::BrickRender& b : n.bricks) brickCost_[std::size_t(b.brick)] = brickWork(b.samples, b.rays);
  s.network = options_.network;
  if (!options_.speeds.empty())
    for (NodeReport& n : reports) n.speed = options_.speeds[std::size_t(n.rank)];
  // Every node read the same steady clock: one origin puts them all on the frame's time line.
  for (NodeReport& n : reports) n.rebaseTimes(start);
  s.perNode = std::move(reports);
  return result;
}

}  // namespace kdswap
