// GuiState: everything the panels draw from and edit. The user's intent (scene, view, transfer
// function, settings) is edited by panels, which then call requestFrame(); the newest snapshots
// the RenderWorker produced are read-only. The GUI loop (gui_app.cpp) turns requests into
// submissions. Only the UI thread touches this.
#pragma once

#include <cstdint>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <imgui.h>

#include "core/cluster/frame_request.h"
#include "ui/gl_texture.h"
#include "ui/raw_layout_fields.h"
#include "ui/render_worker.h"
#include "ui/sweep_worker.h"

namespace kdswap {

//! Where things were drawn this UI frame, in window pixels (for --layout and the GUI test).
struct DrawnLayout {
  ImVec4 viewport{0, 0, 0, 0};  //!< x, y, w, h of the displayed image
  int columns = 0, rows = 0;
  struct Cell {
    int node, phase;
    ImVec4 rect;
  };
  std::vector<Cell> cells;
  std::vector<ImVec2> tfPoints;  //!< opacity control points of the transfer-function editor
  struct Shown {
    int node = -1, phase = -1;
    ImVec4 rect{0, 0, 0, 0};
  };
  Shown tooltip;   //!< the stage cell whose tooltip was drawn (rect: the tooltip window)
  Shown enlarged;  //!< the stage cell shown enlarged (rect: the enlarged picture)
  //! Widgets a script reaches by name (`move item raw-dims-0`): the settings panel's data path,
  //! Open button and raw-layout fields, and the entries of an open combo ("raw-type:uint16").
  std::map<std::string, ImVec4> items;
};

//! A frame the viewport started showing (for --dump-state and the interaction test).
struct ShownFrame {
  long uiFrame = 0;
  std::uint64_t id = 0;
  bool preview = false;
  int width = 0, height = 0;
  View view;
  bool mouseDown = false;  //!< a mouse button was held when it arrived
};

struct StagesUi {
  int phase = -1;            //!< last phase shown; -1 follows the newest frame's last phase
  bool playing = false;
  double nextStepAt = 0;     //!< when the animation advances (ImGui time)
  int selectedNode = -1, selectedPhase = -1;
  float cellScale = 1.0f;    //!< multiplies the fit-to-width cell size
};

struct TransferUi {
  int draggedPoint = -1;
  std::string path = "transfer.json";
  int preset = -1;
};

struct TimelineUi {
  bool durationsOnly = false;  //!< lay durations end to end (the view before frames carried times)
};

struct SettingsUi {
  std::string typedData;  //!< the path or spec being typed
  RawLayoutFields raw;    //!< shown while typedData is a .raw file
  std::optional<std::string> rawFilledFor;  //!< the typedData `raw` was last filled for
  int nodes = 0;          //!< the node count while its slider is dragged
  int bricksPerNode = 0;  //!< bricks per node while its slider is dragged
};

inline constexpr int kMaxRefinePasses = 64;  //!< GuiState::refinePasses' upper bound (--refine, the slider)

struct GuiState {
  // The user's intent.
  SceneSpec scene;
  FrameRequest request;      //!< view, full-quality size, transfer function, settings
  bool showBricks = true;
  //! A still view's full frame is refined to the mean of this many passes on shifted sampling
  //! lattices (kdswap render --passes), rendered while nothing moves; 1: no refinement.
  int refinePasses = 8;
  bool tfEdited = false;     //!< the user chose a transfer function; do not replace it by a preset

  // Requests raised by panels this UI frame.
  bool wantPreview = false;  //!< the view or a value is being dragged: a quick frame now
  bool wantFull = false;     //!< a settled change: a full frame
  void requestFrame(bool continuous) { (continuous ? wantPreview : wantFull) = true; }

  // The newest results.
  std::shared_ptr<const SceneSnapshot> sceneShown;  //!< the scene the newest frame came from
  std::shared_ptr<const FrameSnapshot> frame;       //!< newest frame (maybe a preview)
  std::shared_ptr<const FrameSnapshot> fullFrame;   //!< newest full frame (stages, timing)
  GlTexture frameTexture;                           //!< `frame`, shown in the viewport
  GlTexture fullTexture, stagesTexture;             //!< `fullFrame`'s image and stage atlas
  std::uint64_t lastSubmitted = 0;                  //!< id of the newest request sent to the worker
  std::uint64_t lastFailed = 0;                     //!< id of the newest request that ended without a frame
  bool refinePending = false;                       //!< a preview is shown; full quality follows when the mouse rests
  long uiFrame = 0;                                 //!< UI frames drawn so far
  bool logShown = false;                            //!< keep shownLog (scripts and --dump-state)
  std::vector<ShownFrame> shownLog;                 //!< every frame taken from the worker, oldest first
  std::vector<std::string> errors;                  //!< shown until dismissed
  bool rendering = false, building = false;

  // Panels' own state.
  StagesUi stages;
  TransferUi transfer;
  SettingsUi settings;
  TimelineUi timeline;
  SweepWorker* sweep = nullptr;
  std::vector<std::string> dataChoices;  //!< built-in specs, then files found
  //! Per .raw path, the layout last given for it (--raw-* for the start-up file, the data panel's
  //! fields on Open): the file opens with it whenever chosen again, and the fields show it.
  std::map<std::string, RawLayout> rawLayouts;
  DrawnLayout layout;

  //! The newest request ended without a frame and none is shown: nothing will appear until the
  //! user changes something (start-up data that would not open, say). Its error is in `errors`.
  bool nothingToShow() const { return lastSubmitted != 0 && lastFailed == lastSubmitted && !frame; }
};

}  // namespace kdswap
