// CellCoverage: for one view, the pixels of a brick's screen rectangle whose rays can meet one of
// its visible cells (EmptySpaceMap). A ray that crosses only invisible cells takes no sample there,
// so its pixel stays clear and needs no ray at all. Such rays were a large share of those set up
// per brick: at P = 64 a fifth of the CT head's and two fifths of the phantom's with waves, and
// over a third at P = 1, each paying its set-up, its queueing and the march's hops through the
// empty cells before it found nothing.
//
// The covered pixels are the union of the visible cells' projected rectangles, each with
// Camera::projectBox's pixel of slack: a ray through a pixel centre that meets a cell's box
// projects into the cell's projected hull, so skipping the others changes no image bit and no
// sample count. Bricks with many cells are covered by groups of cells (CellGroups: a group counts
// as visible when any of its cells is), so building the coverage stays a few microseconds per brick.
#pragma once

#include <cstdint>
#include <vector>

#include "core/camera/camera.h"
#include "core/image/rect.h"
#include "core/render/empty_space_map.h"
#include "core/volume/brick.h"

namespace kdswap {

class CellCoverage {
 public:
  //! Bricks with more than this share of their groups visible cover every pixel, unbuilt.
  static constexpr std::size_t kDenseNumerator = 3, kDenseDenominator = 4;

  //! Covers every pixel: nothing is skipped.
  CellCoverage() = default;
  //! The pixels of `rect` (the brick's screen rectangle) through which `camera`'s rays can reach
  //! the brick's visible cells (under `emptySpace`, the brick's map).
  CellCoverage(const Brick& brick, const EmptySpaceMap& emptySpace, const Camera& camera, const Rect& rect);

  //! Bit j (j < 8): pixel (x + j, y) may meet a visible cell. Pixels outside the rectangle meet none.
  int eight(int x, int y) const {
    if (all_) return 0xFF;
    const int bit = x - rect_.x;
    if (y < rect_.y || y >= rect_.bottom() || bit < 0 || bit >= rect_.w) return eightSlowly(x, y);
    const std::uint64_t* row = bits_.data() + std::size_t(y - rect_.y) * std::size_t(wordsPerRow_);
    const int word = bit >> 6, offset = bit & 63;
    std::uint64_t v = row[word] >> offset;
    if (offset > 56) v |= row[word + 1] << (64 - offset);  // each row ends with a spare zero word
    return int(v & 0xFF);
  }
  //! Whether every pixel counts as covered (no map, or nothing to skip).
  bool coversAll() const { return all_; }
  //! Covered pixels of the rectangle (for tests and statistics).
  std::int64_t coveredPixels() const;

 private:
  int eightSlowly(int x, int y) const;
  void coverAll();
  //! Marks the pixels of `r` (within the rectangle).
  void cover(const Rect& r);

  bool all_ = true;
  Rect rect_;
  int wordsPerRow_ = 0;  //!< 64-bit words per row, one spare included
  std::vector<std::uint64_t> bits_;
};

}  // namespace kdswap
