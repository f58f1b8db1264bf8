// MPI frame: per rank, K node tasks (and on rank 0 the host task) in one oneTBB arena, talking
// through MpiCommunicator. The protocol around the unchanged node program: every node loads its
// brick and reports "ready" to the host; the host starts the frame on all nodes at once (so
// wall_s excludes loading, as in VirtualCluster), then gathers each node's tile and report.
#include "core/cluster/mpi_cluster.h"

#if KDSWAP_HAVE_MPI

#include <algorithm>
#include <atomic>
#include <memory>

// The C API only: Open MPI's deprecated C++ bindings would need libmpi_cxx.
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <oneapi/tbb/task_arena.h>
#include <oneapi/tbb/task_group.h>

#include "core/cluster/host.h"
#include "core/cluster/job_description.h"
#include "core/comm/mpi_communicator.h"
#include "core/render/reference_render.h"
#include "core/util/clock.h"
#include "core/util/memory.h"

namespace kdswap {
namespace {

nlohmann::json reportToJson(const NodeReport& n) {
  nlohmann::json phases = nlohmann::json::array();
  for (const PhaseStats& p : n.phases)
    phases.push_back({{"label", p.label}, {"partner", p.partner},
                      {"region", {p.region.x, p.region.y, p.region.w, p.region.h}},
                      {"compute_s", p.computeSeconds}, {"wait_s", p.waitSeconds}, {"pixels", p.pixels},
                      {"bytes_sent", p.bytesSent}, {"bytes_received", p.bytesReceived}});
  return {{"rank", n.rank}, {"render_s", n.renderSeconds}, {"rays", n.rays}, {"samples", n.samples},
          {"private_bytes", n.privateBytes}, {"phases", std::move(phases)}};
}

NodeReport reportFromJson(const std::string& text, int node) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    NodeReport n;
    n.rank = j.at("rank").get<int>();
    n.renderSeconds = j.at("render_s").get<double>();
    n.rays = j.at("rays").get<std::uint64_t>();
    n.samples = j.at("samples").get<std::uint64_t>();
    n.privateBytes = j.at("private_bytes").get<std::uint64_t>();
    for (const auto& p : j.at("phases")) {
      PhaseStats s;
      s.label = p.at("label").get<std::string>();
      s.partner = p.at("partner").get<int>();
      const auto& r = p.at("region");
      s.region = Rect{r.at(0).get<int>(), r.at(1).get<int>(), r.at(2).get<int>(), r.at(3).get<int>()};
      s.computeSeconds = p.at("compute_s").get<double>();
      s.waitSeconds = p.at("wait_s").get<double>();
      s.pixels = p.at("pixels").get<std::int64_t>();
      s.bytesSent = p.at("bytes_sent").get<std::uint64_t>();
      s.bytesReceived = p.at("bytes_received").get<std::uint64_t>();
      n.phases.push_back(std::move(s));
    }
    return n;
  } catch (const nlohmann::json::exception& e) {
    throw Error("report from node " + std::to_string(node) + ": malformed JSON: " + e.what());
  }
}

//! Reads node `node`'s brick straight from the source: only the voxels it stores (owned box plus
//! the replicated and ghost layers), as distributeBricks + receiveBrick would have given it.
void loadBrick(NodeState& state, int node, const VolumeSource& source, const KdTree& tree,
               const VoxelStorage& storage) {
  const VolumeInfo& info = source.info();
  const VoxelBox& owned = tree.brick(node);
  const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
  std::vector<float> raw(stored.empty() ? 0 : std::size_t(stored.count()));
  if (!stored.empty()) source.read(stored, raw.data());
  state.rank = node;
  state.brick = Brick(owned, info.dims, info.spacing, std::move(raw), Brick::Shipping::No, 0, storage);
}

//! Everything the node and host tasks of one rank share for the frame (read-only to the nodes).
struct FrameSetup {
  const VolumeSource& source;
  KdTree tree;
  std::unique_ptr<Strategy> strategy;
  FramePlan plan;
  VoxelStorage storage;  //!< every rank derives it from the same volume and options
  JobDescription job;    //!< this rank's; rank 0's host checks every rank's against its own
};

