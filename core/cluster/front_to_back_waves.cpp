// Front-to-back waves: a dependency graph over the bricks (brick j waits for every brick nearer
// the eye whose screen rectangle meets its own), run as tasks that release their dependents.
#include "core/cluster/front_to_back_waves.h"

#include <atomic>
#include <memory>

#include <oneapi/tbb/parallel_for_each.h>

#include "core/render/front_transmittance.h"
#include "core/util/error.h"

namespace kdswap {

std::vector<RenderedBrick> renderInWaves(std::vector<NodeState>& nodes, const FramePlan& plan) {
  const std::vector<int>& order = plan.order.frontToBack;  // ranks, nearest brick first
  const std::size_t n = order.size();
  std::vector<RenderedBrick> rendered(nodes.size());
  std::vector<Rect> rects(n);
  for (std::size_t i = 0; i < n; ++i) rects[i] = ownBrickScreenRect(nodes[std::size_t(order[i])], plan);

  // after[i]: the bricks (positions in `order`) that wait for brick i; waiting[j]: how many brick
  // j still waits for; waitsFor[j]: their ranks, for the modelled time (FrameStats::renderSpan).
  // Pairs are compared once per frame: P^2 / 2 rectangle tests (~1 ms at 1024).
  std::vector<std::vector<std::size_t>> after(n);
  std::vector<std::vector<int>> waitsFor(n);
  std::unique_ptr<std::atomic<int>[]> waiting(new std::atomic<int>[n]);
  std::vector<std::size_t> ready;
  for (std::size_t j = 0; j < n; ++j) {
    if (!rects[j].empty())
      for (std::size_t i = 0; i < j; ++i)
        if (!rects[i].intersect(rects[j]).empty()) after[i].push_back(j), waitsFor[j].push_back(order[i]);
    waiting[j].store(int(waitsFor[j].size()), std::memory_order_relaxed);
    if (waitsFor[j].empty()) ready.push_back(j);
  }

  FrontTransmittance front(plan.frame());
  tbb::parallel_for_each(ready.begin(), ready.end(), [&](std::size_t i, tbb::feeder<std::size_t>& feeder) {
    const int rank = order[i];
    RenderedBrick& r = rendered[std::size_t(rank)];
    r = renderOwnBrick(nodes[std::size_t(rank)], plan, &front);  // dims `front` where it rendered
    // (only bricks waiting for this one read those pixels)
    if (plan.nodesRendered) plan.nodesRendered->fetch_add(1, std::memory_order_relaxed);  // progress display
    // The last brick in front to finish releases the one behind; acq_rel orders every earlier
    // brick's writes to `front` before its reads.
    for (std::size_t j : after[i])
      if (waiting[j].fetch_sub(1, std::memory_order_acq_rel) == 1) feeder.add(j);
  });
  for (std::size_t j = 0; j < n; ++j) rendered[std::size_t(order[j])].renderedAfter = std::move(waitsFor[j]);
  return rendered;
}

void checkWavesWithBricksPerNode(bool waves, int bricksPerNode) {
  if (waves && bricksPerNode > 1)
    throw Error("--waves renders each node's one brick in visibility order: give --bricks-per-node 1 (over-decomposed "
                "bricks are handed out on demand and keep the occlusion map)");
}

}  // namespace kdswap
