// Soak and stress: many frames with the view changing every frame keep memory flat and never
// fail; the largest node count runs at a small image.
#include <doctest/doctest.h>

#include "core/util/memory.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("1000 frames at P = 64 with a new view every frame: no failure and flat memory") {
  auto volume = test::makeBlobs({32, 32, 32});
  ClusterOptions options;
  options.nodes = 64;
  options.checksums = true;
  VirtualCluster cluster(*volume, options);
  FrameRequest request;
  request.width = 48;
  request.height = 40;
  request.transfer = test::testTransfer();
  std::uint64_t residentAfterWarmUp = 0;
  int frames = 0;
  for (int f = 0; f < 1000; ++f) {
    request.view.azimuthDeg = float(f) * 7.3f;
    request.view.elevationDeg = float((f * 13) % 140) - 70.0f;
    request.view.projection = f % 3 == 0 ? Projection::Orthographic : Projection::Perspective;
    const FrameResult frame = cluster.renderFrame(request);
    REQUIRE(frame.stats.perNode.size() == 64);
    ++frames;
    if (f == 99) residentAfterWarmUp = currentResidentBytes();
  }
  CHECK(frames == 1000);
  const std::uint64_t residentAtEnd = currentResidentBytes();
  INFO("resident after 100 frames " << residentAfterWarmUp << ", after 1000 " << residentAtEnd);
  CHECK(residentAtEnd <= residentAfterWarmUp + 16ull * 1024 * 1024);
}

TEST_CASE("4096 nodes, the largest cluster, render a small image correctly") {
  auto volume = test::makeBlobs({40, 36, 32});
  ClusterOptions options;
  options.nodes = 4096;
  options.threads = 2;
  VirtualCluster cluster(*volume, options);
  FrameRequest request;
  request.width = 24;
  request.height = 20;
  request.transfer = test::testTransfer();
  request.settings.earlyTermination = 1.0f;
  const FrameResult frame = cluster.renderFrame(request);
  const Brick whole = wholeVolumeBrick(*volume);
  const ReferenceResult ref = renderReference(whole, request.view, 24, 20, request.transfer, request.settings,
                                              glm::vec2(volume->info().minValue, volume->info().maxValue));
  CHECK(maxAbsDifference(frame.image, ref.image, ref.image.rect()) <= 1e-5f);
}