void runNode(MpiNetwork& net, const FrameSetup& setup, NodeState& state, int node) {
  MpiCommunicator comm(net, node);
  // No brick is read until the host has seen that every rank describes the same job: a rank with
  // another file or other options would otherwise render its share of a different picture.
  if (node == net.firstLocalNode()) {
    Message job;
    job.text = setup.job.serialize();
    comm.send(Communicator::kHost, kJobTag, std::move(job));
  }
  comm.receive(Communicator::kHost, kLoadTag);
  const double start = nowSeconds();
  loadBrick(state, node, setup.source, setup.tree, setup.storage);
  Message ready;
  ready.header = {std::int64_t((nowSeconds() - start) * 1e9)};
  comm.send(Communicator::kHost, kReadyTag, std::move(ready));
  comm.receive(Communicator::kHost, kGoTag);
  const NodeReport report = runNodeFrame(state, comm, setup.plan, nullptr);
  Message out;
  out.text = reportToJson(report).dump();
  comm.send(Communicator::kHost, kReportTag, std::move(out));
}

void runHost(MpiNetwork& net, const FrameSetup& setup, const ClusterOptions& options, MpiFrameOutcome& outcome) {
  MpiCommunicator host(net, Communicator::kHost);
  const int nodes = net.nodes();
  for (int rank = 0; rank < net.worldSize(); ++rank) {
    const int first = rank * net.nodesPerRank();
    const std::string who = "rank " + std::to_string(rank) + " (nodes " + std::to_string(first) + ".." +
                            std::to_string(first + net.nodesPerRank() - 1) + ")";
    const JobDescription job = JobDescription::parse(host.receive(first, kJobTag).text, who);
    const std::string difference = job.firstDifference(setup.job, "on rank " + std::to_string(rank), "on rank 0");
    if (!difference.empty())
      throw Error(who + " was started with another job than rank 0 (every rank must open the same volume with the "
                  "same options): " + difference);
  }
  for (int v = 0; v < nodes; ++v) host.send(v, kLoadTag, Message{});
  outcome.nodeLoadSeconds.assign(std::size_t(nodes), 0.0);
  for (int v = 0; v < nodes; ++v) {
    const Message m = host.receive(v, kReadyTag);
    if (m.header.size() != 1) throw Error("host: malformed ready message from node " + std::to_string(v));
    outcome.nodeLoadSeconds[std::size_t(v)] = double(m.header[0]) * 1e-9;
  }
  const double start = nowSeconds();
  for (int v = 0; v < nodes; ++v) host.send(v, kGoTag, Message{});
  std::vector<Message> tiles(static_cast<std::size_t>(nodes));
  std::vector<NodeReport> reports(static_cast<std::size_t>(nodes));
  for (int v = 0; v < nodes; ++v) {
    tiles[std::size_t(v)] = host.receive(v, kTileTag);
    reports[std::size_t(v)] = reportFromJson(host.receive(v, kReportTag).text, v);
  }
  const double gatherStart = nowSeconds();
  FrameResult& result = outcome.result;
  result.image = assembleTiles(tiles, setup.plan.frame(), &result.tiles);
  const double end = nowSeconds();

  FrameStats& s = result.stats;
  s.nodes = nodes;
  s.width = setup.plan.request.width;
  s.height = setup.plan.request.height;
  s.strategy = std::string(setup.strategy->name());
  s.partition = toString(options.partition);
  s.wallSeconds = end - start;
  s.gatherSeconds = end - gatherStart;
  // Every rank reads its bricks at once (parallel I/O): the slowest node's load is the figure.
  s.distributeSeconds = *std::max_element(outcome.nodeLoadSeconds.begin(), outcome.nodeLoadSeconds.end());
  s.perNode = std::move(reports);
}

}  // namespace

