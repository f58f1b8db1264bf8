// What the GUI shows and holds, as JSON, for --dump-state and the interaction test: the view, the
// transfer function, the selected stage cell, where things were drawn, the frames shown.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

#include "ui/gui_state.h"

namespace kdswap {

nlohmann::json describeView(const View& view);
//! The current state (without the log of frames shown).
nlohmann::json describeState(const GuiState& state);
//! Every frame taken from the worker, oldest first (GuiState::shownLog).
nlohmann::json describeShownFrames(const GuiState& state);
//! Writes 8-bit pixels (top row first) as a PNG; throws kdswap::Error when it cannot.
void writePixels(const std::string& path, const Pixels& pixels);

}  // namespace kdswap
