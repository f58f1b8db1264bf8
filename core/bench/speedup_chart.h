// The speedup chart (the paper's Figures 7 and 8), rasterised by kdswap itself: modelled speedup
// against node count, both on log2 axes (as the desktop app's Timing panel draws it), one coloured
// curve per image size, the ideal line dashed, a small legend. Labels use the built-in 5x7 font.
#pragma once

#include <string>
#include <vector>

#include "core/bench/bench_grid.h"
#include "core/image/image.h"

namespace kdswap {

//! Where the chart puts a point. Both axes are log2, so the ideal speedup (= P) is a straight
//! diagonal and a straight segment between two measured counts is a constant parallel efficiency
//! trend, not a line that bends against the ideal between the measurements.
struct SpeedupChartLayout {
  int left = 0, right = 0, top = 0, bottom = 0;  //!< plot area in image pixels
  double log2NodesLo = 0, log2NodesHi = 1;        //!< x range
  double log2SpeedupLo = 0, log2SpeedupHi = 1;    //!< y range: whole powers of two

  float x(double nodes) const;
  float y(double speedup) const;
};

//! The layout drawSpeedupChart uses for these cells (same arguments, same errors).
SpeedupChartLayout speedupChartLayout(const std::vector<BenchCell>& cells, const std::string& strategy,
                                      int width = 640, int height = 480);

//! Opaque chart of the cells of `strategy` (BenchCell::speedup must be filled). Throws Error when
//! the size is below 200x150 or no cell belongs to `strategy`. Cells without a speedup (an
//! interrupted cell's 0) are left out of the curves.
Image drawSpeedupChart(const std::vector<BenchCell>& cells, const std::string& strategy, int width = 640,
                       int height = 480);

}  // namespace kdswap
