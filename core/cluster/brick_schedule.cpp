// On-demand brick hand-out, simulated on modelled per-node clocks.
#include "core/cluster/brick_schedule.h"

#include <algorithm>
#include <deque>

#include "core/util/check.h"

namespace kdswap {

std::vector<double> firstBrickCosts(const BrickLayout& layout, const CostField* cost, const glm::ivec3& dims) {
  const CostField uniform = cost ? CostField{} : CostField::uniform(dims);
  std::vector<double> costs;
  for (int b = 0; b < layout.bricks(); ++b) costs.push_back((cost ? *cost : uniform).cost(layout.box(b)));
  return costs;
}

BrickSchedule scheduleBricks(const BrickLayout& layout, const std::vector<double>& cost,
                             const std::vector<double>& speeds, std::vector<std::set<int>>& held) {
  const int nodes = layout.nodes();
  KDSWAP_CHECK_EQ(int(cost.size()), layout.bricks());
  held.resize(std::size_t(nodes));
  BrickSchedule s;
  s.layout = &layout;
  s.renders.assign(std::size_t(nodes), {});
  s.ships.assign(std::size_t(nodes), {});
  s.receives.assign(std::size_t(nodes), 0);
  auto speed = [&](int n) { return speeds.empty() ? 1.0 : speeds[std::size_t(n)]; };

  // Every brick costs a little (ray setup, compositing its image), so empty bricks, or bricks
  // measured at zero, still advance their node's clock and are not all taken by one node.
  double mean = 0.0;
  for (double c : cost) mean += c / double(cost.size());
  std::vector<double> work(cost.size());
  for (std::size_t b = 0; b < cost.size(); ++b) work[b] = std::max(cost[b], 0.0) + 1e-3 * mean + 1e-12;

  std::vector<std::deque<int>> waiting{std::size_t(nodes)};
  std::vector<double> waitingWork(std::size_t(nodes), 0.0), clock(std::size_t(nodes), 0.0);
  for (int b = 0; b < layout.bricks(); ++b) {
    waiting[std::size_t(layout.home(b))].push_back(b);
    waitingWork[std::size_t(layout.home(b))] += work[std::size_t(b)];
  }
  for (int handedOut = 0; handedOut < layout.bricks(); ++handedOut) {
    // The node that finishes its current brick first asks next (lowest rank on ties).
    int asker = 0;
    for (int n = 1; n < nodes; ++n)
      if (clock[std::size_t(n)] < clock[std::size_t(asker)]) asker = n;
    int from = asker;
    if (waiting[std::size_t(asker)].empty()) {
      for (int n = 0; n < nodes; ++n)
        if (!waiting[std::size_t(n)].empty() &&
            (waiting[std::size_t(from)].empty() || waitingWork[std::size_t(n)] > waitingWork[std::size_t(from)]))
          from = n;
    }
    std::deque<int>& queue = waiting[std::size_t(from)];
    const int brick = from == asker ? queue.front() : queue.back();
    if (from == asker) queue.pop_front(); else queue.pop_back();
    waitingWork[std::size_t(from)] -= work[std::size_t(brick)];
    clock[std::size_t(asker)] += work[std::size_t(brick)] / speed(asker);
    s.renders[std::size_t(asker)].push_back(brick);
    if (from != asker && held[std::size_t(asker)].insert(brick).second) {
      s.ships[std::size_t(from)].emplace_back(brick, asker);
      ++s.receives[std::size_t(asker)];
    }
  }
  for (double c : clock) s.modelledMakespan = std::max(s.modelledMakespan, c);
  return s;
}

}  // namespace kdswap
