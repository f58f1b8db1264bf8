// The per-node timeline (issue: a true Gantt chart): each node's render interval and each phase's
// wall interval, in seconds since the frame's start, as the virtual cluster reports them.
#include <doctest/doctest.h>

#include <algorithm>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/composite/registry.h"
#include "test_support.h"

using namespace kdswap;

namespace {

// Rebasing subtracts two readings of ~1e5 s; their rounding is ~1e-11 s.
constexpr double kClockTolerance = 1e-9;

FrameRequest smallRequest() {
  FrameRequest request;
  request.width = 40;
  request.height = 36;
  request.transfer = test::testTransfer();
  request.view.azimuthDeg = 30.0f;
  request.view.elevationDeg = 20.0f;
  return request;
}

std::string where(const FrameStats& s, const NodeReport& n, int phase = -1) {
  std::ostringstream text;
  text << s.strategy << " P=" << s.nodes << " node " << n.rank;
  if (phase >= 0) text << " phase " << phase << " (" << n.phases[std::size_t(phase)].label << ")";
  text << ": kdswap render --dataset <test volume> --nodes " << s.nodes << " --composite " << s.strategy
       << " --stats frame.json";
  return text.str();
}

// Render, then every phase, one after another inside [0, wall]; each phase is filled by its wait
// and compute time (PhaseStats::start/end).
void checkOrderedInsideFrame(const FrameStats& s) {
  for (const NodeReport& n : s.perNode) {
    INFO(where(s, n));
    REQUIRE(n.timed);
    CHECK(n.renderStart >= 0.0);
    CHECK(n.renderStart <= n.renderEnd);
    double previous = n.renderEnd;
    for (std::size_t k = 0; k < n.phases.size(); ++k) {
      const PhaseStats& p = n.phases[k];
      INFO(where(s, n, int(k)));
      CHECK(previous <= p.start);
      CHECK(p.start <= p.end);
      CHECK(std::abs(p.end - p.start - (p.computeSeconds + p.waitSeconds)) <= kClockTolerance);
      previous = p.end;
    }
    CHECK(previous <= s.wallSeconds + kClockTolerance);
  }
}

}  // namespace

TEST_CASE("every node's render and phase intervals follow one another inside the frame, for every strategy") {
  auto volume = test::makeBlobs({24, 22, 20});
  const FrameRequest request = smallRequest();
  for (const std::string& strategy : strategyNames())
    for (int nodes : {1, 2, 3, 8, 13}) {
      ClusterOptions options;
      options.nodes = nodes;
      options.strategy = strategy;
      VirtualCluster cluster(*volume, options);
      for (int frame = 0; frame < 2; ++frame) {  // the second frame too: the origin is per frame
        const FrameResult result = cluster.renderFrame(request);
        REQUIRE(int(result.stats.perNode.size()) == nodes);
        checkOrderedInsideFrame(result.stats);
      }
    }
}

TEST_CASE("on one thread the renders queue for the core: the last ends after all render work summed") {
  auto volume = test::makeBlobs({32, 32, 32});
  FrameRequest request = smallRequest();
  request.width = request.height = 64;
  for (int nodes : {2, 8}) {
    ClusterOptions options;
    options.nodes = nodes;
    options.threads = 1;
    options.execution = NodeExecution::Tasks;  // the one worker thread runs every node and every tile
    VirtualCluster cluster(*volume, options);
    const FrameStats s = cluster.renderFrame(request).stats;
    checkOrderedInsideFrame(s);
    double work = 0, lastEnd = 0;
    for (const NodeReport& n : s.perNode) {
      INFO(where(s, n));
      // One thread: the node's tiles ran one after another inside its render interval.
      CHECK(n.renderEnd - n.renderStart >= n.renderSeconds - kClockTolerance);
      work += n.renderSeconds;
      lastEnd = std::max(lastEnd, n.renderEnd);
    }
    CHECK(lastEnd >= work - kClockTolerance);
  }
}

