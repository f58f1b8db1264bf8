// The GUI's panels: each one function drawing one window from GuiState, returning early when
// collapsed. They read snapshots core produced and edit the user's intent; none renders pixels.
#pragma once

#include <imgui.h>

#include "ui/gui_state.h"

namespace kdswap {

void drawViewportPanel(GuiState& state);
void drawStagesPanel(GuiState& state);
void drawTransferPanel(GuiState& state);
void drawTimingPanel(GuiState& state);
void drawSettingsPanel(GuiState& state);

//! A distinct colour per node, shared by the brick overlay, the stages headers and the timeline.
inline ImU32 nodeColour(int rank, float alpha = 1.0f) {
  const float hue = float(rank) * 0.618034f;  // golden-ratio steps keep neighbours apart
  return ImColor::HSV(hue - float(int(hue)), 0.65f, 0.95f, alpha);
}

//! The view a fresh scene starts from (and R restores): the core defaults with the user's
//! projection and up axis kept.
View resetView(const View& current);

}  // namespace kdswap
