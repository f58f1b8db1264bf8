// Load balancing (issue 8): cost-aware k-d planes, planes weighted by node speed, and the network
// model's communication time. Work is judged by deterministic counts (the cost estimate, samples
// taken per node), never by timings.
#include <doctest/doctest.h>

#include <algorithm>
#include <numeric>
#include <random>

#include <nlohmann/json.hpp>

#include "core/metrics/network_model.h"
#include "core/partition/cost_field.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "test_support.h"

using namespace kdswap;

namespace {

double maxOverMean(const std::vector<double>& v) {
  const double mean = std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
  return *std::max_element(v.begin(), v.end()) / mean;
}

std::vector<double> brickCosts(const KdTree& tree, const CostField& field) {
  std::vector<double> costs;
  for (int r = 0; r < tree.ranks(); ++r) costs.push_back(field.cost(tree.brick(r)));
  return costs;
}

CostField estimateWithPreset(const VolumeSource& source) {
  const VolumeInfo& info = source.info();
  return CostField::estimate(source, TransferTable(loadTransferFunction(info.preset), 1.0f),
                             glm::vec2(info.minValue, info.maxValue));
}

}  // namespace

TEST_CASE("the cost field counts visible blocks at full cost and empty ones at a small cost") {
  // Bright only in the half x >= 16: the visible half costs 1 per cell, the other kEmptyCellCost.
  auto volume = test::makeVolume({33, 17, 9}, [](int x, int, int) { return x >= 16 ? 1.0f : 0.0f; });
  TransferFunction tf = test::testTransfer();
  const CostField field = CostField::estimate(*volume, TransferTable(tf, 1.0f), glm::vec2(0.0f, 1.0f));
  const VoxelBox all{glm::ivec3(0), glm::ivec3(32, 16, 8)};
  const std::vector<double> layers = field.layerCosts(all, 0);
  REQUIRE(layers.size() == 32);
  // Blocks are 8 cells wide: cells 0..7 see only zeros; cells 8..15 touch voxel x = 16 (visible).
  CHECK(layers[0] == doctest::Approx(16.0 * 8.0 * CostField::kEmptyCellCost));
  CHECK(layers[31] == doctest::Approx(16.0 * 8.0));
  CHECK(field.cost(all) == doctest::Approx(std::accumulate(layers.begin(), layers.end(), 0.0)));
  CHECK(CostField::uniform({33, 17, 9}).cost(all) == doctest::Approx(32.0 * 16 * 8));
}

TEST_CASE("the cost field estimated in shares of block layers adds up to the whole estimate (MPI ranks)") {
  auto volume = openDataset("vessels:40x36x70");
  const glm::ivec3 dims = volume->info().dims;
  const TransferTable table(loadTransferFunction("vessels"), 1.0f);
  const glm::vec2 range(volume->info().minValue, volume->info().maxValue);
  const CostField whole = CostField::estimate(*volume, table, range);
  const int layers = CostField::blockLayers(dims);
  REQUIRE(layers == 9);  // 69 cells in blocks of 8
  for (const int ranks : {1, 2, 4, 13}) {
    CAPTURE(ranks);
    std::vector<float> sum(whole.blockCosts().size(), 0.0f);
    for (int r = 0; r < ranks; ++r) {
      const CostField share = CostField::estimateLayers(*volume, table, range, layers * r / ranks, layers * (r + 1) / ranks);
      for (std::size_t i = 0; i < sum.size(); ++i) sum[i] += share.blockCosts()[i];
    }
    CHECK(sum == whole.blockCosts());
    const CostField merged = CostField::fromBlockCosts(dims, sum);
    const VoxelBox box{glm::ivec3(3, 5, 7), glm::ivec3(30, 33, 60)};
    CHECK(merged.cost(box) == whole.cost(box));
  }
  // The field is not uniform, so a share that left layers out would be caught above.
  CHECK(whole.visibleFraction() > 0.0);
  CHECK(whole.visibleFraction() < 1.0);
  CHECK_THROWS_AS(CostField::fromBlockCosts(dims, std::vector<float>(3, 1.0f)), Error);
}

