// The GUI's panels: each one function drawing one window from GuiState, returning early when
// collapsed. They read snapshots core produced and edit the user's intent; none renders pixels.
#pragma once

#include <string>

#include <imgui.h>

#include "ui/gui_state.h"

namespace kdswap {

void drawViewportPanel(GuiState& state);
void drawStagesPanel(GuiState& state);
void drawTransferPanel(GuiState& state);
void drawTimingPanel(GuiState& state);
void drawSettingsPanel(GuiState& state);
//! The Timing panel's Timeline tab (timeline_view.cpp): the frame's per-node Gantt chart.
void drawTimelineTab(const FrameSnapshot& frame, TimelineUi& ui);

//! A distinct colour per node, shared by the brick overlay, the stages headers and the timeline.
inline ImU32 nodeColour(int rank, float alpha = 1.0f) {
  const float hue = float(rank) * 0.618034f;  // golden-ratio steps keep neighbours apart
  return ImColor::HSV(hue - float(int(hue)), 0.65f, 0.95f, alpha);
}

//! "1 node", "8 nodes": a count with its noun, singular for one.
inline std::string counted(long long n, const char* noun) {
  return std::to_string(n) + " " + noun + (n == 1 ? "" : "s");
}

//! `text` shortened with "..." to fit `width` pixels in the current font (whole if it fits).
std::string fitText(const std::string& text, float width);
//! TextUnformatted that ends in "..." when `text` is wider than the space left on the line, with
//! the whole text in a tooltip then.
void textFitted(const std::string& text, bool disabled = false);
//! SameLine() when an item `width` pixels wide still fits on the current line, else a new line.
void sameLineIfFits(float width);
//! Width of a button showing `label` (frame padding included).
float buttonWidth(const char* label);
//! Width of a widget `item` pixels wide followed by its `label`.
float labelledWidth(float item, const char* label);

//! What a panel without a full frame shows: that one is coming, or, when the newest request
//! failed with nothing on screen, that none will come until the user changes something.
inline void drawNoFullFrameText(const GuiState& state) {
  ImGui::PushTextWrapPos(0.0f);  // wrapped at the panel's edge, however narrow
  ImGui::TextDisabled("%s", state.nothingToShow()
                                ? "Nothing to show: the Viewport says why. Choose other data or settings."
                                : "Waiting for the first full frame...");
  ImGui::PopTextWrapPos();
}

//! The view a fresh scene starts from (and R restores): the core defaults with the user's
//! projection and up axis kept.
View resetView(const View& current);

}  // namespace kdswap
