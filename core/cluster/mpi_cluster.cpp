// MPI frame. Before the network runs, collective calls: the ranks agree on the job, load their
// nodes' bricks (parallel I/O) and merge the culling summary. Then, per rank, K node tasks (and on
// rank 0 the host task) in one oneTBB arena, talking through MpiCommunicator: every node reports
// "ready" to the host; the host starts the frame on all nodes at once (so wall_s excludes loading,
// as in VirtualCluster), then gathers each node's tile and report.
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
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_group.h>

#include "core/cluster/host.h"
#include "core/cluster/job_description.h"
#include "core/comm/mpi_agreement.h"
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
                      {"bytes_sent", p.bytesSent}, {"bytes_received", p.bytesReceived},
                      {"messages_sent", p.messagesSent}, {"messages_received", p.messagesReceived},
                      {"start_s", p.start}, {"end_s", p.end}});
  nlohmann::json bricks = nlohmann::json::array();
  for (const NodeReport::BrickRender& b : n.bricks)
    bricks.push_back({{"brick", b.brick}, {"seconds", b.seconds}, {"rays", b.rays}, {"samples", b.samples},
                      {"start_s", b.start}, {"end_s", b.end}});
  return {{"rank", n.rank},
          {"render_s", n.renderSeconds},
          {"rays", n.rays},
          {"occluded", n.occluded},
          {"samples", n.samples},
          {"private_bytes", n.privateBytes},
          {"timed", n.timed},
          {"render_start_s", n.renderStart},
          {"render_end_s", n.renderEnd},
          {"phases", std::move(phases)},
          {"bricks", std::move(bricks)}};
}

NodeReport reportFromJson(const std::string& text, int node) {
  try {
    const nlohmann::json j = nlohmann::json::parse(text);
    NodeReport n;
    n.rank = j.at("rank").get<int>();
    n.renderSeconds = j.at("render_s").get<double>();
    n.rays = j.at("rays").get<std::uint64_t>();
    n.occluded = j.at("occluded").get<std::uint64_t>();
    n.samples = j.at("samples").get<std::uint64_t>();
    n.privateBytes = j.at("private_bytes").get<std::uint64_t>();
    n.timed = j.at("timed").get<bool>();
    n.renderStart = j.at("render_start_s").get<double>();
    n.renderEnd = j.at("render_end_s").get<double>();
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
      s.messagesSent = p.at("messages_sent").get<std::uint64_t>();
      s.messagesReceived = p.at("messages_received").get<std::uint64_t>();
      s.start = p.at("start_s").get<double>();
      s.end = p.at("end_s").get<double>();
      n.phases.push_back(std::move(s));
    }
    for (const auto& b : j.at("bricks"))
      n.bricks.push_back(NodeReport::BrickRender{b.at("brick").get<int>(), b.at("seconds").get<double>(),
                                                 b.at("rays").get<std::uint64_t>(), b.at("samples").get<std::uint64_t>(),
                                                 b.at("start_s").get<double>(), b.at("end_s").get<double>()});
    return n;
  } catch (const nlohmann::json::exception& e) {
    throw Error("report from node " + std::to_string(node) + ": malformed JSON: " + e.what());
  }
}

//! Reads node `node`'s brick straight from the source: only the voxels it stores (owned box plus
//! the replicated and ghost layers), as distributeBricks + receiveBrick would have given it; with
//! over-decomposition its M sub-bricks, as distributePieces would have (kept shippable: another
//! node may render one).
void loadBricks(NodeState& state, int node, const VolumeSource& source, const KdTree& tree, const BrickLayout& layout,
                const VoxelStorage& storage) {
  const VolumeInfo& info = source.info();
  auto read = [&](const VoxelBox& owned) {
    const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
    std::vector<float> raw(stored.empty() ? 0 : std::size_t(stored.count()));
    if (!stored.empty()) source.read(stored, raw.data());
    return raw;
  };
  state.rank = node;
  if (layout.perNode() == 1) {
    const VoxelBox& owned = tree.brick(node);
    state.brick = Brick(owned, info.dims, info.spacing, read(owned), Brick::Shipping::No, Brick::kCellShiftByVolume,
                        storage);
    return;
  }
  for (int b = node * layout.perNode(); b < (node + 1) * layout.perNode(); ++b)
    state.pieces.insert_or_assign(
        b, Brick(layout.box(b), info.dims, info.spacing, read(layout.box(b)), Brick::Shipping::Yes,
                 Brick::kCellShiftByVolume, storage));
}

