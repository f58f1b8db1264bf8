// Empty-space maps kept across frames: reused while nothing they depend on changes, rebuilt when
// something does, and a cluster whose transfer function changes between frames still renders the
// single-node image (a stale map would leave visible matter out).
#include <doctest/doctest.h>

#include <cstring>
#include <optional>

#include "core/render/empty_space_cache.h"
#include "core/render/reference_render.h"
#include "core/transfer/presets.h"
#include "test_support.h"

using namespace kdswap;

namespace {

bool sameReach(const EmptySpaceMap& a, const EmptySpaceMap& b) {
  const glm::ivec3 n = a.cellCount();
  if (n != b.cellCount()) return false;
  return std::memcmp(a.reachData(), b.reachData(), std::size_t(n.x) * n.y * n.z) == 0 &&
         a.anyVisible() == b.anyVisible() && a.visibleLo() == b.visibleLo() && a.visibleHi() == b.visibleHi();
}

//! Opacity 0 below `threshold`, rising to 0.6 at 1; colours from `hue`.
TransferFunction ramp(float threshold, float hue) {
  return TransferFunction({{0.0f, {hue, 0.2f, 0.9f}}, {1.0f, {1.0f, hue, 0.3f}}},
                          {{0.0f, 0.0f}, {threshold, 0.0f}, {1.0f, 0.6f}}, "ramp");
}

}  // namespace

TEST_CASE("an empty-space map is kept while the visible entries, mapping and switch stay, rebuilt otherwise") {
  auto volume = test::makeBlobs(glm::ivec3(40, 36, 33));
  const Brick brick = wholeVolumeBrick(*volume);
  const TransferTable base(ramp(0.5f, 0.1f), 0.5f);
  const TransferTable recoloured(ramp(0.5f, 0.8f), 0.5f);  // other colours, same entries with opacity > 0
  const TransferTable lower(ramp(0.2f, 0.1f), 0.5f);       // more entries visible

  EmptySpaceCache cache;
  const auto first = cache.mapFor(brick, base, 1.0f, 0.0f, true);
  CHECK(sameReach(*first, EmptySpaceMap(brick, base, 1.0f, 0.0f, true)));
  CHECK(cache.mapFor(brick, base, 1.0f, 0.0f, true) == first);
  CHECK(cache.mapFor(brick, recoloured, 1.0f, 0.0f, true) == first);

  const auto widened = cache.mapFor(brick, lower, 1.0f, 0.0f, true);
  CHECK(widened != first);
  CHECK(sameReach(*widened, EmptySpaceMap(brick, lower, 1.0f, 0.0f, true)));
  CHECK_FALSE(sameReach(*widened, *first));  // the test volume has cells between the two thresholds

  const auto rescaled = cache.mapFor(brick, lower, 0.5f, 0.0f, true);
  CHECK(rescaled != widened);
  CHECK(sameReach(*rescaled, EmptySpaceMap(brick, lower, 0.5f, 0.0f, true)));
  const auto off = cache.mapFor(brick, lower, 0.5f, 0.0f, false);
  CHECK(off != rescaled);
  CHECK(sameReach(*off, EmptySpaceMap(brick, lower, 0.5f, 0.0f, false)));

  cache.clear();
  const auto again = cache.mapFor(brick, lower, 0.5f, 0.0f, false);
  CHECK(again != off);
  CHECK(sameReach(*again, *off));
}

TEST_CASE("a cluster whose transfer function and range change between frames renders each frame's single-node image") {
  auto volume = test::makeBlobs(glm::ivec3(48, 40, 36));
  for (const int nodes : {1, 8, 16}) {
    ClusterOptions options;
    options.nodes = nodes;
    VirtualCluster cluster(*volume, options);
    FrameRequest request;
    request.width = 72;
    request.height = 64;
    request.view.azimuthDeg = 40.0f;
    request.settings.earlyTermination = 1.0f;  // exact comparison: no termination bound
    struct Step {
      float threshold, hue;
      std::optional<glm::vec2> range;  //!< unset: the data's range
    };
    // High threshold, then lower (more matter visible: a kept map would skip it), a colour-only
    // change, a narrower range (new mapping), and back to the first.
    const Step steps[] = {{0.6f, 0.1f, {}},
                          {0.15f, 0.1f, {}},
                          {0.15f, 0.9f, {}},
                          {0.15f, 0.9f, glm::vec2(0.0f, 0.5f)},
                          {0.6f, 0.1f, {}}};
    std::uint64_t previousSamples = 0;
    for (const Step& step : steps) {
      request.transfer = ramp(step.threshold, step.hue);
      request.settings.valueRange = step.range;
      request.view.azimuthDeg += 7.0f;
      const FrameResult frame = cluster.renderFrame(request);
      CAPTURE(nodes);
      CAPTURE(step.threshold);
      CAPTURE(step.range.has_value());
      CHECK(test::diffAgainstReference(*volume, request, frame.image) <= 1e-5f);
      CHECK(frame.stats.samples() != previousSamples);
      previousSamples = frame.stats.samples();
    }
  }
}
