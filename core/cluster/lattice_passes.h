// Passes of one frame on shifted sampling lattices, averaged (kdswap render --passes, kdswap
// animate --passes): pass i is an ordinary distributed frame whose rays' lattice phases are
// shifted by latticePassShift(i), and the picture is the passes' mean, in which jitter's grain and
// the lattice's rings average out. The desktop app's refinement of a still view is the same loop,
// publishing the mean after each pass and stopping when a newer request arrives.
#pragma once

#include <functional>

#include "core/cluster/frame_request.h"
#include "core/cluster/virtual_cluster.h"
#include "core/image/image_average.h"
#include "core/volume/brick.h"

namespace kdswap {

inline constexpr int kMaxLatticePasses = 256;  //!< --passes' upper bound: beyond it the mean hardly changes

struct PassesResult {
  //! The first pass's result (stats, tiles, and phases if the request asked for them), its image
  //! replaced by the mean of all passes.
  FrameResult frame;
  int passes = 1;            //!< passes rendered (fewer than asked when the observer stopped them)
  double wallSeconds = 0.0;  //!< all passes' wall time
};

//! Called after pass `pass` (0 first) with that pass's own result and the running mean (which
//! holds the passes so far when more than one was asked for, nothing otherwise); returning false
//! ends the passes there.
using PassObserver = std::function<bool(int pass, const FrameResult& result, const ImageAverage& mean)>;

//! Renders `request` as `passes` passes (1: one ordinary frame) on `cluster`, each seen by
//! `afterPass` if set. Throws what renderFrame throws.
PassesResult renderPasses(VirtualCluster& cluster, const FrameRequest& request, int passes,
                          const PassObserver& afterPass = {});

//! The single-node reference of the same passes (renderReference over `whole`, the whole volume
//! as one brick), averaged alike: what --verify compares a mean of passes with.
Image referencePasses(const Brick& whole, const FrameRequest& request, glm::vec2 valueRange, int passes);

}  // namespace kdswap