TEST_CASE("cost-aware planes balance the estimated work where halving space does not (vessels, phantom)") {
  for (const std::string spec : {"vessels:128", "phantom:128"}) {
    CAPTURE(spec);
    auto source = openDataset(spec);
    auto field = std::make_shared<CostField>(estimateWithPreset(*source));
    for (int nodes : {4, 8, 16}) {
      CAPTURE(nodes);
      const KdTree bySpace = KdTree::build(source->info().dims, nodes, PartitionKind::KdTree);
      const KdTree byCost = KdTree::build(source->info().dims, nodes, PartitionKind::KdTree, 2, {}, {field, {}});
      const double spaceImbalance = maxOverMean(brickCosts(bySpace, *field));
      const double costImbalance = maxOverMean(brickCosts(byCost, *field));
      MESSAGE(spec << " P=" << nodes << ": estimated work max/mean " << spaceImbalance << " by space, "
                   << costImbalance << " by cost");
      CHECK(costImbalance <= spaceImbalance + 1e-9);
      CHECK(costImbalance < 1.1);
    }
  }
}

TEST_CASE("cost-aware planes lower the busiest node's samples on the sparse vessels") {
  auto source = openDataset("vessels:128");
  const VolumeInfo& info = source->info();
  FrameRequest request;
  request.width = request.height = 128;
  request.transfer = loadTransferFunction(info.preset);
  request.settings.earlyTermination = 1.0f;
  auto busiest = [&](const std::string& balance) {
    ClusterOptions options;
    options.nodes = 8;
    options.balance = balance;
    options.balanceTransfer = request.transfer;
    VirtualCluster cluster(*source, options);
    std::vector<double> samples;
    for (const NodeReport& n : cluster.renderFrame(request).stats.perNode) samples.push_back(double(n.samples));
    return maxOverMean(samples);
  };
  const double space = busiest("space"), cost = busiest("cost");
  MESSAGE("samples max/mean: " << space << " by space, " << cost << " by cost");
  CHECK(cost < space);
}

TEST_CASE("node speeds: a node twice as fast is given twice the work") {
  const glm::ivec3 dims(65, 49, 41);
  const CostField uniform = CostField::uniform(dims);
  const KdTree two = KdTree::build(dims, 2, PartitionKind::KdTree, 2, {}, {nullptr, {2.0, 1.0}});
  CHECK(uniform.cost(two.brick(0)) / uniform.cost(two.brick(1)) == doctest::Approx(2.0).epsilon(0.05));
  // Eight nodes alternating fast and slow, and a shaped (radix-k style) tree of three slabs.
  const KdTree eight = KdTree::build(dims, 8, PartitionKind::KdTree, 2, {}, {nullptr, {1, 0.5, 1, 0.5, 1, 0.5, 1, 0.5}});
  for (int r = 0; r < 8; ++r) {
    const double perSpeed = uniform.cost(eight.brick(r)) / (r % 2 ? 0.5 : 1.0);
    CHECK(perSpeed == doctest::Approx(uniform.cost({glm::ivec3(0), dims - 1}) / 6.0).epsilon(0.12));
  }
  const KdTree three = KdTree::build(dims, 3, PartitionKind::KdTree, 2, {3, 0, 0, 0}, {nullptr, {1.0, 2.0, 3.0}});
  for (int r = 0; r < 3; ++r)
    CHECK(uniform.cost(three.brick(r)) / double(r + 1) ==
          doctest::Approx(uniform.cost({glm::ivec3(0), dims - 1}) / 6.0).epsilon(0.05));
  CHECK_THROWS_WITH_AS(KdTree::build(dims, 2, PartitionKind::KdTree, 2, {}, {nullptr, {1.0}}),
                       doctest::Contains("1 node speeds for 2 nodes"), Error);
  CHECK_THROWS_WITH_AS(KdTree::build(dims, 2, PartitionKind::KdTree, 2, {}, {nullptr, {1.0, 0.0}}),
                       doctest::Contains("must be positive"), Error);
}

