// BrickSchedule: who renders which brick in one over-decomposed frame, and which bricks must be
// shipped first. Bricks are handed out on demand: every node starts on its own bricks, and a node
// that runs out takes a brick still waiting at the node with the most work left (from the end of
// its queue). The virtual nodes share two cores, so "runs out" cannot be observed in real time:
// the hand-out is simulated on a modelled clock per node from each brick's estimated cost (its
// work last frame: samples taken plus a cost per ray; or the cost field's estimate at first)
// divided by the node's speed.
#pragma once

#include <cstdint>
#include <set>
#include <utility>
#include <vector>

#include "core/partition/brick_layout.h"
#include "core/partition/cost_field.h"

namespace kdswap {

struct BrickSchedule {
  const BrickLayout* layout = nullptr;
  std::vector<std::vector<int>> renders;  //!< renders[node]: bricks it renders, in order
  //! ships[home]: (brick, destination) pairs the home sends before rendering: its bricks that
  //! another node renders this frame and does not hold yet.
  std::vector<std::vector<std::pair<int, int>>> ships;
  std::vector<int> receives;  //!< receives[node]: bricks shipped to it this frame
  double modelledMakespan = 0;  //!< the simulated frame's render time (max over nodes)
};

//! The estimate of a brick's work for the next frame, from what it took this frame: the samples
//! plus a cost per ray for setup and empty-space stepping. Counts, not seconds: measured times on a
//! shared machine vary far more from frame to frame than the work does, and counts are the same on
//! every MPI rank that plans the next frame.
inline double brickWork(std::uint64_t samples, std::uint64_t rays) { return double(samples) + 16.0 * double(rays); }

//! The first frame's estimate of each brick's work, before any was measured: the cost field's
//! (--balance cost), or without one the brick's share of a uniform field.
std::vector<double> firstBrickCosts(const BrickLayout& layout, const CostField* cost, const glm::ivec3& dims);

//! `cost[b]`: estimated seconds of brick b on a speed-1 node. `speeds`: per node (empty = 1).
//! `held[n]`: bricks node n holds (its own ones are implied); updated with this frame's shipments.
BrickSchedule scheduleBricks(const BrickLayout& layout, const std::vector<double>& cost,
                             const std::vector<double>& speeds, std::vector<std::set<int>>& held);

}  // namespace kdswap
