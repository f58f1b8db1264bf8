// The speedup chart (the paper's Figures 7 and 8), rasterised by kdswap itself: modelled speedup
// against node count on a log2 axis, one coloured curve per image size, the ideal line dashed,
// a small legend. Labels use the built-in 5x7 bitmap font.
#pragma once

#include <string>
#include <vector>

#include "core/bench/bench_grid.h"
#include "core/image/image.h"

namespace kdswap {

//! Opaque chart of the cells of `strategy` (BenchCell::speedup must be filled). Throws Error when
//! the size is below 200x150 or no cell belongs to `strategy`.
Image drawSpeedupChart(const std::vector<BenchCell>& cells, const std::string& strategy, int width = 640,
                       int height = 480);

}  // namespace kdswap
