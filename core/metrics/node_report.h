// What one node measured in one frame: the quantities of the paper's tables, per phase, and when
// (a timeline: the wall interval of rendering and of each phase).
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
  //! The phase's wall interval, from beginPhase to endPhase: its wait and compute lie inside it
  //! and fill it (end - start == waitSeconds + computeSeconds). Clock: see NodeReport::timed.
  double start = 0, end = 0;
};

struct NodeReport {
  int rank = -1;
  double renderSeconds = 0;       //!< ray-casting work on one processor
  //! Wall interval of the render step: from the node's task starting the frame to its partial
  //! image ready to composite (with over-decomposition: brick shipping and every brick rendered).
  //! Its length is not renderSeconds: the caster's tiles may run on several threads at once, and
  //! the task may wait for a core or for a shipped brick.
  double renderStart = 0, renderEnd = 0;
  //! The start and end times are set. In the node program they are absolute nowSeconds(); a
  //! cluster's FrameStats holds them as seconds since the frame's start (rebaseTimes; over MPI
  //! each node's own arrival of the start message). A report made without them (one read back
  //! from elsewhere, a test's) has it false and every time 0.
  bool timed = false;
  //! Relative speed of the processor this node models (1 = this machine's core). Modelled times
  //! divide measured work by it; measured figures stay as measured.
  double speed = 1.0;
  std::uint64_t rays = 0, samples = 0;
  //! Of the rays: skipped because matter in front certainly ends them (the occlusion map, or with
  //! waves the light the bricks in front left spent).
  std::uint64_t occluded = 0;
  std::uint64_t privateBytes = 0; //!< brick (voxels + gradients) + largest image held
  std::vector<PhaseStats> phases; //!< compositing phases, in order (render not included)
  //! Over-decomposition: every brick this node rendered this frame.
  struct BrickRender {
    int brick = -1;
    double seconds = 0;
    std::uint64_t rays = 0, samples = 0;
    double start = 0, end = 0;  //!< wall interval of this brick's ray casting (same clock)
  };
  std::vector<BrickRender> bricks;
  //! Front-to-back waves: the ranks whose bricks are nearer the eye with screen rectangles that meet
  //! this one's. The modelled time has each node wait for their whole renders, as separate machines
  //! would; in process each screen cell waits only for those bricks' pieces in that cell, so on the
  //! wall clock the renders may overlap. Empty for the paper's independent nodes.
  std::vector<int> renderedAfter;

  //! Moves every time to a clock starting at `origin` (absolute seconds): the frame's start.
  void rebaseTimes(double origin) {
    renderStart -= origin, renderEnd -= origin;
    for (PhaseStats& p : phases) p.start -= origin, p.end -= origin;
    for (BrickRender& b : bricks) b.start -= origin, b.end -= origin;
  }

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
