// What one node measured in one frame: the quantities of the paper's tables, per phase.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "core/image/rect.h"

namespace kdswap {

struct PhaseStats {
  std::string label;         //!< "render", "fold", "swap", "merge", "chain"
  int partner = -1;
  Rect region;               //!< the node's screen region after the phase
  double computeSeconds = 0; //!< compositing work (time suspended excluded)
  double waitSeconds = 0;    //!< time waiting for a message
  std::int64_t pixels = 0;   //!< pixels composited
  std::uint64_t bytesSent = 0, bytesReceived = 0;
  std::uint64_t messagesSent = 0, messagesReceived = 0;
};

struct NodeReport {
  int rank = -1;
  double renderSeconds = 0;       //!< ray-casting work on one processor
  //! Relative speed of the processor this node models (1 = this machine's core). Modelled times
  //! divide measured work by it; measured figures stay as measured.
  double speed = 1.0;
  std::uint64_t rays = 0, samples = 0;
  std::uint64_t occluded = 0;     //!< of the rays: skipped by occlusion culling
  std::uint64_t privateBytes = 0; //!< brick (voxels + gradients) + largest image held
  std::vector<PhaseStats> phases; //!< compositing phases, in order (render not included)
  //! Over-decomposition: every brick this node rendered this frame.
  struct BrickRender {
    int brick = -1;
    double seconds = 0;
    std::uint64_t rays = 0, samples = 0;
  };
  std::vector<BrickRender> bricks;

  double modelledRenderSeconds() const { return renderSeconds / speed; }
  double compositeSeconds() const {
    double s = 0;
    for (const PhaseStats& p : phases) s += p.computeSeconds;
    return s;
  }
  double waitSeconds() const {
    double s = 0;
    for (const PhaseStats& p : phases) s += p.waitSeconds;
    return s;
  }
  std::uint64_t bytesSent() const {
    std::uint64_t b = 0;
    for (const PhaseStats& p : phases) b += p.bytesSent;
    return b;
  }
};

}  // namespace kdswap