//! Collective: throws on every rank when any rank has a problem (see firstProblemOfAnyRank).
void agreeOrThrow(const std::string& problem) {
  const std::string first = firstProblemOfAnyRank(problem);
  if (!first.empty()) throw Error(first);
}

//! Collective: rank 0 compares every rank's job with its own; "" when all agree.
std::string jobDisagreement(const JobDescription& mine, int nodesPerRank) {
  const std::vector<std::string> all = gatherTextOnRankZero(mine.serialize());
  for (std::size_t r = 1; r < all.size(); ++r) {
    const int first = int(r) * nodesPerRank;
    const std::string who = "rank " + std::to_string(r) + " (nodes " + std::to_string(first) + ".." +
                            std::to_string(first + nodesPerRank - 1) + ")";
    std::string difference;
    try {  // nothing may throw on rank 0 alone between collectives
      difference = JobDescription::parse(all[r], who).firstDifference(mine, "on rank " + std::to_string(r), "on rank 0");
    } catch (const std::exception& e) {
      return e.what();
    }
    if (!difference.empty())
      return who + " was started with another job than rank 0 (every rank must open the same volume with the same "
                   "options): " + difference;
  }
  return "";
}

//! Collective: MPI_Allreduce in place of `count` elements; MPI counts are ints, so in chunks.
template <typename T>
void allReduceInChunks(T* data, std::size_t count, MPI_Datatype type, MPI_Op op) {
  constexpr std::size_t kChunk = std::size_t(1) << 28;
  for (std::size_t at = 0; at < count; at += kChunk)
    MPI_Allreduce(MPI_IN_PLACE, data + at, int(std::min(kChunk, count - at)), type, op, MPI_COMM_WORLD);
}

//! Collective: the whole volume's cell summary from every rank's bricks, merged (min of minima,
//! max of maxima; fine codes min of lo, max of hi).
CellRangeGrid mergedCellSummary(const glm::ivec3& dims, const std::vector<NodeState>& states) {
  std::vector<const Brick*> bricks;
  for (const NodeState& s : states) {
    bricks.push_back(&s.brick);
    for (const auto& [id, piece] : s.pieces) bricks.push_back(&piece);
  }
  std::vector<glm::vec2> ranges = CellRangeGrid::rangesOf(dims, bricks);
  std::vector<float> lows(ranges.size()), highs(ranges.size());
  for (std::size_t i = 0; i < ranges.size(); ++i) lows[i] = ranges[i].x, highs[i] = ranges[i].y;
  allReduceInChunks(lows.data(), lows.size(), MPI_FLOAT, MPI_MIN);
  allReduceInChunks(highs.data(), highs.size(), MPI_FLOAT, MPI_MAX);
  for (std::size_t i = 0; i < ranges.size(); ++i) ranges[i] = glm::vec2(lows[i], highs[i]);
  // Every rank picks the same cells for fine codes from the same merged ranges.
  CellRangeGrid grid = CellRangeGrid::withRanges(dims, std::move(ranges), bricks);
  std::vector<std::uint8_t> codeLows(grid.fine.size()), codeHighs(grid.fine.size());
  for (std::size_t i = 0; i < grid.fine.size(); ++i) codeLows[i] = grid.fine[i].lo, codeHighs[i] = grid.fine[i].hi;
  allReduceInChunks(codeLows.data(), codeLows.size(), MPI_UNSIGNED_CHAR, MPI_MIN);
  allReduceInChunks(codeHighs.data(), codeHighs.size(), MPI_UNSIGNED_CHAR, MPI_MAX);
  for (std::size_t i = 0; i < grid.fine.size(); ++i) grid.fine[i] = CellRangeGrid::FineCodes{codeLows[i], codeHighs[i]};
  return grid;
}

