// How large the interface is drawn: 1 on an ordinary screen, the monitor's content scale on a
// high-density one (2 on a 4K screen set to 200%), or what --ui-scale asks for (a projector in a
// classroom). The font, ImGui's spacing and the panels' own sizes in pixels are all multiplied by it.
#pragma once

namespace kdswap {

//! The font's size in pixels at scale 1.
inline constexpr float kBaseFontSize = 15.0f;
//! The range --ui-scale accepts and the monitor's scale is clamped to.
inline constexpr float kMinUiScale = 0.5f, kMaxUiScale = 4.0f;

//! Set once, before the first UI frame (gui_app.cpp).
void setUiScale(float scale);
float uiScale();
//! `pixels` at scale 1, at the current scale.
inline float scaled(float pixels) { return pixels * uiScale(); }

}  // namespace kdswap
