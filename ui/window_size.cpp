#include "ui/window_size.h"

#include <algorithm>

namespace kdswap {

WindowSize fitWindowToWorkArea(WindowSize wanted, int areaWidth, int areaHeight) {
  if (areaWidth <= 0 || areaHeight <= 0) return wanted;
  // glfwCreateWindow sizes the content; a window manager adds a title bar on top, so a window cut
  // to the screen's height leaves room for one. One that fits already is left alone.
  constexpr int kTitleBar = 40;
  WindowSize size = wanted;
  if (size.width > areaWidth) size.width = std::max(areaWidth, kSmallestFittedWindow.width);
  if (size.height > areaHeight) size.height = std::max(areaHeight - kTitleBar, kSmallestFittedWindow.height);
  size.width = std::min(size.width, wanted.width), size.height = std::min(size.height, wanted.height);
  return size;
}

}  // namespace kdswap
