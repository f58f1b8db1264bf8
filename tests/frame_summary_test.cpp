// The one-frame summary that `kdswap render` prints (formatFrameTable): the culled ray-brick pairs
// and the occlusion map's time appear where there are some, and not as zeros where there are none.
#include <doctest/doctest.h>

#include "core/metrics/frame_stats.h"

using namespace kdswap;

namespace {

FrameStats twoNodes(std::uint64_t occluded, double mapSeconds) {
  FrameStats s;
  s.nodes = 2;
  s.width = s.height = 64;
  s.strategy = "binary-swap";
  s.partition = "kd";
  s.wallSeconds = 0.02;
  s.occlusionMapSeconds = mapSeconds;
  for (int rank = 0; rank < 2; ++rank) {
    NodeReport n;
    n.rank = rank;
    n.rays = 1000;
    n.occluded = rank == 1 ? occluded : 0;
    s.perNode.push_back(n);
  }
  return s;
}

}  // namespace

TEST_CASE("the frame summary names the culled pairs and the occlusion map's time only where there are some") {
  const std::string none = formatFrameTable(twoNodes(0, 0.0));
  CHECK(none.find("skipped") == std::string::npos);
  CHECK(none.find("occlusion map") == std::string::npos);
  const std::string culled = formatFrameTable(twoNodes(250, 0.00425));
  CHECK(culled.find("rays 2000 (250 skipped: matter in front ends them)") != std::string::npos);
  CHECK(culled.find("gather 0.00 ms, occlusion map 4.25 ms)") != std::string::npos);
}
