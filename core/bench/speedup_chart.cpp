// Speedup chart: log2-log2 axes, ticks, one polyline per image size, dashed ideal line, legend.
#include "core/bench/speedup_chart.h"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/bench/bitmap_font.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

const Rgba kWhite{1, 1, 1, 1}, kBlack{0, 0, 0, 1}, kGrey{0.85f, 0.85f, 0.85f, 1}, kIdeal{0.35f, 0.35f, 0.35f, 1};
const Rgba kPalette[] = {{0.12f, 0.47f, 0.71f, 1}, {0.84f, 0.15f, 0.16f, 1}, {0.17f, 0.63f, 0.17f, 1},
                         {1.0f, 0.5f, 0.05f, 1},   {0.58f, 0.40f, 0.74f, 1}, {0.55f, 0.34f, 0.29f, 1}};

void plot(Image& img, int x, int y, const Rgba& c, int thickness) {
  for (int dy = 0; dy < thickness; ++dy)
    for (int dx = 0; dx < thickness; ++dx)
      if (img.rect().contains(x + dx, y + dy)) img.at(x + dx, y + dy) = c;
}

// Walks the segment in half-pixel steps; `dash` > 0 lights `dash` pixels of every 2 * dash.
void drawLine(Image& img, float x0, float y0, float x1, float y1, const Rgba& c, int thickness, int dash = 0,
              float* walked = nullptr) {
  const float length = std::hypot(x1 - x0, y1 - y0);
  const int steps = std::max(1, int(std::ceil(length * 2.0f)));
  float along = walked ? *walked : 0.0f;
  for (int i = 0; i <= steps; ++i) {
    const float t = float(i) / float(steps);
    const float d = along + t * length;
    if (dash > 0 && int(d / float(dash)) % 2 == 1) continue;
    plot(img, int(std::lround(x0 + t * (x1 - x0))), int(std::lround(y0 + t * (y1 - y0))), c, thickness);
  }
  if (walked) *walked = along + length;
}

// A power of two as a tick label: 8, 1, 0.5, 0.25.
std::string powerOfTwoLabel(int exponent) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", std::ldexp(1.0, exponent));
  return buf;
}

}  // namespace

float SpeedupChartLayout::x(double nodes) const {
  return float(left + (std::log2(nodes) - log2NodesLo) / (log2NodesHi - log2NodesLo) * (right - left));
}

float SpeedupChartLayout::y(double speedup) const {
  return float(bottom - (std::log2(speedup) - log2SpeedupLo) / (log2SpeedupHi - log2SpeedupLo) * (bottom - top));
}

SpeedupChartLayout speedupChartLayout(const std::vector<BenchCell>& cells, const std::string& strategy, int width,
                                      int height) {
  if (width < 200 || height < 150) throw Error("speedup chart: size must be at least 200x150");
  int pMin = 1 << 30, pMax = 0;
  double sMin = 1e300, sMax = 0;
  for (const BenchCell& c : cells) {
    if (c.strategy != strategy) continue;
    pMin = std::min(pMin, c.nodes);
    pMax = std::max(pMax, c.nodes);
    if (c.speedup > 0) sMin = std::min(sMin, c.speedup), sMax = std::max(sMax, c.speedup);
  }
  if (pMax == 0) throw Error("speedup chart: no cell for strategy " + strategy);
  SpeedupChartLayout l;
  l.left = 56, l.right = width - 120, l.top = 28, l.bottom = height - 44;
  l.log2NodesLo = std::log2(double(pMin));
  l.log2NodesHi = std::max(l.log2NodesLo + 1.0, std::log2(double(pMax)));
  // The y range holds the ideal line (speedup = P over the measured counts) and every measured
  // speedup, widened to whole powers of two; a speedup below 1 (nodes that cost more than they
  // save) gets its own power of two below the baseline rather than being cut off.
  const double lowest = std::min(double(pMin), sMin), highest = std::max(double(pMax), sMax);
  l.log2SpeedupLo = std::floor(std::log2(lowest) + 1e-9);
  l.log2SpeedupHi = std::max(l.log2SpeedupLo + 1.0, std::ceil(std::log2(highest) - 1e-9));
  return l;
}