MpiFrameOutcome renderFrameOverMpi(MpiNetwork& net, const VolumeSource* source, const FrameRequest* request,
                                   const ClusterOptions& options) {
  MpiFrameOutcome outcome;
  outcome.ranks = net.worldSize();
  outcome.nodesPerRank = net.nodesPerRank();
  const std::string where = "rank " + std::to_string(net.worldRank());
  bool hostDone = false;
  if (source && request) {
    try {
      const VolumeInfo& info = source->info();
      // The partition in the strategy's group shape, exactly as the in-process cluster builds it.
      std::unique_ptr<Strategy> strategy = createStrategy(options.strategy, options.composite);
      KdTree tree = KdTree::build(info.dims, net.nodes(), options.partition, options.slabAxis,
                                  strategy->treeShape(net.nodes()));
      const FramePlan plan(*request, tree, info.spacing, resolveValueRange(request->settings, info), *strategy);
      const FrameSetup setup{*source, std::move(tree), std::move(strategy), plan,
                             VoxelStorage::forVolume(info, options.voxels),
                             describeJob(*source, *request, options, net.nodesPerRank())};
      std::vector<NodeState> states(std::size_t(net.nodesPerRank()));
      tbb::task_arena arena(options.threads > 0 ? options.threads : tbb::task_arena::automatic);
      arena.execute([&] {
        tbb::task_group group;
        // A task that fails tells every rank (abortAll) unless it failed because of an abort,
        // which the failure that caused it has already reported.
        auto guarded = [&](const std::string& who, auto&& body) {
          try {
            body();
          } catch (const FrameAborted&) {
          } catch (const std::exception& e) {
            net.abortAll(who + ": " + e.what());
          }
        };
        if (net.worldRank() == 0)
          group.run([&] {
            guarded("host (" + where + ")", [&] {
              runHost(net, setup, options, outcome);
              hostDone = true;
            });
          });
        for (int i = 0; i < net.nodesPerRank(); ++i)
          group.run([&, i] {
            const int node = net.firstLocalNode() + i;
            guarded("node " + std::to_string(node) + " (" + where + ")",
                    [&] { runNode(net, setup, states[std::size_t(i)], node); });
          });
        group.wait();
      });
    } catch (const std::exception& e) {
      net.abortAll(where + ": " + e.what());
    }
  }
  net.finish();

  // The progress thread has stopped: MPI calls from this thread are now serialized with it.
  const unsigned long long rss = peakResidentBytes();
  outcome.rankPeakRss.assign(std::size_t(net.worldSize()), 0);
  static_assert(sizeof(unsigned long long) == sizeof(std::uint64_t));
  MPI_Gather(&rss, 1, MPI_UNSIGNED_LONG_LONG, outcome.rankPeakRss.data(), 1, MPI_UNSIGNED_LONG_LONG, 0,
             MPI_COMM_WORLD);
  outcome.ok = net.worldRank() == 0 ? hostDone && !net.aborted() : !net.aborted();
  if (!outcome.ok) outcome.error = net.abortReason();
  if (outcome.ok && net.worldRank() == 0)
    outcome.result.stats.peakRssBytes = *std::max_element(outcome.rankPeakRss.begin(), outcome.rankPeakRss.end());
  return outcome;
}

nlohmann::json MpiFrameOutcome::statsJson() const {
  nlohmann::json j = result.stats.toJson();
  j["ranks"] = ranks;
  j["nodes_per_rank"] = nodesPerRank;
  nlohmann::json perRank = nlohmann::json::array();
  for (int r = 0; r < ranks; ++r) {
    double load = 0;
    for (int v = r * nodesPerRank; v < (r + 1) * nodesPerRank && v < int(nodeLoadSeconds.size()); ++v)
      load = std::max(load, nodeLoadSeconds[std::size_t(v)]);
    perRank.push_back({{"rank", r},
                       {"nodes", {r * nodesPerRank, (r + 1) * nodesPerRank - 1}},
                       {"load_s", load},
                       {"peak_rss_bytes", r < int(rankPeakRss.size()) ? rankPeakRss[std::size_t(r)] : 0}});
  }
  j["per_rank"] = std::move(perRank);
  return j;
}

}  // namespace kdswap

#endif  // KDSWAP_HAVE_MPI
