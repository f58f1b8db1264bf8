// The desktop app's window, loop and screenshot: GLFW + Dear ImGui (OpenGL 3.3 core) around the
// panels in panels.h and the background RenderWorker.
#pragma once

#include <string>

#include "ui/window_size.h"
#include "core/volume/reader.h"

namespace kdswap {

struct GuiOptions {
  std::string dataset = "phantom:128";  //!< built-in data set spec or volume file path
  RawLayout raw;                        //!< --raw-*: the layout of `dataset` if it is a headerless .raw file
  int nodes = 8;
  std::string partition = "kd";
  std::string composite = "binary-swap";
  std::string balance = "space";        //!< plane placement: space or cost (from the transfer function)
  int bricksPerNode = 1;                //!< over-decomposition, 1..64
  bool waves = false;                   //!< front-to-back waves (RenderSettings::frontToBackWaves)
  int refinePasses = 8;                 //!< GuiState::refinePasses, 1..kMaxRefinePasses
  std::string tf;                       //!< preset name or JSON path; empty: the data set's preset
  int imageSize = 512;                  //!< rendered frame is imageSize x imageSize
  std::string up = "+z";                //!< volume axis up on screen (parseUpAxis); R keeps it
  int windowWidth = kDefaultWindowSize.width, windowHeight = kDefaultWindowSize.height;
  bool windowSizeGiven = false;         //!< --size given: open at exactly that size; else fit the screen
  float uiScale = 0.0f;                 //!< --ui-scale; 0: the monitor's content scale (ui/ui_scale.h)
  std::string screenshot;               //!< write the window to this PNG before exiting
  int frames = 0;                       //!< > 0: exit after this many UI frames once the first full frame is shown
  std::string layout;                   //!< with --screenshot: JSON of where panels drew (for tests)
  std::string script;                   //!< synthetic input (ui/input_script.h); exit when it ends
  std::string dumpState;                //!< at exit: JSON of the state, script checkpoints, frames shown
  std::string reportFps;                //!< at exit: JSON of the UI frame timing (see FrameClock)
  bool fullRedraw = false;              //!< draw the whole window every frame (see DamageRenderer)
};

//! Runs the app until the window closes (or the screenshot is written). Returns the exit code.
//! Throws kdswap::Error for a bad option or when no display / OpenGL 3.3 context is available.
int runGui(const GuiOptions& options);

}  // namespace kdswap