Image drawSpeedupChart(const std::vector<BenchCell>& cells, const std::string& strategy, int width, int height) {
  const SpeedupChartLayout l = speedupChartLayout(cells, strategy, width, height);
  std::map<int, std::vector<std::pair<int, double>>> curves;  // size -> (nodes, speedup), nodes ascending
  std::vector<int> ticks;
  for (const BenchCell& c : cells) {
    if (c.strategy != strategy) continue;
    ticks.push_back(c.nodes);
    if (c.speedup > 0) curves[c.width].push_back({c.nodes, c.speedup});
    else curves[c.width];  // keeps the size in the legend
  }
  for (auto& [size, points] : curves) std::sort(points.begin(), points.end());

  Image img(Rect{0, 0, width, height});
  std::fill(img.data(), img.data() + std::size_t(width) * height, kWhite);

  // Grid and ticks: y at powers of two (every one, or every n-th when there are many), x at every
  // measured node count.
  const int yLo = int(l.log2SpeedupLo), yHi = int(l.log2SpeedupHi);
  const int yEvery = std::max(1, (yHi - yLo + 9) / 10);
  for (int k = yLo; k <= yHi; k += yEvery) {
    const float yk = l.y(std::ldexp(1.0, k));
    drawLine(img, float(l.left), yk, float(l.right), yk, k == yLo ? kBlack : kGrey, 1);
    const std::string label = powerOfTwoLabel(k);
    drawText(img, l.left - 6 - textWidth(label), int(yk) - 3, label, kBlack);
  }
  drawLine(img, float(l.left), float(l.bottom), float(l.right), float(l.bottom), kBlack, 1);
  std::sort(ticks.begin(), ticks.end());
  ticks.erase(std::unique(ticks.begin(), ticks.end()), ticks.end());
  for (int p : ticks) {
    drawLine(img, l.x(p), float(l.top), l.x(p), float(l.bottom), kGrey, 1);
    drawLine(img, l.x(p), float(l.bottom), l.x(p), float(l.bottom + 4), kBlack, 1);
    const std::string label = std::to_string(p);
    drawText(img, int(l.x(p)) - textWidth(label) / 2, l.bottom + 8, label, kBlack);
  }
  drawLine(img, float(l.left), float(l.top), float(l.left), float(l.bottom), kBlack, 1);
  drawText(img, (l.left + l.right - textWidth("NODES (LOG2)")) / 2, l.bottom + 22, "NODES (LOG2)", kBlack);
  drawText(img, l.left - 40, 8, "MODELLED SPEEDUP (LOG2) - " + strategy, kBlack);

  // Ideal speedup = P: a straight dashed diagonal on these axes.
  const double pLo = std::exp2(l.log2NodesLo), pHi = std::exp2(l.log2NodesHi);
  float walked = 0.0f;
  drawLine(img, l.x(pLo), l.y(pLo), l.x(pHi), l.y(pHi), kIdeal, 1, 5, &walked);

  int index = 0, legendY = l.top + 4;
  for (const auto& [size, points] : curves) {
    const Rgba& c = kPalette[index++ % 6];
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      drawLine(img, l.x(points[i].first), l.y(points[i].second), l.x(points[i + 1].first), l.y(points[i + 1].second),
               c, 2);
    for (const auto& [p, s] : points) plot(img, int(l.x(p)) - 2, int(l.y(s)) - 2, c, 5);  // a 5x5 marker
    drawLine(img, float(l.right + 12), float(legendY + 3), float(l.right + 32), float(legendY + 3), c, 2);
    drawText(img, l.right + 38, legendY, std::to_string(size) + "X" + std::to_string(size), kBlack);
    legendY += 14;
  }
  drawLine(img, float(l.right + 12), float(legendY + 3), float(l.right + 32), float(legendY + 3), kIdeal, 1, 3);
  drawText(img, l.right + 38, legendY, "IDEAL", kBlack);
  return img;
}

}  // namespace kdswap
