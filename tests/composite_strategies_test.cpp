// Strategy-specific hazards of direct-send, radix-k, 2-3 swap and telescoping (the invariant sweep
// in distributed_invariant_test.cpp covers every strategy at default options): radix-k with
// explicit radices, radices that cannot serve P, nodes left idle, telescoping's odd group
// counts, sparse messages, and the k-way k-d splits these strategies build on.
#include <doctest/doctest.h>

#include <bit>

#include "core/composite/radix_k.h"
#include "core/composite/registry.h"
#include "core/util/error.h"
#include "test_support.h"

using namespace kdswap;

namespace {

constexpr float kTolerance = 1e-5f;

struct Fixture {
  std::unique_ptr<MemoryVolume> volume = test::makeBlobs({29, 33, 27}, glm::vec3(1.0f, 0.9f, 1.1f));
  Brick whole = wholeVolumeBrick(*volume);
  TransferFunction tf = test::testTransfer();
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

std::vector<View> someViews() {
  std::vector<View> views(3);
  views[0].azimuthDeg = 30.0f, views[0].elevationDeg = 20.0f, views[0].distance = 2.5f;
  views[1].azimuthDeg = -140.0f, views[1].elevationDeg = -35.0f, views[1].projection = Projection::Orthographic;
  views[2].azimuthDeg = 95.0f, views[2].elevationDeg = 60.0f, views[2].distance = 1.9f;
  return views;
}

//! Renders the views with `options` and checks each against the single-node reference.
void checkMatchesReference(const ClusterOptions& options, const std::string& what, int w = 43, int h = 35) {
  VirtualCluster cluster(*fixture().volume, options);
  for (const View& view : someViews()) {
    FrameRequest request;
    request.view = view;
    request.width = w;
    request.height = h;
    request.transfer = fixture().tf;
    request.settings.earlyTermination = 1.0f;
    const FrameResult frame = cluster.renderFrame(request);
    const VolumeInfo& info = fixture().volume->info();
    const ReferenceResult ref = renderReference(fixture().whole, view, w, h, fixture().tf, request.settings,
                                                glm::vec2(info.minValue, info.maxValue));
    const float diff = maxAbsDifference(frame.image, ref.image, ref.image.rect());
    CHECK_MESSAGE(diff <= kTolerance, what << ": max abs diff " << diff << "; reproduce: "
                                           << test::reproduce(options.nodes, options.strategy, "kd", w, h, view));
  }
}

ClusterOptions optionsFor(const std::string& strategy, int nodes, std::vector<int> radices = {}) {
  ClusterOptions options;
  options.checksums = true;
  options.strategy = strategy;
  options.nodes = nodes;
  options.composite.radices = std::move(radices);
  return options;
}

const std::vector<std::string> kNewStrategies = {"direct-send", "radix-k", "2-3-swap", "telescoping"};

}  // namespace

TEST_CASE("radix-k with radices {4,2}, {8}, {2,2,2} and {2,4} matches the single-node image for 8 nodes") {
  for (const std::vector<int>& radices : std::vector<std::vector<int>>{{4, 2}, {8}, {2, 2, 2}, {2, 4}})
    for (PartitionKind partition : {PartitionKind::KdTree, PartitionKind::Slab}) {
      ClusterOptions options = optionsFor("radix-k", 8, radices);
      options.partition = partition;
      checkMatchesReference(options, "radices " + std::to_string(radices.size()) + " rounds, first " +
                                         std::to_string(radices[0]));
    }
}

TEST_CASE("radix-k's default radices group P's prime factors into rounds of at most 8") {
  const RadixK radix(CompositeOptions{});
  CHECK(radix.radices(8) == std::vector<int>{8});
  CHECK(radix.radices(12) == std::vector<int>{4, 3});
  CHECK(radix.radices(64) == std::vector<int>{8, 8});
  CHECK(radix.radices(1024) == std::vector<int>{8, 8, 8, 2});
  CHECK(radix.radices(30) == std::vector<int>{6, 5});
  CHECK(radix.radices(13) == std::vector<int>{13});
  CHECK(radix.radices(1).empty());
  checkMatchesReference(optionsFor("radix-k", 16, {}), "16 = 8 * 2 by default");
}

TEST_CASE("radix-k with mixed radices matches the single-node image for 12, 18 and 30 nodes") {
  checkMatchesReference(optionsFor("radix-k", 12, {3, 4}), "12 = 3 * 4");
  checkMatchesReference(optionsFor("radix-k", 18, {2, 3, 3}), "18 = 2 * 3 * 3");
  checkMatchesReference(optionsFor("radix-k", 30, {5, 6}), "30 = 5 * 6");
}

TEST_CASE("radix-k refuses radices that do not multiply to the node count and names a valid factorisation") {
  CHECK_THROWS_WITH_AS(VirtualCluster(*fixture().volume, optionsFor("radix-k", 12, {4, 2})),
                       doctest::Contains("--radices 2,2,3"), Error);
  CHECK_THROWS_WITH_AS(VirtualCluster(*fixture().volume, optionsFor("radix-k", 8, {1, 8})),
                       doctest::Contains("each must be >= 2"), Error);
  CHECK_THROWS_WITH_AS(VirtualCluster(*fixture().volume, optionsFor("radix-k", 7, {0})), doctest::Contains("radix-k"),
                       Error);
}

TEST_CASE("2-3 swap keeps every node busy in every one of its floor(log2 P) rounds") {
  for (int nodes : {2, 3, 5, 6, 7, 11, 12, 13, 27, 31, 40}) {
    VirtualCluster cluster(*fixture().volume, optionsFor("2-3-swap", nodes));
    FrameRequest request;
    request.width = 64;
    request.height = 48;
    request.transfer = fixture().tf;
    const FrameResult frame = cluster.renderFrame(request);
    const int rounds = int(std::bit_width(unsigned(nodes))) - 1;
    for (const NodeReport& node : frame.stats.perNode) {
      REQUIRE(int(node.phases.size()) == rounds);
      for (const PhaseStats& phase : node.phases)
        CHECK_MESSAGE(phase.partner >= 0, "P=" << nodes << " node " << node.rank << " idle in " << phase.label);
    }
  }
}

TEST_CASE("telescoping matches the single-node image for 6 and 13 nodes, and its phase rows line up") {
  for (int nodes : {6, 13}) {
    checkMatchesReference(optionsFor("telescoping", nodes), "telescoping P=" + std::to_string(nodes));
    VirtualCluster cluster(*fixture().volume, optionsFor("telescoping", nodes));
    FrameRequest request;
    request.width = 40;
    request.height = 30;
    request.transfer = fixture().tf;
    const FrameResult frame = cluster.renderFrame(request);
    // Swap rounds of the largest group, then one telescoping step per smaller group.
    const int phases = int(std::bit_width(unsigned(nodes))) - 1 + std::popcount(unsigned(nodes)) - 1;
    for (const NodeReport& node : frame.stats.perNode) CHECK(int(node.phases.size()) == phases);
  }
}

TEST_CASE("every new strategy on one node returns its image unchanged") {
  for (const std::string& strategy : kNewStrategies) checkMatchesReference(optionsFor(strategy, 1), strategy + " P=1");
}

TEST_CASE("every new strategy with sparse messages matches the single-node image") {
  for (const std::string& strategy : kNewStrategies)
    for (int nodes : {5, 8, 13}) {
      ClusterOptions options = optionsFor(strategy, nodes);
      options.composite.sparse = true;
      checkMatchesReference(options, strategy + " sparse P=" + std::to_string(nodes));
    }
}

TEST_CASE("a shaped k-d tree cuts k-way nodes into slabs in proportion to their ranks") {
  const glm::ivec3 dims(91, 61, 47);
  // Root: three children of 1, 2 and 3 leaves; the cut along x is 1/6, 2/6, 3/6 of 90 cells.
  const TreeShape shape = {3, 0, 2, 0, 0, 3, 0, 0, 0};
  REQUIRE(shapeLeaves(shape) == 6);
  const KdTree tree = KdTree::build(dims, 6, PartitionKind::KdTree, 2, shape);
  const KdNode& root = tree.nodes()[std::size_t(tree.root())];
  REQUIRE(root.children.size() == 3);
  CHECK(root.axis == 0);
  CHECK(root.planes == std::vector<int>{15, 45});
  std::int64_t cells = 0;
  for (int r = 0; r < 6; ++r) cells += tree.brick(r).count();
  CHECK(cells == std::int64_t(90) * 60 * 46);  // the bricks tile the domain
  CHECK_THROWS_AS(KdTree::build(dims, 5, PartitionKind::KdTree, 2, shape), Error);
  CHECK_THROWS_AS(shapeLeaves({2, 0}), Error);
  CHECK(levelShape({3, 2}) == TreeShape{3, 2, 0, 0, 2, 0, 0, 2, 0, 0});
}
