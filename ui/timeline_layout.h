// Timeline layout: a frame's per-node intervals as bars on a time axis, the rows they sit in and
// the axis ticks. Plain arithmetic, no ImGui, so it is tested windowless (gui_units_test.cpp).
#pragma once

#include <utility>
#include <vector>

#include "core/metrics/frame_stats.h"

namespace kdswap {

struct TimelineBar {
  enum class Kind { NotStarted, Render, Brick, Wait, Composite };
  Kind kind = Kind::Render;
  int phase = -1;             //!< index into NodeReport::phases (Wait, Composite), else -1
  int brick = -1;             //!< index into NodeReport::bricks (Brick), else -1
  double start = 0, end = 0;  //!< seconds since the frame's start (durations only: since 0)
};

//! True when every node's report carries start and end times (a stats record may lack them).
bool hasTimeline(const FrameStats& stats);

//! One node's bars in drawing order. Timed: not started until its task ran, the render interval
//! (and inside it each brick's ray casting), then per phase its wait followed by its compositing:
//! the stats hold only the two totals of a phase, and a phase mostly waits for the partner's
//! pixels before compositing them. `durationsOnly` (forced for a report without times): the
//! durations laid end to end from 0, render work first, as before there were times.
std::vector<TimelineBar> timelineBars(const NodeReport& node, bool durationsOnly);

//! Seconds the axis spans: the frame's wall time (and any bar past it), or the longest sum of
//! durations.
double timelineSpan(const FrameStats& stats, bool durationsOnly);

//! Index of the bar at time `t`, counting a bar's ends as `slack` seconds wider (so a bar thinner
//! than a pixel can be hovered); the shortest one where bars overlap (a brick inside its render
//! interval). -1 when none.
int barAt(const std::vector<TimelineBar>& bars, double t, double slack);

//! The smallest step of 1, 2 or 5 x 10^k seconds whose ticks lie at least `minPixels` apart when
//! `span` seconds fill `widthPixels`.
double tickStep(double span, float widthPixels, float minPixels);

struct TimelineRows {
  float height = 0;    //!< one row, pixels
  float gap = 0;       //!< blank pixels at a row's bottom, so neighbouring rows stay apart
  int labelEvery = 1;  //!< label rows 0, n, 2n, ... (a power of two)
  float total = 0;     //!< every row: more than the space given means the rows scroll
};

//! Rows sharing `available` pixels, each `minRow` to `maxRow` high (4096 nodes scroll; 8 nodes are
//! not each a panel high), labelled often enough that labels lie `labelPixels` apart or more.
TimelineRows timelineRows(int nodes, float available, float minRow, float maxRow, float labelPixels);

//! Rows [first, last) that show at scroll offset `scroll` in a view `visible` pixels high.
std::pair<int, int> visibleRows(const TimelineRows& rows, int nodes, float scroll, float visible);

}  // namespace kdswap
