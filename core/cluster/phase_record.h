// PhaseRecord: every node's image and region after rendering and after each compositing phase,
// kept when a frame asks for it (the paper's Figure 6, the GUI's stages panel, --phases).
#pragma once

#include <string>
#include <vector>

#include "core/image/image.h"

namespace kdswap {

struct PhaseCell {
  std::string label;  //!< "render", "swap", ...
  int partner = -1;
  Rect region;        //!< the node's region after this phase (render: its brick's screen rect)
  Image image;        //!< the node's image after this phase
  std::uint64_t bytesExchanged = 0;
};

struct PhaseRecord {
  Rect frame;
  std::vector<std::vector<PhaseCell>> cells;  //!< cells[node][phase]; phase 0 is "render"
  int phaseCount() const { return cells.empty() ? 0 : int(cells.front().size()); }
};

}  // namespace kdswap
