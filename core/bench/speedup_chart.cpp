// Speedup chart: axes, ticks, one polyline per image size, dashed ideal line, legend.
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

// A round upper bound for the y axis: 1, 2 or 5 times a power of ten.
double niceCeiling(double v) {
  if (v <= 1.0) return 1.0;
  const double p = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= v) return m * p;
  return 10.0 * p;
}

std::string formatTick(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, v == std::floor(v) ? "%.0f" : "%.1f", v);
  return buf;
}

}  // namespace

Image drawSpeedupChart(const std::vector<BenchCell>& cells, const std::string& strategy, int width, int height) {
  if (width < 200 || height < 150) throw Error("speedup chart: size must be at least 200x150");
  std::map<int, std::vector<std::pair<int, double>>> curves;  // size -> (nodes, speedup), nodes ascending
  int pMin = 1 << 30, pMax = 0;
  double yMax = 1.0;
  for (const BenchCell& c : cells) {
    if (c.strategy != strategy) continue;
    curves[c.width].push_back({c.nodes, c.speedup});
    pMin = std::min(pMin, c.nodes);
    pMax = std::max(pMax, c.nodes);
    yMax = std::max(yMax, c.speedup);
  }
  if (curves.empty()) throw Error("speedup chart: no cell for strategy " + strategy);
  for (auto& [size, points] : curves) std::sort(points.begin(), points.end());
  yMax = niceCeiling(std::max(yMax, double(pMax)) * 1.02);

  Image img(Rect{0, 0, width, height});
  std::fill(img.data(), img.data() + std::size_t(width) * height, kWhite);
  const int left = 56, right = width - 120, top = 28, bottom = height - 44;
  const double lo = std::log2(double(pMin)), hi = std::max(lo + 1.0, std::log2(double(pMax)));
  auto sx = [&](double p) { return float(left + (std::log2(p) - lo) / (hi - lo) * (right - left)); };
  auto sy = [&](double s) { return float(bottom - s / yMax * (bottom - top)); };

  // Grid and ticks: y in five steps, x at every measured node count.
  for (int i = 0; i <= 5; ++i) {
    const double v = yMax * i / 5.0;
    drawLine(img, float(left), sy(v), float(right), sy(v), i == 0 ? kBlack : kGrey, 1);
    const std::string label = formatTick(v);
    drawText(img, left - 6 - textWidth(label), int(sy(v)) - 3, label, kBlack);
  }
  std::vector<int> ticks;
  for (const auto& [size, points] : curves)
    for (const auto& [p, s] : points) ticks.push_back(p);
  std::sort(ticks.begin(), ticks.end());
  ticks.erase(std::unique(ticks.begin(), ticks.end()), ticks.end());
  for (int p : ticks) {
    drawLine(img, sx(p), float(top), sx(p), float(bottom), kGrey, 1);
    drawLine(img, sx(p), float(bottom), sx(p), float(bottom + 4), kBlack, 1);
    const std::string label = std::to_string(p);
    drawText(img, int(sx(p)) - textWidth(label) / 2, bottom + 8, label, kBlack);
  }
  drawLine(img, float(left), float(top), float(left), float(bottom), kBlack, 1);
  drawText(img, (left + right - textWidth("NODES (LOG2)")) / 2, bottom + 22, "NODES (LOG2)", kBlack);
  drawText(img, left - 40, 8, "MODELLED SPEEDUP - " + strategy, kBlack);

  // Ideal speedup = P, dashed, sampled finely because it is curved on a log2 x axis.
  float walked = 0.0f;
  const int samples = 128;
  for (int i = 0; i < samples; ++i) {
    const double p0 = std::exp2(lo + (hi - lo) * i / samples), p1 = std::exp2(lo + (hi - lo) * (i + 1) / samples);
    drawLine(img, sx(p0), sy(p0), sx(p1), sy(p1), kIdeal, 1, 5, &walked);
  }

  int index = 0, legendY = top + 4;
  for (const auto& [size, points] : curves) {
    const Rgba& c = kPalette[index++ % 6];
    for (std::size_t i = 0; i + 1 < points.size(); ++i)
      drawLine(img, sx(points[i].first), sy(points[i].second), sx(points[i + 1].first), sy(points[i + 1].second), c, 2);
    for (const auto& [p, s] : points) plot(img, int(sx(p)) - 2, int(sy(s)) - 2, c, 5);  // a 5x5 marker
    drawLine(img, float(right + 12), float(legendY + 3), float(right + 32), float(legendY + 3), c, 2);
    drawText(img, right + 38, legendY, std::to_string(size) + "X" + std::to_string(size), kBlack);
    legendY += 14;
  }
  drawLine(img, float(right + 12), float(legendY + 3), float(right + 32), float(legendY + 3), kIdeal, 1, 3);
  drawText(img, right + 38, legendY, "IDEAL", kBlack);
  return img;
}

}  // namespace kdswap
