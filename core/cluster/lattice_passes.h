// Passes of one frame on shifted sampling lattices, averaged (kdswap render --passes, kdswap
// animate --passes): pass i is an ordinary distributed frame whose rays' lattice phases are
// shifted by latticePassShift(i), and the picture is the passes' mean, in which jitter's grain and
// the lattice's rings average out. (The desktop app refines a still view pass by pass the same
// way, in ui/render_worker.cpp, publishing the mean after each pass.)
#pragma once

#include <functional>

#include "core/cluster/frame_request.h"
#include "core/cluster/virtual_cluster.h"

namespace kdswap {

inline constexpr int kMaxLatticePasses = 256;  //!< --passes' upper bound: beyond it the mean hardly changes

struct PassesResult {
  //! The first pass's result (stats, tiles, and phases if the request asked for them), its image
  //! replaced by the mean of all passes.
  FrameResult frame;
  int passes = 1;
  double wallSeconds = 0.0;  //!< all passes' wall time
};

//! Renders `request` as `passes` passes (1: one ordinary frame) on `cluster`; `passDone` (if set)
//! is called after each. Throws what renderFrame throws.
PassesResult renderPasses(VirtualCluster& cluster, const FrameRequest& request, int passes,
                          const std::function<void()>& passDone = {});

}  // namespace kdswap
