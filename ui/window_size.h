// The window's size on opening: the size asked for with --size, or else the default shrunk to the
// screen, so a laptop's 1366 x 768 shows the whole window (the panels lay out down to 640 x 480).
#pragma once

namespace kdswap {

struct WindowSize {
  int width = 0, height = 0;
};

//! The default window size, as big as the panels want it on a large screen.
inline constexpr WindowSize kDefaultWindowSize{1600, 1000};
//! The smallest size the window is shrunk to, whatever the screen.
inline constexpr WindowSize kSmallestFittedWindow{640, 480};

//! `wanted` shrunk to fit a work area of `areaWidth` x `areaHeight` pixels (the screen less its
//! panels; 0 or less: unknown, then `wanted` as it is). A side that fits is kept; one that does not
//! takes the area's (the height less room for a title bar), but not below kSmallestFittedWindow.
WindowSize fitWindowToWorkArea(WindowSize wanted, int areaWidth, int areaHeight);

}  // namespace kdswap
