// Many more virtual nodes than threads: waiting nodes suspend, so 1024 nodes on 2 threads finish
// without deadlock, and each node's data stays private.
#include <doctest/doctest.h>

#include <oneapi/tbb/global_control.h>

#include "core/util/error.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("1024 nodes on a cluster limited to 2 threads complete every strategy without deadlock") {
  auto volume = test::makeBlobs({40, 40, 40});
  for (const char* strategy : {"binary-swap", "binary-tree", "sequential"}) {
    ClusterOptions options;
    options.nodes = 1024;
    options.threads = 2;
    options.strategy = strategy;
    options.stallSeconds = 30.0;  // a deadlock would surface as an error naming the waiting nodes
    VirtualCluster cluster(*volume, options);
    FrameRequest request;
    request.width = 40;
    request.height = 30;
    request.transfer = test::testTransfer();
    const FrameResult frame = cluster.renderFrame(request);
    CHECK(frame.stats.nodes == 1024);
    CHECK(frame.stats.perNode.size() == 1024);
    CHECK(frame.image.opaqueBounds().area() > 0);
  }
}

TEST_CASE("each node reports its private memory, and no node holds the whole volume") {
  auto volume = test::makeBlobs({48, 48, 48});
  ClusterOptions options;
  options.nodes = 16;
  VirtualCluster cluster(*volume, options);
  FrameRequest request;
  request.width = 32;
  request.height = 32;
  request.transfer = test::testTransfer();
  const FrameResult frame = cluster.renderFrame(request);
  const std::uint64_t wholeBytes = 48ull * 48 * 48 * sizeof(Voxel);
  std::uint64_t sum = 0;
  for (const NodeReport& n : frame.stats.perNode) {
    CHECK(n.privateBytes > 0);
    CHECK(n.privateBytes < wholeBytes / 4);
    sum += n.privateBytes;
  }
  CHECK(sum >= wholeBytes);  // owned voxels cover the volume; layers and images add a little
}

TEST_CASE("binary swap runs log2(P) phases and the stats record bytes, waits and a modelled time") {
  auto volume = test::makeBlobs({32, 32, 32});
  ClusterOptions options;
  options.nodes = 8;
  VirtualCluster cluster(*volume, options);
  FrameRequest request;
  request.width = 64;
  request.height = 64;
  request.transfer = test::testTransfer();
  request.recordPhases = true;
  const FrameResult frame = cluster.renderFrame(request);
  REQUIRE(frame.phases);
  CHECK(frame.phases->phaseCount() == 4);  // render + 3 swaps
  CHECK(frame.stats.phaseCount() == 3);
  CHECK(frame.stats.bytesSent() > 0);
  CHECK(frame.stats.modelledParallelSeconds() >= frame.stats.renderMax());
  // After the last swap each node's region is 1/8 of the frame.
  for (const auto& row : frame.phases->cells) CHECK(row.back().region.area() == 64 * 64 / 8);
}

TEST_CASE("a rejected node count or strategy name is a clear error") {
  auto volume = test::makeBlobs({8, 8, 8});
  ClusterOptions options;
  options.nodes = 5000;
  CHECK_THROWS_WITH_AS(VirtualCluster(*volume, options), doctest::Contains("between 1 and 4096"), Error);
  options.nodes = 4;
  options.strategy = "binary-swapp";
  CHECK_THROWS_WITH_AS(VirtualCluster(*volume, options), doctest::Contains("binary-swapp\": unknown (valid: "), Error);
}
