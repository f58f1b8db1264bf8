// Front-to-back waves (RenderSettings::frontToBackWaves): nodes render nearest first and stop
// their rays where the nodes in front already stopped the light. Checked against the single-node
// image (exactly, 1e-5, with early termination off; and with it on, far inside the threshold's
// bound the independent nodes need), against the single-node samples (never more), and against
// the nodes rendering independently (the same image with termination off).
#include <doctest/doctest.h>

#include <random>

#include "core/composite/registry.h"
#include "core/render/front_transmittance.h"
#include "test_support.h"

using namespace kdswap;

namespace {

struct Fixture {
  std::unique_ptr<MemoryVolume> volume = test::makeBlobs({33, 29, 31}, glm::vec3(1.0f, 1.2f, 0.8f));
  Brick whole = wholeVolumeBrick(*volume);
  TransferFunction tf = test::testTransfer();
  glm::vec2 range() const { return glm::vec2(volume->info().minValue, volume->info().maxValue); }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

FrameRequest wavesRequest(const View& view, int w, int h, float ert) {
  FrameRequest r;
  r.view = view;
  r.width = w;
  r.height = h;
  r.transfer = fixture().tf;
  r.settings.earlyTermination = ert;
  r.settings.frontToBackWaves = true;
  return r;
}

std::string describe(int nodes, const std::string& strategy, const View& v, int w, int h) {
  return strategy + " P=" + std::to_string(nodes) + " view " + std::to_string(v.azimuthDeg) + "," +
         std::to_string(v.elevationDeg) + " " + std::to_string(w) + "x" + std::to_string(h);
}

}  // namespace

TEST_CASE("front-to-back waves: with early termination off, the image equals the single-node image") {
  std::mt19937 rng(61);
  for (const std::string& strategy : {std::string("binary-swap"), std::string("direct-send")})
    for (int nodes : {2, 3, 8, 13, 64}) {
      ClusterOptions options;
      options.checksums = true;
      options.nodes = nodes;
      options.strategy = strategy;
      VirtualCluster cluster(*fixture().volume, options);
      for (const View& view : test::randomViews(rng, 2))
        for (auto [w, h] : std::vector<std::pair<int, int>>{{41, 37}, {64, 1}, {7, 9}}) {
          const FrameRequest request = wavesRequest(view, w, h, 1.0f);
          const FrameResult frame = cluster.renderFrame(request);
          const ReferenceResult ref =
              renderReference(fixture().whole, view, w, h, fixture().tf, request.settings, fixture().range());
          CHECK_MESSAGE(maxAbsDifference(frame.image, ref.image, ref.image.rect()) <= 1e-5f,
                        describe(nodes, strategy, view, w, h));
        }
    }
}

TEST_CASE("front-to-back waves: with early termination on, no more samples than one node and the same image") {
  std::mt19937 rng(62);
  for (float ert : {0.5f, 0.9f, 0.99f})
    for (int nodes : {2, 8, 27, 64}) {
      ClusterOptions options;
      options.nodes = nodes;
      VirtualCluster cluster(*fixture().volume, options);
      ClusterOptions single;
      single.nodes = 1;
      VirtualCluster one(*fixture().volume, single);
      for (const View& view : test::randomViews(rng, 2)) {
        const FrameRequest request = wavesRequest(view, 48, 40, ert);
        const FrameResult frame = cluster.renderFrame(request);
        const FrameResult reference = one.renderFrame(request);  // P = 1: waves do not apply
        const std::string what = describe(nodes, "binary-swap", view, 48, 40) + " ert " + std::to_string(ert);
        // Independent nodes may keep up to 1 - ert more light; waves stop where one node stops.
        CHECK_MESSAGE(maxAbsDifference(frame.image, reference.image, reference.image.rect()) <= 1e-3f, what);
        // A brick stops where the light in front times its own reaches the stop: the single-node
        // ray's samples, give or take the rounding of the product (a sample or so on a few rays).
        // Counted with every sample taken: skipping leaves out different invisible samples in a
        // small brick and in the whole volume (a brick with few empty cells skips none of them:
        // EmptySpaceMap::marchesEverySample).
        FrameRequest everySample = request;
        everySample.settings.skipEmptySpace = false;
        const std::uint64_t taken = cluster.renderFrame(everySample).stats.samples(),
                            expected = one.renderFrame(everySample).stats.samples();
        CHECK_MESSAGE(taken <= expected + expected / 200 + 8, what);
        CHECK_MESSAGE(taken + expected / 50 >= expected, what);
      }
    }
}

TEST_CASE("front-to-back waves: fewer samples than independent nodes where matter hides bricks") {
  ClusterOptions options;
  options.nodes = 16;
  VirtualCluster cluster(*fixture().volume, options);
  FrameRequest request = wavesRequest(View{}, 64, 64, 0.9f);
  const FrameResult waves = cluster.renderFrame(request);
  CHECK(cluster.nodesRendered() == 16);  // counted once each, as the waves render them (progress display)
  request.settings.frontToBackWaves = false;
  const FrameResult independent = cluster.renderFrame(request);
  CHECK(waves.stats.samples() < independent.stats.samples());
  CHECK(maxAbsDifference(waves.image, independent.image, independent.image.rect()) <= 0.1f + 1e-5f);
  // Every node still composites and records its partial image (the stages view, the timeline).
  request.settings.frontToBackWaves = true;
  request.recordPhases = true;
  const FrameResult recorded = cluster.renderFrame(request);
  REQUIRE(recorded.phases);
  REQUIRE(recorded.phases->cells.size() == 16u);
  for (const auto& row : recorded.phases->cells) {
    REQUIRE_FALSE(row.empty());
    CHECK(row.front().label == "render");
  }
  CHECK(maxAbsDifference(recorded.image, waves.image, waves.image.rect()) == 0.0f);
}

TEST_CASE("front transmittance: the spent pixels of a run of eight or fewer, as at() <= stop one by one") {
  const Rect frame{3, 2, 21, 4};
  FrontTransmittance front(frame);
  // Partial images of opacity 0, 0.5, 0.9, 0.99 and 1 in a pattern, one pixel column each, so the
  // product in front ends on both sides of the stop (0.01) and exactly at 0.
  std::mt19937 random(7);
  const float alphas[] = {0.0f, 0.5f, 0.9f, 0.99f, 1.0f};
  for (int layer = 0; layer < 3; ++layer) {
    Image partial(frame);
    for (int y = frame.y; y < frame.bottom(); ++y)
      for (int x = frame.x; x < frame.right(); ++x) partial.at(x, y).a = alphas[random() % 5];
    front.addBehind(partial);
  }
  const float stop = 0.01f;
  int spentSeen = 0, litSeen = 0;
  for (int y = frame.y; y < frame.bottom(); ++y)
    for (int x = frame.x; x < frame.right(); ++x)
      for (int n = 1; n <= 8 && x + n <= frame.right(); ++n) {
        int expected = 0;
        for (int j = 0; j < n; ++j) expected |= int(front.at(x + j, y) <= stop) << j;
        CHECK_MESSAGE(front.spentIn(x, y, n, stop) == expected, "pixel " << x << "," << y << " n " << n);
        spentSeen += __builtin_popcount(unsigned(expected)), litSeen += n - __builtin_popcount(unsigned(expected));
      }
  CHECK(spentSeen > 0);
  CHECK(litSeen > 0);
}

TEST_CASE("front transmittance: a brick rendered with it dims each pixel as addBehind of its image would") {
  Fixture& f = fixture();
  const View view{};
  const Camera camera(view, glm::vec3(0.0f), glm::vec3(f.whole.volumeDims() - 1) * f.whole.spacing(), 48, 40);
  RenderSettings settings;
  settings.earlyTermination = 0.9f;
  const TransferTable table(f.tf, settings.stepVoxels);
  // Light already dimmed in front, unevenly: some pixels spent (their rays are skipped), some not.
  FrontTransmittance rendered(camera.frame()), reference(camera.frame());
  Image inFront(camera.frame());
  std::mt19937 random(3);
  const float alphas[] = {0.0f, 0.3f, 0.95f};
  for (int y = 0; y < camera.frame().h; ++y)
    for (int x = 0; x < camera.frame().w; ++x) inFront.at(x, y).a = alphas[random() % 3];
  rendered.addBehind(inFront);
  reference.addBehind(inFront);
  const RayCaster caster(f.whole, table, settings, f.range(), nullptr, nullptr, &rendered);
  RenderCounters counters;
  const Image image = caster.render(camera, counters);
  REQUIRE(counters.samples > 0);
  REQUIRE(counters.occluded > 0);  // spent pixels took no ray
  reference.addBehind(image);
  int dimmed = 0;
  for (int y = 0; y < camera.frame().h; ++y)
    for (int x = 0; x < camera.frame().w; ++x) {
      CHECK_MESSAGE(rendered.at(x, y) == reference.at(x, y), "pixel " << x << "," << y);
      dimmed += image.rect().contains(x, y) && image.at(x, y).a > 0.0f;
    }
  CHECK(dimmed > 100);
}

TEST_CASE("ray caster: a brick rendered region by region equals it rendered whole: pixels, counters and content bounds") {
  Fixture& f = fixture();
  RenderSettings settings;
  settings.earlyTermination = 0.9f;
  const TransferTable table(f.tf, settings.stepVoxels);
  const RayCaster caster(f.whole, table, settings, f.range());
  std::mt19937 rng(17);
  for (const View& view : test::randomViews(rng, 3)) {
    const Camera camera(view, glm::vec3(0.0f), glm::vec3(f.whole.volumeDims() - 1) * f.whole.spacing(), 53, 47);
    RenderCounters whole;
    Rect content{1, 2, 3, 4};
    const Image reference = caster.render(camera, whole, &content);
    REQUIRE(caster.screenRect(camera) == reference.rect());
    CHECK(content == reference.opaqueBounds());
    CHECK(!content.empty());
    CHECK(content != reference.rect());  // the blobs leave clear margins: the bounds are not just the rectangle
    REQUIRE(whole.samples > 0);
    // Regions of a ragged grid, in a shuffled order: sizes not multiples of eight, some a pixel wide.
    const Rect rect = reference.rect();
    std::vector<Rect> regions;
    for (int y = rect.y; y < rect.bottom();) {
      const int h = std::min(rect.bottom() - y, 1 + int(rng() % 13));
      for (int x = rect.x; x < rect.right();) {
        const int w = std::min(rect.right() - x, 1 + int(rng() % 19));
        regions.push_back(Rect{x, y, w, h});
        x += w;
      }
      y += h;
    }
    std::shuffle(regions.begin(), regions.end(), rng);
    // With the coverage render uses, and without one (every pixel of the rectangle then takes a
    // ray, so more rays are counted, but no more samples and no other pixel).
    const CellCoverage cover = caster.coverage(camera);
    for (const CellCoverage* coverage : {&cover, static_cast<const CellCoverage*>(nullptr)}) {
      Image pieced(rect);
      RenderCounters counters;
      Rect united;
      for (const Rect& region : regions) {
        const Rect bounds = caster.renderRegion(camera, region, pieced, counters, coverage);
        CHECK(bounds == pieced.crop(region).opaqueBounds());
        united = united.unite(bounds);
      }
      CHECK(united == content);
      CHECK(maxAbsDifference(pieced, reference, rect) == 0.0f);
      CHECK(counters.samples == whole.samples);
      if (coverage) {
        CHECK(counters.rays == whole.rays);
        CHECK(counters.occluded == whole.occluded);
      } else {
        CHECK(counters.rays > whole.rays);  // the blobs leave pixels no visible cell covers
      }
    }
  }
}

TEST_CASE("front-to-back waves: the same image bits with one, two and four worker threads") {
  // Pieces of a frame run in whatever order the threads take them; each pixel's bricks still
  // render it nearest first, so the light each reads, and the image, cannot depend on the order.
  std::mt19937 rng(63);
  const std::vector<View> views = test::randomViews(rng, 3);
  for (int nodes : {8, 64}) {
    std::vector<Image> first;
    for (int threads : {1, 2, 4}) {
      ClusterOptions options;
      options.nodes = nodes;
      options.threads = threads;
      VirtualCluster cluster(*fixture().volume, options);
      for (std::size_t v = 0; v < views.size(); ++v) {
        const FrameResult frame = cluster.renderFrame(wavesRequest(views[v], 97, 83, 0.9f));
        if (threads == 1) {
          first.push_back(frame.image);
          continue;
        }
        CHECK_MESSAGE(maxAbsDifference(frame.image, first[v], first[v].rect()) == 0.0f,
                      describe(nodes, "binary-swap", views[v], 97, 83) << " threads " << threads);
      }
    }
  }
}

TEST_CASE("front-to-back waves: a node composites once its own brick is rendered, as tasks or as threads") {
  // The waves render every brick beside the node tasks and hand each node its brick as soon as
  // the brick's last piece is done: the node's compositing starts after that piece ends, whatever
  // the other bricks are doing, and the frame is the same however the nodes run.
  std::mt19937 rng(64);
  const std::vector<View> views = test::randomViews(rng, 2);
  for (int nodes : {2, 8, 64}) {
    std::vector<Image> asTasks;
    for (NodeExecution execution : {NodeExecution::Tasks, NodeExecution::Threads}) {
      ClusterOptions options;
      options.nodes = nodes;
      options.execution = execution;
      VirtualCluster cluster(*fixture().volume, options);
      for (std::size_t v = 0; v < views.size(); ++v) {
        const std::string what = describe(nodes, "binary-swap", views[v], 57, 45) +
                                 (execution == NodeExecution::Tasks ? " tasks" : " threads");
        const FrameResult frame = cluster.renderFrame(wavesRequest(views[v], 57, 45, 0.9f));
        REQUIRE(frame.stats.perNode.size() == std::size_t(nodes));
        for (const NodeReport& node : frame.stats.perNode) {
          CHECK_MESSAGE(node.renderStart <= node.renderEnd, what << " node " << node.rank);
          REQUIRE_FALSE(node.phases.empty());
          CHECK_MESSAGE(node.renderEnd <= node.phases.front().start, what << " node " << node.rank);
        }
        if (execution == NodeExecution::Tasks) {
          asTasks.push_back(frame.image);
          continue;
        }
        CHECK_MESSAGE(maxAbsDifference(frame.image, asTasks[v], asTasks[v].rect()) == 0.0f, what);
      }
    }
  }
}