TEST_CASE("a binary-swap node finishes a phase only after its partner began it (one clock for all nodes)") {
  auto volume = test::makeBlobs({32, 32, 32});
  const FrameRequest request = smallRequest();
  for (int threads : {1, 0})
    for (int nodes : {2, 8}) {
      ClusterOptions options;
      options.nodes = nodes;
      options.threads = threads;
      VirtualCluster cluster(*volume, options);
      const FrameStats s = cluster.renderFrame(request).stats;
      for (const NodeReport& n : s.perNode)
        for (std::size_t k = 0; k < n.phases.size(); ++k) {
          const PhaseStats& p = n.phases[k];
          INFO(where(s, n, int(k)) << ", threads " << threads);
          REQUIRE(p.partner >= 0);  // P a power of two: every phase swaps with a partner
          const PhaseStats& q = s.perNode[std::size_t(p.partner)].phases.at(k);
          CHECK(q.partner == n.rank);
          // The node received the partner's half, which the partner sent inside its own phase.
          CHECK(p.end >= q.start - kClockTolerance);
        }
    }
}

TEST_CASE("with over-decomposition each brick's ray casting lies inside its node's render interval") {
  auto volume = test::makeBlobs({32, 32, 32});
  const FrameRequest request = smallRequest();
  ClusterOptions options;
  options.nodes = 4;
  options.bricksPerNode = 4;
  VirtualCluster cluster(*volume, options);
  std::vector<double> costs(16, 1.0);
  for (int b = 0; b < 4; ++b) costs[std::size_t(b)] = 20.0;  // node 0's bricks are rendered elsewhere
  cluster.setBrickCosts(costs);
  const FrameStats s = cluster.renderFrame(request).stats;
  checkOrderedInsideFrame(s);
  std::size_t bricks = 0;
  for (const NodeReport& n : s.perNode) {
    INFO(where(s, n));
    double previous = n.renderStart;
    for (const NodeReport::BrickRender& b : n.bricks) {
      CHECK(previous <= b.start);
      CHECK(b.start <= b.end);
      previous = b.end;
    }
    CHECK(previous <= n.renderEnd);
    bricks += n.bricks.size();
  }
  CHECK(bricks == 16);
  const nlohmann::json j = s.toJson();
  for (const nlohmann::json& n : j["per_node"]) {
    REQUIRE(n.contains("bricks_rendered"));
    REQUIRE(n.contains("brick_intervals_s"));
    CHECK(n["brick_intervals_s"].size() == n["bricks_rendered"].size());
  }
}

TEST_CASE("the stats JSON carries the timeline keys beside the existing ones, and omits them without times") {
  auto volume = test::makeBlobs({24, 24, 24});
  ClusterOptions options;
  options.nodes = 4;
  VirtualCluster cluster(*volume, options);
  FrameStats s = cluster.renderFrame(smallRequest()).stats;
  nlohmann::json j = s.toJson();
  REQUIRE(j["per_node"].size() == 4);
  for (std::size_t r = 0; r < 4; ++r) {
    const nlohmann::json& n = j["per_node"][r];
    const NodeReport& report = s.perNode[r];
    for (const char* key : {"rank", "render_s", "speed", "composite_s", "wait_s", "bytes_sent", "private_bytes", "phases"})
      CHECK_MESSAGE(n.contains(key), key);
    CHECK(n["render_start_s"].get<double>() == report.renderStart);
    CHECK(n["render_end_s"].get<double>() == report.renderEnd);
    REQUIRE(n["phases"].size() == report.phases.size());
    REQUIRE(!report.phases.empty());
    for (std::size_t k = 0; k < report.phases.size(); ++k) {
      const nlohmann::json& p = n["phases"][k];
      for (const char* key : {"label", "partner", "composite_s", "wait_s", "messages_sent"}) CHECK_MESSAGE(p.contains(key), key);
      CHECK(p["start_s"].get<double>() == report.phases[k].start);
      CHECK(p["end_s"].get<double>() == report.phases[k].end);
      CHECK(p["end_s"].get<double>() <= j["wall_s"].get<double>() + kClockTolerance);
    }
  }
  // A report without times has no timeline keys rather than zeros.
  for (NodeReport& n : s.perNode) n.timed = false;
  j = s.toJson();
  for (const nlohmann::json& n : j["per_node"]) {
    CHECK_FALSE(n.contains("render_start_s"));
    CHECK_FALSE(n.contains("render_end_s"));
    for (const nlohmann::json& p : n["phases"]) CHECK_FALSE(p.contains("start_s"));
  }
}
