// Drawing the compositing stages (Figure 6 of Ma et al. 1993).
#include "core/cluster/phase_grid.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <span>

#include "core/image/image_io.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

const Rgba kBackground{0.08f, 0.08f, 0.10f, 1.0f};
const Rgba kOutline{1.0f, 0.8f, 0.1f, 1.0f};
const Rgba kGap{0.0f, 0.0f, 0.0f, 1.0f};

Rgba onBackground(const Rgba& p, float dim) {
  const float t = 1.0f - p.a;
  return Rgba{(p.r + t * kBackground.r) * dim, (p.g + t * kBackground.g) * dim, (p.b + t * kBackground.b) * dim, 1.0f};
}

bool onOutline(const Rect& r, int x, int y) {
  return r.contains(x, y) && (x == r.x || y == r.y || x == r.right() - 1 || y == r.bottom() - 1);
}

// Paints `image` (frame-sized, any rect) into `out` at (ox, oy) scaled by `scale` (<= 1), nearest.
void paintScaled(Image& out, int ox, int oy, const Rect& frame, float scale, const std::function<Rgba(int, int)>& pixel) {
  const int w = std::max(1, int(frame.w * scale)), h = std::max(1, int(frame.h * scale));
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const int fx = std::min(frame.w - 1, int((x + 0.5f) / scale)), fy = std::min(frame.h - 1, int((y + 0.5f) / scale));
      if (out.rect().contains(ox + x, oy + y)) out.at(ox + x, oy + y) = pixel(fx, fy);
    }
}

}  // namespace

Image drawPhaseCell(const PhaseCell& cell, const Rect& frame) {
  Image out(frame);
  for (int y = frame.y; y < frame.bottom(); ++y)
    for (int x = frame.x; x < frame.right(); ++x)
      out.at(x, y) = onOutline(cell.region, x, y) ? kOutline
                                                  : onBackground(cell.image.sample(x, y), cell.region.contains(x, y) ? 1.0f : 0.35f);
  return out;
}

Image drawPhaseGrid(const PhaseRecord& record, const Image& finalImage, int maxWidth) {
  const Rect& frame = record.frame;
  const int columns = int(record.cells.size()), rows = record.phaseCount();
  const int gap = 2;
  float scale = std::min(1.0f, float(maxWidth - gap * (columns + 1)) / float(std::max(1, columns * frame.w)));
  scale = std::max(scale, 1.0f / float(std::max(frame.w, frame.h)));
  const int cellW = std::max(1, int(frame.w * scale)), cellH = std::max(1, int(frame.h * scale));
  const int gridW = gap + columns * (cellW + gap);
  const float finalScale = std::min(1.0f, float(std::max(gridW - 2 * gap, 1)) / float(frame.w));
  const int finalW = std::max(1, int(frame.w * finalScale)), finalH = std::max(1, int(frame.h * finalScale));
  const int width = std::max(gridW, finalW + 2 * gap);
  const int height = gap + rows * (cellH + gap) + finalH + gap;
  Image out(Rect{0, 0, width, height});
  for (Rgba& p : std::span<Rgba>(out.data(), std::size_t(out.rect().area()))) p = kGap;
  for (int c = 0; c < columns; ++c)
    for (int r = 0; r < rows && r < int(record.cells[std::size_t(c)].size()); ++r) {
      const PhaseCell& cell = record.cells[std::size_t(c)][std::size_t(r)];
      // Outline drawn in cell pixels so it stays visible however small the cell is.
      const Rect scaled{int(cell.region.x * scale), int(cell.region.y * scale), std::max(1, int(cell.region.w * scale)),
                        std::max(1, int(cell.region.h * scale))};
      const bool hasRegion = !cell.region.empty();
      const int ox = gap + c * (cellW + gap), oy = gap + r * (cellH + gap);
      paintScaled(out, ox, oy, frame, scale, [&](int fx, int fy) {
        return onBackground(cell.image.sample(fx, fy), cell.region.contains(fx, fy) ? 1.0f : 0.35f);
      });
      if (hasRegion)
        for (int y = scaled.y; y < scaled.bottom(); ++y)
          for (int x = scaled.x; x < scaled.right(); ++x)
            if (onOutline(scaled, x, y) && out.rect().contains(ox + x, oy + y)) out.at(ox + x, oy + y) = kOutline;
    }
  const int fy0 = gap + rows * (cellH + gap), fx0 = (width - finalW) / 2;
  paintScaled(out, fx0, fy0, frame, finalScale, [&](int fx, int fy) { return onBackground(finalImage.sample(fx, fy), 1.0f); });
  return out;
}

void writePhaseCells(const std::string& dir, const PhaseRecord& record, const Image& finalImage) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw Error(dir + ": cannot create directory: " + ec.message());
  for (std::size_t n = 0; n < record.cells.size(); ++n)
    for (std::size_t p = 0; p < record.cells[n].size(); ++p) {
      const PhaseCell& cell = record.cells[n][p];
      const std::string name = "node" + std::to_string(n) + "_phase" + std::to_string(p) + "_" + cell.label + ".png";
      writeImage((std::filesystem::path(dir) / name).string(), drawPhaseCell(cell, record.frame));
    }
  writeImage((std::filesystem::path(dir) / "final.png").string(), finalImage);
}

}  // namespace kdswap