TEST_CASE("balanced partitions keep the distributed image equal to the single-node image") {
  auto volume = test::makeBlobs({37, 31, 29});
  FrameRequest request;
  request.width = 43;
  request.height = 37;
  request.transfer = test::testTransfer();
  request.settings.earlyTermination = 1.0f;
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> speed(0.25, 4.0);
  std::uniform_real_distribution<float> angle(-180.0f, 180.0f);
  for (const std::string strategy : {"binary-swap", "radix-k", "2-3-swap", "telescoping", "direct-send"})
    for (int nodes : {2, 3, 6, 8, 13}) {
      ClusterOptions options;
      options.nodes = nodes;
      options.strategy = strategy;
      options.balance = "cost";
      options.balanceTransfer = request.transfer;
      for (int r = 0; r < nodes; ++r) options.speeds.push_back(speed(rng));
      VirtualCluster cluster(*volume, options);
      request.view.azimuthDeg = angle(rng);
      request.view.elevationDeg = angle(rng) / 3.0f;
      const FrameResult frame = cluster.renderFrame(request);
      CHECK_MESSAGE(test::diffAgainstReference(*volume, request, frame.image) <= 1e-5f, strategy << " P=" << nodes);
      // Modelled times divide each node's work by its speed.
      for (const NodeReport& n : frame.stats.perNode)
        CHECK(n.speed == doctest::Approx(options.speeds[std::size_t(n.rank)]));
    }
}

TEST_CASE("network models: the CM-5's fat tree, and a shared Ethernet that serialises every node's bytes") {
  const NetworkModel cm5 = networkModel("cm5");
  CHECK(cm5.bandwidthBetween(0, 3) == doctest::Approx(20e6));   // same group of 4
  CHECK(cm5.bandwidthBetween(1, 13) == doctest::Approx(10e6));  // same group of 16
  CHECK(cm5.bandwidthBetween(2, 40) == doctest::Approx(5e6));
  CHECK(cm5.bandwidthBetween(2, -1) == doctest::Approx(5e6));
  CHECK_THROWS_WITH_AS(networkModel("token-ring"), doctest::Contains("ideal, cm5 or ethernet10"), Error);

  // Two nodes swapping 1 MB each in one phase.
  std::vector<NodeReport> nodes(2);
  for (int r = 0; r < 2; ++r) {
    nodes[std::size_t(r)].rank = r;
    PhaseStats p;
    p.partner = 1 - r;
    p.bytesSent = p.bytesReceived = 1000000;
    p.messagesSent = p.messagesReceived = 1;
    nodes[std::size_t(r)].phases.push_back(p);
  }
  CHECK(networkModel("ideal").phaseSeconds(nodes, 0) == 0.0);
  CHECK(cm5.phaseSeconds(nodes, 0) == doctest::Approx(80e-6 + 1e6 / 20e6));  // in parallel
  CHECK(networkModel("ethernet10").phaseSeconds(nodes, 0) == doctest::Approx(1e-3 + 2e6 / 1.25e6));  // one after another

  // A real frame: shared Ethernet costs far more than the CM-5's network and dominates the
  // modelled time, the trend of the paper's Table 9 against Table 4.
  auto volume = test::makeBlobs({48, 48, 48});
  FrameRequest request;
  request.width = request.height = 128;
  request.transfer = test::testTransfer();
  ClusterOptions options;
  options.nodes = 8;
  VirtualCluster cluster(*volume, options);
  FrameStats stats = cluster.renderFrame(request).stats;
  const double ideal = stats.modelledParallelSeconds();
  CHECK(stats.modelledCommSeconds() == 0.0);
  stats.network = cm5;
  const double cm5Comm = stats.modelledCommSeconds();
  CHECK(stats.modelledParallelSeconds() == doctest::Approx(ideal + cm5Comm));
  stats.network = networkModel("ethernet10");
  const double ethernetComm = stats.modelledCommSeconds();
  MESSAGE("P=8 128x128: communication " << cm5Comm * 1e3 << " ms on cm5, " << ethernetComm * 1e3
                                        << " ms on ethernet10; compute " << ideal * 1e3 << " ms");
  CHECK(ethernetComm > 10.0 * cm5Comm);
  CHECK(ethernetComm > ideal);  // dominant on shared Ethernet
  CHECK(stats.toJson()["network"] == "ethernet10");
}
