// Float premultiplied images to opaque 8-bit pixels, downscaled by box filtering.
#include "ui/frame_pixels.h"

#include <algorithm>
#include <cmath>

namespace kdswap {
namespace {

constexpr float kDimOutsideRegion = 0.35f;  // as core's phase grid
constexpr int kMaxTapsPerAxis = 4;          // box filter taps; enough to avoid sparkle at 1/8 scale

std::uint8_t toByte(float v) { return std::uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f)); }

// Writes the picture of `frame` into dst (row stride `stride` pixels) at w x h, dimming pixels
// whose source lies outside `bright` (when not empty).
void paint(const Image& image, const Rect& frame, const Rect* bright, int w, int h, std::uint8_t* dst, int stride) {
  const float sx = float(frame.w) / float(w), sy = float(frame.h) / float(h);
  const int tx = std::clamp(int(std::ceil(sx)), 1, kMaxTapsPerAxis), ty = std::clamp(int(std::ceil(sy)), 1, kMaxTapsPerAxis);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      float r = 0, g = 0, b = 0;
      for (int j = 0; j < ty; ++j)
        for (int i = 0; i < tx; ++i) {
          const int fx = frame.x + std::min(frame.w - 1, int((float(x) + (float(i) + 0.5f) / float(tx)) * sx));
          const int fy = frame.y + std::min(frame.h - 1, int((float(y) + (float(j) + 0.5f) / float(ty)) * sy));
          const Rgba p = image.sample(fx, fy);
          const float t = 1.0f - p.a;
          const float dim = bright && !bright->contains(fx, fy) ? kDimOutsideRegion : 1.0f;
          r += dim * (p.r + t * kImageBackground[0]);
          g += dim * (p.g + t * kImageBackground[1]);
          b += dim * (p.b + t * kImageBackground[2]);
        }
      const float n = 1.0f / float(tx * ty);
      std::uint8_t* out = dst + (std::size_t(y) * stride + x) * 4;
      out[0] = toByte(r * n), out[1] = toByte(g * n), out[2] = toByte(b * n), out[3] = 255;
    }
}

void fitInside(const Rect& frame, int maxSide, int& w, int& h) {
  const float scale = std::min(1.0f, float(maxSide) / float(std::max(frame.w, frame.h)));
  w = std::max(1, int(std::lround(frame.w * scale)));
  h = std::max(1, int(std::lround(frame.h * scale)));
}

}  // namespace

Pixels toPixels(const Image& image, const Rect& frame, int maxSide) {
  Pixels out;
  if (frame.empty()) return out;
  fitInside(frame, maxSide, out.width, out.height);
  out.rgba.resize(std::size_t(out.width) * out.height * 4);
  paint(image, frame, nullptr, out.width, out.height, out.rgba.data(), out.width);
  return out;
}

StageAtlas buildStageAtlas(const PhaseRecord& record, int maxCellSide, int maxAtlasWidth) {
  StageAtlas atlas;
  atlas.columns = int(record.cells.size());
  atlas.rows = record.phaseCount();
  if (atlas.columns == 0 || atlas.rows == 0 || record.frame.empty()) return atlas;
  const int side = std::clamp(maxAtlasWidth / atlas.columns, 4, maxCellSide);
  fitInside(record.frame, side, atlas.cellWidth, atlas.cellHeight);
  Pixels& px = atlas.pixels;
  px.width = atlas.columns * atlas.cellWidth;
  px.height = atlas.rows * atlas.cellHeight;
  px.rgba.assign(std::size_t(px.width) * px.height * 4, 0);
  for (int node = 0; node < atlas.columns; ++node)
    for (int phase = 0; phase < atlas.rows && phase < int(record.cells[std::size_t(node)].size()); ++phase) {
      const PhaseCell& cell = record.cells[std::size_t(node)][std::size_t(phase)];
      std::uint8_t* origin = px.rgba.data() + (std::size_t(phase * atlas.cellHeight) * px.width + node * atlas.cellWidth) * 4;
      paint(cell.image, record.frame, &cell.region, atlas.cellWidth, atlas.cellHeight, origin, px.width);
    }
  return atlas;
}

}  // namespace kdswap