//! Collective: --balance cost's work estimate, each rank classifying its share of the block layers
//! (reading only those voxels), summed into the whole field on every rank.
std::shared_ptr<const CostField> distributedCostField(const VolumeSource& source, const ClusterOptions& options,
                                                      int rank, int ranks) {
  const glm::ivec3 dims = source.info().dims;
  const int layers = CostField::blockLayers(dims);
  const int first = int(std::int64_t(layers) * rank / ranks), end = int(std::int64_t(layers) * (rank + 1) / ranks);
  const glm::vec2 range = options.balanceRange.y > options.balanceRange.x
                              ? options.balanceRange
                              : glm::vec2(source.info().minValue, source.info().maxValue);
  std::string problem;
  std::vector<float> costs;
  try {
    costs = CostField::estimateLayers(source, TransferTable(options.balanceTransfer, 1.0f), range, first, end)
                .blockCosts();
  } catch (const std::exception& e) {
    problem = e.what();
  }
  agreeOrThrow(problem);
  allReduceInChunks(costs.data(), costs.size(), MPI_FLOAT, MPI_SUM);  // each block from one rank, others 0
  return std::make_shared<CostField>(CostField::fromBlockCosts(dims, std::move(costs)));
}

void runNode(MpiNetwork& net, MpiRankFrame& frame, int local) {
  const int node = net.firstLocalNode() + local;
  MpiCommunicator comm(net, node);
  Message ready;
  ready.header = {std::int64_t(frame.loadSeconds[std::size_t(local)] * 1e9), std::int64_t(frame.mapSeconds * 1e9)};
  comm.send(Communicator::kHost, kReadyTag, std::move(ready));
  comm.receive(Communicator::kHost, kGoTag);
  // Ranks' clocks are not one clock: each node's times count from its own arrival of "start",
  // which trails the host's start by one message.
  const double started = nowSeconds();
  NodeReport report = runNodeFrame(frame.states[std::size_t(local)], comm, *frame.plan, nullptr);
  for (const NodeReport::BrickRender& b : report.bricks)  // one node renders each brick: no two write one entry
    frame.brickWorkHere[std::size_t(b.brick)] = brickWork(b.samples, b.rays);
  frame.raysHere += report.rays;
  frame.occludedHere += report.occluded;
  report.rebaseTimes(started);
  Message out;
  out.text = reportToJson(report).dump();
  comm.send(Communicator::kHost, kReportTag, std::move(out));
}

void runHost(MpiNetwork& net, const MpiRankFrame& frame, MpiFrameOutcome& outcome) {
  MpiCommunicator host(net, Communicator::kHost);
  const int nodes = net.nodes();
  outcome.nodeLoadSeconds.assign(std::size_t(nodes), 0.0);
  double mapSeconds = 0;
  for (int v = 0; v < nodes; ++v) {
    const Message m = host.receive(v, kReadyTag);
    if (m.header.size() != 2) throw Error("host: malformed ready message from node " + std::to_string(v));
    outcome.nodeLoadSeconds[std::size_t(v)] = double(m.header[0]) * 1e-9;
    mapSeconds = std::max(mapSeconds, double(m.header[1]) * 1e-9);
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
  result.image = assembleTiles(tiles, frame.plan->frame(), &result.tiles);
  const double end = nowSeconds();

  FrameStats& s = result.stats;
  s.nodes = nodes;
  s.width = frame.request.width;
  s.height = frame.request.height;
  s.strategy = std::string(frame.strategy->name());
  s.partition = toString(frame.options.partition);
  s.network = frame.options.network;  // a model of a machine's network, for the modelled time
  // The occlusion map belongs to the frame (it depends on the view), as in the virtual cluster,
  // whose wall time includes it; here every rank computes it before the frame starts.
  s.wallSeconds = end - start + mapSeconds;
  s.gatherSeconds = end - gatherStart;
  s.occlusionMapSeconds = mapSeconds;
  // Every rank reads its bricks at once (parallel I/O): the slowest node's load is the figure.
  s.distributeSeconds = *std::max_element(outcome.nodeLoadSeconds.begin(), outcome.nodeLoadSeconds.end());
  if (!frame.options.speeds.empty())  // modelled times divide each node's work by its speed
    for (NodeReport& n : reports) n.speed = frame.options.speeds[std::size_t(n.rank)];
  s.perNode = std::move(reports);
}

}  // namespace

