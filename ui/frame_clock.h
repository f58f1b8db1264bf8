// FrameClock: where the UI thread's time goes, frame by frame (waiting for events, taking the
// worker's results and uploading them, building the ImGui frame, drawing, swapping), split by
// whether a frame was rendering in the background. Reported by --report-fps.
#pragma once

#include <array>
#include <string>
#include <vector>

namespace kdswap {

class FrameClock {
 public:
  //! The parts of one UI frame, in loop order.
  enum Part { Wait, Take, Build, Draw, Swap, kParts };
  static constexpr std::array<const char*, kParts> kPartNames = {"wait", "take", "build", "draw", "swap"};

  //! Starts a frame at `now` (wall seconds); the previous frame ends here.
  void begin(double now);
  //! Ends part `part` at `now`: it lasted from the previous mark (or begin) until now.
  void mark(Part part, double now);
  //! Whether a frame was rendering in the background during this UI frame.
  void setRendering(bool rendering) { current_.rendering = rendering; }
  //! Leave this frame out of the report: it did work for a test harness (saving pictures).
  void exclude() { current_.excluded = true; }
  //! Whether this frame reached the screen, and which fraction of the window it redrew.
  void setPresented(bool presented, double fraction) { current_.presented = presented, current_.fraction = fraction; }

  //! Summary as JSON: for "idle" and "rendering" UI frames, the count, the fps (1 / median
  //! interval and frames / seconds), median and 95th percentile of the interval and of each part
  //! (wall time), the UI thread's own work per frame (take + build + draw + swap, wall and thread
  //! CPU time), and how many frames were presented, with their median redrawn fraction.
  std::string reportJson() const;
  //! One line per kind of frame, for the terminal.
  std::string reportText() const;

 private:
  struct Sample {
    double interval = 0;                //!< wall seconds from this frame's begin to the next one's
    std::array<double, kParts> part{};  //!< wall seconds
    double workCpu = 0;                 //!< UI thread CPU seconds outside Wait
    double waitCpu = 0;                 //!< UI thread CPU seconds in Wait (event handling)
    bool rendering = false, presented = false, excluded = false;
    double fraction = 0;
  };
  std::vector<Sample> samples_;
  Sample current_;
  double frameStart_ = -1, lastMark_ = 0, lastCpu_ = 0;
};

}  // namespace kdswap
