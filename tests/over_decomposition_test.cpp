// Over-decomposition (issue 8): more bricks than nodes, handed out on demand, composited at their
// home node in the right order. The hand-out is checked on synthetic costs; the images against
// the single-node reference while bricks really move between nodes.
#include <doctest/doctest.h>

#include <algorithm>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "core/cluster/brick_schedule.h"
#include "core/util/error.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("a layout cuts every node's brick into sub-bricks that tile it exactly") {
  const glm::ivec3 dims(40, 33, 27);
  const KdTree tree = KdTree::build(dims, 6, PartitionKind::KdTree);
  for (int m : {1, 2, 3, 4, 8}) {
    const BrickLayout layout(tree, m);
    REQUIRE(layout.bricks() == 6 * m);
    for (int node = 0; node < 6; ++node) {
      std::int64_t cells = 0;
      for (int b = node * m; b < (node + 1) * m; ++b) {
        CHECK(layout.home(b) == node);
        const VoxelBox& box = layout.box(b);
        CHECK(tree.brick(node).contains(box.lo));
        cells += box.count();
      }
      CHECK(cells == tree.brick(node).count());
    }
  }
  CHECK_THROWS_WITH_AS(BrickLayout(tree, 0), doctest::Contains("from 1 to 64"), Error);
}

TEST_CASE("bricks are handed out on demand: idle nodes take work from the busiest node") {
  const KdTree tree = KdTree::build({64, 64, 64}, 4, PartitionKind::KdTree);
  const BrickLayout layout(tree, 4);
  // Node 0's bricks cost 10 each, every other brick 1: alone, node 0 would need 40.
  std::vector<double> cost(16, 1.0);
  for (int b = 0; b < 4; ++b) cost[std::size_t(b)] = 10.0;
  std::vector<std::set<int>> held;
  const BrickSchedule s = scheduleBricks(layout, cost, {}, held);
  std::vector<int> seen;
  for (const auto& list : s.renders) seen.insert(seen.end(), list.begin(), list.end());
  std::sort(seen.begin(), seen.end());
  for (int b = 0; b < 16; ++b) CHECK(seen[std::size_t(b)] == b);  // every brick exactly once
  CHECK(s.modelledMakespan < 25.0);
  CHECK(s.renders[0].size() < 4);  // some of node 0's bricks went elsewhere...
  CHECK(s.ships[0].size() == 4 - s.renders[0].size());  // ...and node 0 ships each of them
  int received = 0;
  for (int n = 1; n < 4; ++n) received += s.receives[std::size_t(n)];
  CHECK(received == int(s.ships[0].size()));
  // The next frame with the same costs moves the same bricks, which their takers already hold.
  const BrickSchedule again = scheduleBricks(layout, cost, {}, held);
  CHECK(again.renders == s.renders);
  for (const auto& ships : again.ships) CHECK(ships.empty());

  // A node a quarter as fast as the others (its partition not shrunk for it) keeps two of its
  // four bricks: alone it would need 16 units, on demand the frame takes 8.
  std::vector<std::set<int>> held2;
  const BrickSchedule slow = scheduleBricks(layout, std::vector<double>(16, 1.0), {1.0, 0.25, 1.0, 1.0}, held2);
  CHECK(slow.renders[1].size() == 2);
  CHECK(slow.modelledMakespan == doctest::Approx(8.0).epsilon(0.01));
}

TEST_CASE("over-decomposed frames equal the single-node image while bricks move between nodes") {
  auto volume = test::makeBlobs({35, 30, 28});
  FrameRequest request;
  request.width = 39;
  request.height = 34;
  request.transfer = test::testTransfer();
  request.settings.earlyTermination = 1.0f;
  std::mt19937 rng(31);
  std::uniform_real_distribution<float> angle(-180.0f, 180.0f);
  std::uniform_real_distribution<double> cost(0.1, 10.0);
  for (const std::string strategy : {"binary-swap", "radix-k", "2-3-swap", "direct-send", "sequential"})
    for (int nodes : {1, 2, 5, 8})
      for (int perNode : {2, 3, 4}) {
        CAPTURE(strategy);
        CAPTURE(nodes);
        CAPTURE(perNode);
        ClusterOptions options;
        options.nodes = nodes;
        options.strategy = strategy;
        options.bricksPerNode = perNode;
        options.checksums = true;
        VirtualCluster cluster(*volume, options);
        for (int frame = 0; frame < 3; ++frame) {
          CAPTURE(frame);
          // Random costs: a different hand-out, and different bricks shipped, every frame.
          std::vector<double> costs(std::size_t(nodes * perNode));
          for (double& c : costs) c = cost(rng);
          cluster.setBrickCosts(costs);
          request.view.azimuthDeg = angle(rng);
          request.view.elevationDeg = angle(rng) / 3.0f;
          const FrameResult result = cluster.renderFrame(request);
          CHECK(test::diffAgainstReference(*volume, request, result.image) <= 1e-5f);
          std::multiset<int> rendered;
          for (const NodeReport& n : result.stats.perNode)
            for (const NodeReport::BrickRender& b : n.bricks) rendered.insert(b.brick);
          CHECK(int(rendered.size()) == nodes * perNode);
          CHECK(int(std::set<int>(rendered.begin(), rendered.end()).size()) == nodes * perNode);
          // After the frame the estimates are the measured work.
          CHECK(cluster.brickCosts() != costs);
        }
      }
}

TEST_CASE("a failed over-decomposed frame is followed by a correct one, bricks shipped again") {
  auto volume = test::makeBlobs({24, 24, 24});
  FrameRequest request;
  request.width = request.height = 32;
  request.transfer = test::testTransfer();
  request.settings.earlyTermination = 1.0f;
  ClusterOptions options;
  options.nodes = 4;
  options.bricksPerNode = 4;
  options.stallSeconds = 1.0;
  VirtualCluster cluster(*volume, options);
  std::vector<double> costs(16, 1.0);
  for (int b = 0; b < 4; ++b) costs[std::size_t(b)] = 20.0;  // node 0's bricks are stolen
  cluster.setBrickCosts(costs);
  FaultPlan fault;
  fault.kind = FaultPlan::Kind::ThrowInRender;
  fault.node = 2;
  cluster.injectFault(fault);
  CHECK_THROWS_WITH_AS(cluster.renderFrame(request), doctest::Contains("node 2"), Error);
  cluster.setBrickCosts(costs);
  const FrameResult next = cluster.renderFrame(request);
  CHECK(test::diffAgainstReference(*volume, request, next.image) <= 1e-5f);
  CHECK(next.stats.toJson()["per_node"][0]["bricks_rendered"].size() < 4);
}
