// Timeline layout: bars from a node's report, the time axis's tick step, rows and scrolling.
#include "ui/timeline_layout.h"

#include <algorithm>
#include <cmath>

namespace kdswap {

bool hasTimeline(const FrameStats& stats) {
  if (stats.perNode.empty()) return false;
  for (const NodeReport& n : stats.perNode)
    if (!n.timed) return false;
  return true;
}

std::vector<TimelineBar> timelineBars(const NodeReport& node, bool durationsOnly) {
  using Kind = TimelineBar::Kind;
  std::vector<TimelineBar> bars;
  auto add = [&](Kind kind, double start, double end, int phase = -1, int brick = -1) {
    bars.push_back(TimelineBar{kind, phase, brick, start, end});
  };
  if (durationsOnly || !node.timed) {
    double t = node.renderSeconds;
    add(Kind::Render, 0.0, t);
    for (std::size_t k = 0; k < node.phases.size(); ++k) {
      const PhaseStats& p = node.phases[k];
      if (p.waitSeconds > 0) add(Kind::Wait, t, t + p.waitSeconds, int(k));
      t += p.waitSeconds;
      add(Kind::Composite, t, t + p.computeSeconds, int(k));
      t += p.computeSeconds;
    }
    return bars;
  }
  if (node.renderStart > 0) add(Kind::NotStarted, 0.0, node.renderStart);
  add(Kind::Render, node.renderStart, node.renderEnd);
  for (std::size_t b = 0; b < node.bricks.size(); ++b) add(Kind::Brick, node.bricks[b].start, node.bricks[b].end, -1, int(b));
  for (std::size_t k = 0; k < node.phases.size(); ++k) {
    const PhaseStats& p = node.phases[k];
    const double waited = std::min(p.start + p.waitSeconds, p.end);
    if (p.waitSeconds > 0) add(Kind::Wait, p.start, waited, int(k));
    add(Kind::Composite, waited, p.end, int(k));  // even when empty: the phase's tooltip stays reachable
  }
  return bars;
}

// Runs every UI frame over up to 4096 nodes: the ends timelineBars would give, without building bars.
double timelineSpan(const FrameStats& stats, bool durationsOnly) {
  double span = durationsOnly ? 0.0 : stats.wallSeconds;
  for (const NodeReport& n : stats.perNode) {
    if (durationsOnly || !n.timed) {
      span = std::max(span, n.renderSeconds + n.waitSeconds() + n.compositeSeconds());
      continue;
    }
    span = std::max(span, n.renderEnd);
    for (const NodeReport::BrickRender& b : n.bricks) span = std::max(span, b.end);
    for (const PhaseStats& p : n.phases) span = std::max(span, p.end);
  }
  return std::max(span, 1e-9);
}

int barAt(const std::vector<TimelineBar>& bars, double t, double slack) {
  int best = -1;
  double bestDistance = 0, bestLength = 0;
  for (std::size_t i = 0; i < bars.size(); ++i) {
    const TimelineBar& b = bars[i];
    const double distance = std::max({0.0, b.start - t, t - b.end}), length = b.end - b.start;
    if (distance > slack) continue;
    if (best < 0 || distance < bestDistance || (distance == bestDistance && length < bestLength))
      best = int(i), bestDistance = distance, bestLength = length;
  }
  return best;
}

double tickStep(double span, float widthPixels, float minPixels) {
  if (!(span > 0) || !(widthPixels > 0)) return 1.0;
  const double least = span * double(minPixels) / double(widthPixels);
  const double decade = std::pow(10.0, std::floor(std::log10(least)));
  for (double m : {1.0, 2.0, 5.0})
    if (m * decade >= least * (1 - 1e-12)) return m * decade;
  return 10.0 * decade;
}

TimelineRows timelineRows(int nodes, float available, float minRow, float maxRow, float labelPixels) {
  const int n = std::max(nodes, 1);
  TimelineRows rows;
  // Whole pixels: rows of equal height, and gaps that do not flicker between 0 and 1 pixel.
  rows.height = std::clamp(std::floor(available / float(n)), minRow, maxRow);
  rows.gap = rows.height >= 8 ? 2.0f : rows.height >= 4 ? 1.0f : 0.0f;
  while (float(rows.labelEvery) * rows.height < labelPixels) rows.labelEvery *= 2;
  rows.total = rows.height * float(n);
  return rows;
}

std::pair<int, int> visibleRows(const TimelineRows& rows, int nodes, float scroll, float visible) {
  if (rows.height <= 0 || nodes <= 0) return {0, 0};
  const int first = std::clamp(int(std::floor(scroll / rows.height)), 0, nodes);
  const int last = std::clamp(int(std::ceil((scroll + visible) / rows.height)), first, nodes);
  return {first, last};
}

}  // namespace kdswap
