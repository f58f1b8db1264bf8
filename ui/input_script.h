// InputScript: synthetic mouse and keyboard input for tests and measurements (--script FILE).
// Each UI frame the script's mouse position, buttons, wheel and keys replace what the window
// system reported, so a run is the same on any display, Xvfb included. One command a line:
//
//   move TARGET              put the mouse on a target (below); one frame
//   glide DX DY FRAMES       move the mouse by (DX, DY) pixels in FRAMES equal steps
//   down|up|click BUTTON     left, right or middle; click is down for one frame, then up
//   wheel STEPS              one wheel event (positive: away from the user, zooms in)
//   key K                    press and release a letter key (R resets the view)
//   type TEXT                type TEXT (the rest of the line, single spaces) into the widget
//                            with keyboard focus, as one frame's characters
//   frames N                 let N UI frames pass
//   wait full|preview        until the full-quality frame of the latest request is shown and
//                            nothing is rendering or pending; or until a preview is on screen
//                            (timeout: 300 s; fails at once when the latest request ended
//                            without a frame, e.g. data that would not open)
//   checkpoint NAME          record the state (view, transfer function, frames shown, layout)
//                            and pictures under NAME (see gui_app.h, --dump-state)
//   verify-redraw            on the next frame that changes nothing, redraw the whole window and
//                            count pixels differing from the partially redrawn one (DamageRenderer)
//
// Targets: `viewport FX FY` (fractions of the displayed image), `cell NODE PHASE` (centre of a
// compositing-stage cell), `tf-point K` (opacity control point K), `item NAME` (centre of a widget
// drawn this frame: data-path, open, and for a .raw path raw-dims-0..2, raw-type, raw-endian,
// raw-spacing-0..2, raw-skip; an open combo's entries as raw-type:uint16, raw-endian:big), `at X Y`
// (window pixels).
// `#` starts a comment.
#pragma once

#include <string>
#include <vector>

#include <imgui.h>

#include "ui/gui_state.h"

namespace kdswap {

class InputScript {
 public:
  //! Parses the file; throws kdswap::Error naming the file and line of a bad command.
  static InputScript load(const std::string& path);

  //! Call between the platform backend's NewFrame and ImGui::NewFrame: this frame's input.
  void apply(ImGuiIO& io) const;

  struct Step {
    bool finished = false;   //!< the last command completed
    std::string checkpoint;  //!< non-empty: record a checkpoint with this name now
    bool verifyRedraw = false;
  };
  //! Call once per UI frame after the frame was built: advances the commands. Throws
  //! kdswap::Error when a target is missing or a wait times out.
  Step advance(const GuiState& state, double now);

 private:
  struct Command {
    std::string verb;
    std::vector<std::string> args;
    int line = 0;
  };
  ImVec2 target(const Command& c, const GuiState& state) const;
  [[noreturn]] void fail(const Command& c, const std::string& what) const;

  std::string path_;
  std::vector<Command> commands_;
  std::size_t next_ = 0;        //!< index of the command in progress
  bool started_ = false;        //!< the command in progress has begun
  int framesLeft_ = 0;
  ImVec2 from_, by_;            //!< glide: start position and total offset
  int glideFrames_ = 0;
  double startedAt_ = 0;
  std::size_t shownAtStart_ = 0;

  // The synthetic input, applied every frame.
  ImVec2 mouse_{-FLT_MAX, -FLT_MAX};
  bool down_[3] = {false, false, false};
  float wheel_ = 0;
  int key_ = -1;                //!< GLFW key code held this frame
  std::string text_;            //!< characters typed this frame
};

}  // namespace kdswap