MpiRankFrame::MpiRankFrame(const VolumeSource& source, const FrameRequest& request, const ClusterOptions& options,
                           int ranks, int nodesPerRank, std::shared_ptr<const CostField> cost)
    : source(source),
      request(request),
      options(options),
      nodesPerRank(nodesPerRank),
      arena(options.threads, nodesPerRank),
      // The partition in the strategy's group shape, exactly as the in-process cluster builds it.
      strategy(createStrategy(options.strategy, options.composite)),
      tree(KdTree::build(source.info().dims, ranks * nodesPerRank, options.partition, options.slabAxis,
                         strategy->treeShape(ranks * nodesPerRank), PartitionBalance{cost, options.speeds})),
      layout(tree, options.bricksPerNode, PartitionBalance{cost, {}}),
      storage(VoxelStorage::forVolume(source.info(), options.voxels)),
      states(std::size_t(nodesPerRank)),
      loadSeconds(std::size_t(nodesPerRank), 0.0) {
  plan.emplace(this->request, tree, source.info().spacing, resolveValueRange(request.settings, source.info()),
               *strategy);
  if (layout.perNode() > 1) {
    brickCost = firstBrickCosts(layout, cost.get(), source.info().dims);
    held.assign(std::size_t(ranks * nodesPerRank), {});
  }
}

void MpiRankFrame::setView(const View& view, float phaseShift) {
  const VolumeInfo& info = source.info();
  request.view = view;
  request.settings.phaseShift = phaseShift;
  plan.emplace(request, tree, info.spacing, resolveValueRange(request.settings, info), *strategy);
  occlusionMap.reset();
  mapSeconds = 0;
  if (!occlusionGrid || !cullingRest.mapThisFrame()) return;
  const double start = nowSeconds();
  arena.execute([&] {
    occlusionMap.emplace(*occlusionGrid, plan->camera, glm::vec3(info.dims - 1) * info.spacing, info.spacing,
                         request.settings);
  });
  plan->occlusion = &*occlusionMap;
  mapSeconds = nowSeconds() - start;
}

