// The paper's Figure 6 as a picture: one column per node, one row per phase (after rendering and
// after each compositing phase), each cell the node's image in the full frame with its region
// outlined and the rest dimmed; the final image below the grid.
#pragma once

#include <string>

#include "core/cluster/phase_record.h"
#include "core/image/image.h"

namespace kdswap {

//! Opaque RGB(A=1) picture of the grid. Cells are scaled so the grid is at most `maxWidth` wide.
Image drawPhaseGrid(const PhaseRecord& record, const Image& finalImage, int maxWidth = 2048);

//! One cell as a full-frame picture (region outlined, outside dimmed).
Image drawPhaseCell(const PhaseCell& cell, const Rect& frame);

//! Writes every cell as DIR/node<N>_phase<K>_<label>.png and the final image as DIR/final.png.
void writePhaseCells(const std::string& dir, const PhaseRecord& record, const Image& finalImage);

}  // namespace kdswap
