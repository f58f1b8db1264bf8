// The modelled parallel time's render span (FrameStats::renderSpan): the max render for the
// paper's independent nodes; in front-to-back waves the longest chain of renders that waited for
// each other (NodeReport::renderedAfter), since a node there starts only when those have finished.
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>

#include <nlohmann/json.hpp>

#include "core/composite/registry.h"
#include "test_support.h"

using namespace kdswap;

namespace {

NodeReport report(int rank, double renderSeconds, std::vector<int> after = {}, double speed = 1.0) {
  NodeReport n;
  n.rank = rank;
  n.renderSeconds = renderSeconds;
  n.renderedAfter = std::move(after);
  n.speed = speed;
  return n;
}

FrameRequest wavesRequest(const View& view) {
  FrameRequest r;
  r.view = view;
  r.width = 48;
  r.height = 40;
  r.transfer = test::testTransfer();
  r.settings.frontToBackWaves = true;
  return r;
}

double renderSum(const FrameStats& s) {
  double sum = 0;
  for (const NodeReport& n : s.perNode) sum += n.modelledRenderSeconds();
  return sum;
}

}  // namespace

TEST_CASE("render span: the max render without waits, the longest chain of waits with them") {
  FrameStats s;
  s.perNode = {report(0, 1.0), report(1, 2.0), report(2, 3.0), report(3, 4.0)};
  CHECK(s.renderSpan() == 4.0);
  CHECK(s.modelledParallelSeconds() == 4.0);

  // 1 and 2 wait for 0, 3 for both: 0 ends at 1, 1 at 3, 2 at 4, 3 at 4 + 4. Listed out of rank order.
  s.perNode = {report(3, 4.0, {1, 2}), report(1, 2.0, {0}), report(0, 1.0), report(2, 3.0, {0})};
  CHECK(s.renderSpan() == 8.0);
  CHECK(s.renderMax() == 4.0);
  CHECK(s.modelledParallelSeconds() == 8.0);
  CHECK(s.toJson().at("render_span_s").get<double>() == 8.0);
  CHECK(s.toJson().at("per_node").at(0).at("rendered_after") == nlohmann::json::array({1, 2}));

  // A node twice as fast models half its work: 3 ends at 4 + 2.
  s.perNode[0].speed = 2.0;
  CHECK(s.renderSpan() == 6.0);

  // Compositing phases add their max on top of the span, as they do on top of the max render.
  PhaseStats phase;
  phase.computeSeconds = 0.5;
  for (NodeReport& n : s.perNode) n.phases = {phase};
  CHECK(s.modelledParallelSeconds() == 6.5);
}

TEST_CASE("render span: a wait on an unknown rank or around a cycle adds nothing and ends") {
  FrameStats s;
  s.perNode = {report(0, 1.0, {7}), report(1, 2.0, {0})};
  CHECK(s.renderSpan() == 3.0);
  s.perNode = {report(0, 1.0, {1}), report(1, 2.0, {0})};  // cannot come from waves; must not hang
  const double span = s.renderSpan();
  CHECK(span >= 2.0);
  CHECK(span <= 3.0);
}

TEST_CASE("waves record the nodes in front of each node, whose pieces its own pieces waited for") {
  auto volume = test::makeBlobs({33, 29, 31}, glm::vec3(1.0f, 1.2f, 0.8f));
  for (int nodes : {2, 8, 13}) {
    ClusterOptions options;
    options.nodes = nodes;
    VirtualCluster cluster(*volume, options);
    for (const View& view : {View{30.0f, 15.0f}, View{-120.0f, 50.0f}}) {
      const FrameResult frame = cluster.renderFrame(wavesRequest(view));
      const FrameStats& s = frame.stats;
      INFO("P=" << nodes << " view " << view.azimuthDeg << "," << view.elevationDeg);
      REQUIRE(int(s.perNode.size()) == nodes);
      for (const NodeReport& n : s.perNode)
        for (int rank : n.renderedAfter) {
          INFO("node " << n.rank << " after " << rank);
          REQUIRE(rank >= 0);
          REQUIRE(rank < nodes);
          CHECK(rank != n.rank);
          // The wall timeline: renders overlap (pieces wait cell by cell), but the node in front
          // had started before this one ended, and the model chains them whole.
          CHECK(s.perNode[std::size_t(rank)].renderStart <= n.renderEnd);
          CHECK(s.renderSpan() >= n.modelledRenderSeconds() + s.perNode[std::size_t(rank)].modelledRenderSeconds());
        }
      CHECK(s.renderSpan() >= s.renderMax());
      CHECK(s.renderSpan() <= renderSum(s) * (1 + 1e-12));
      CHECK(s.modelledParallelSeconds() >= s.renderSpan());
    }
  }
}

TEST_CASE("waves of slabs stacked along the line of sight form one chain: the span is every render summed") {
  auto volume = test::makeBlobs({33, 29, 31}, glm::vec3(1.0f, 1.2f, 0.8f));
  ClusterOptions options;
  options.nodes = 6;
  options.partition = PartitionKind::Slab;
  options.slabAxis = 1;  // azimuth 0 with +z up looks along y (Camera: the front axis)
  VirtualCluster cluster(*volume, options);
  const FrameResult frame = cluster.renderFrame(wavesRequest(View{0.0f, 0.0f}));
  const FrameStats& s = frame.stats;
  // Every slab covers the image's centre, so each waits for all slabs in front of it.
  std::vector<std::size_t> waits;
  for (const NodeReport& n : s.perNode) waits.push_back(n.renderedAfter.size());
  std::sort(waits.begin(), waits.end());
  std::vector<std::size_t> chain(6);
  std::iota(chain.begin(), chain.end(), std::size_t(0));
  CHECK(waits == chain);
  CHECK(s.renderSpan() == doctest::Approx(renderSum(s)).epsilon(1e-12));

  // The paper's independent nodes wait for no one: the span is the max render.
  FrameRequest independent = wavesRequest(View{0.0f, 0.0f});
  independent.settings.frontToBackWaves = false;
  const FrameResult alone = cluster.renderFrame(independent);
  for (const NodeReport& n : alone.stats.perNode) CHECK(n.renderedAfter.empty());
  CHECK(alone.stats.renderSpan() == alone.stats.renderMax());
}