std::unique_ptr<MpiRankFrame> prepareRankFrame(const VolumeSource& source, const FrameRequest& request,
                                               const ClusterOptions& options, int nodesPerRank) {
  const int ranks = worldSize(), rank = worldRank();
  std::string problem;
  // No brick is read until every rank describes the same job: a rank with another file or other
  // options would otherwise render its share of a different picture.
  JobDescription job;
  try {
    job = describeJob(source, request, options, nodesPerRank);  // reads the middle slice
  } catch (const std::exception& e) {
    problem = e.what();
  }
  agreeOrThrow(problem);
  agreeOrThrow(jobDisagreement(job, nodesPerRank));

  std::shared_ptr<const CostField> cost;
  if (options.balance == "cost") cost = distributedCostField(source, options, rank, ranks);

  std::unique_ptr<MpiRankFrame> frame;
  try {
    frame = std::make_unique<MpiRankFrame>(source, request, options, ranks, nodesPerRank, std::move(cost));
  } catch (const std::exception& e) {
    problem = e.what();
  }
  agreeOrThrow(problem);

  try {
    frame->arena.execute([&] {
      tbb::parallel_for(0, nodesPerRank, [&](int i) {
        const double start = nowSeconds();
        loadBricks(frame->states[std::size_t(i)], rank * nodesPerRank + i, source, frame->tree, frame->layout,
                   frame->storage);
        frame->loadSeconds[std::size_t(i)] = nowSeconds() - start;
      });
    });
  } catch (const std::exception& e) {
    problem = e.what();
  }
  agreeOrThrow(problem);

  // Occlusion culling, as VirtualCluster::renderFrame does it: the same summary (here merged from
  // the ranks' bricks), the same grid and the same map, so frames equal the virtual cluster's.
  if (request.settings.cullOccluded && frame->layout.bricks() > 1) {
    frame->arena.execute([&] {
      const CellRangeGrid cells = mergedCellSummary(source.info().dims, frame->states);
      const glm::vec2 map = normalisingScaleBias(frame->plan->valueRange);
      frame->occlusionGrid.emplace(cells, frame->plan->table, map.x, map.y, request.settings.earlyTermination);
    });
    if (!frame->occlusionGrid->active()) frame->occlusionGrid.reset();
  }
  frame->setView(request.view, request.settings.phaseShift);
  return frame;
}

MpiFrameOutcome renderFrameOverMpi(MpiNetwork& net, MpiRankFrame& frame) {
  MpiFrameOutcome outcome;
  outcome.ranks = net.worldSize();
  outcome.nodesPerRank = net.nodesPerRank();
  const std::string where = "rank " + std::to_string(net.worldRank());
  const bool pieces = frame.layout.perNode() > 1;
  if (pieces) {  // local, the same on every rank: the same book gives the same hand-out
    frame.schedule = scheduleBricks(frame.layout, frame.brickCost, frame.options.speeds, frame.held);
    frame.plan->bricks = &frame.schedule;
    frame.brickWorkHere.assign(frame.brickCost.size(), 0.0);
  }
  frame.raysHere = 0, frame.occludedHere = 0;
  bool hostDone = false;
  try {
    frame.arena.execute([&] {
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
            runHost(net, frame, outcome);
            hostDone = true;
          });
        });
      for (int i = 0; i < net.nodesPerRank(); ++i)
        group.run([&, i] {
          guarded("node " + std::to_string(net.firstLocalNode() + i) + " (" + where + ")",
                  [&] { runNode(net, frame, i); });
        });
      group.wait();
    });
  } catch (const std::exception& e) {
    net.abortAll(where + ": " + e.what());
  }
  net.finish();

  // The progress thread has stopped: MPI calls from this thread are now serialized with it.
  const unsigned long long rss = peakResidentBytes();
  outcome.rankPeakRss.assign(std::size_t(net.worldSize()), 0);
  static_assert(sizeof(unsigned long long) == sizeof(std::uint64_t));
  MPI_Gather(&rss, 1, MPI_UNSIGNED_LONG_LONG, outcome.rankPeakRss.data(), 1, MPI_UNSIGNED_LONG_LONG, 0,
             MPI_COMM_WORLD);
  if (frame.plan->occlusion) {  // the rest rule on the whole frame's counts, alike on every rank
    std::uint64_t counts[2] = {frame.raysHere, frame.occludedHere};
    MPI_Allreduce(MPI_IN_PLACE, counts, 2, MPI_UINT64_T, MPI_SUM, MPI_COMM_WORLD);
    frame.cullingRest.afterFrame(counts[0], counts[1]);
  }
  if (pieces) {
    // The next frame's estimates: each brick's work from the rank whose node rendered it (the
    // others hold 0). Only after a frame every rank completed: a failed one ends the run anyway.
    std::vector<double> work = frame.brickWorkHere;
    int failed = net.aborted() ? 1 : 0;
    MPI_Allreduce(MPI_IN_PLACE, &failed, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    allReduceInChunks(work.data(), work.size(), MPI_DOUBLE, MPI_SUM);
    if (!failed) frame.brickCost = std::move(work);
  }
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
