// 8-bit pictures the GUI uploads as textures, made from core's float images on the render worker
// (so the UI thread only uploads): the final frame, and the compositing stages as one atlas.
#pragma once

#include <cstdint>
#include <vector>

#include "core/cluster/phase_record.h"
#include "core/image/image.h"

namespace kdswap {

//! Dark blue-grey the images are composited over (the same as core's phase grid).
inline constexpr float kImageBackground[3] = {0.08f, 0.08f, 0.10f};

struct Pixels {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  //!< opaque RGBA8, row-major, top row first
  bool empty() const { return width <= 0 || height <= 0; }
};

//! `image` over the background, covering `frame`, box-filtered down so neither side exceeds
//! `maxSide` (aspect kept).
Pixels toPixels(const Image& image, const Rect& frame, int maxSide);

//! The stages of one frame (Figure 6) as a single atlas: cell (node, phase) occupies
//! [node * cellWidth, +cellWidth) x [phase * cellHeight, +cellHeight). Outside a cell's region
//! the picture is dimmed; the region outline is left to the GUI, which draws it crisply.
struct StageAtlas {
  Pixels pixels;
  int columns = 0, rows = 0;
  int cellWidth = 0, cellHeight = 0;
};

//! Cells shrink with the node count so the atlas stays under `maxAtlasWidth` pixels wide.
StageAtlas buildStageAtlas(const PhaseRecord& record, int maxCellSide = 192, int maxAtlasWidth = 8192);

}  // namespace kdswap
