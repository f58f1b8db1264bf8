// The dependency graph of front-to-back waves at screen-cell granularity: each brick's screen
// rectangle is cut by one grid of square cells over the frame into pieces, and a piece waits only
// for the pieces in front (nearer bricks, same cell) that share a pixel with it. A brick's cell
// then starts as soon as the cells in front of that cell are done, not after whole bricks in
// front whose rectangles merely touch its own elsewhere. Every pixel is still rendered by its
// bricks nearest first, so the light each brick reads there is the same product every frame.
#pragma once

#include <cstddef>
#include <vector>

#include "core/image/rect.h"

namespace kdswap {

struct ScreenPiece {
  std::size_t brick;  //!< position of its brick in the front-to-back order
  Rect rect;          //!< the brick's rectangle within one cell of the grid
};

class ScreenPieceGraph {
 public:
  //! `rects[i]`: the screen rectangle of the i-th brick, nearest first (empty: no pieces);
  //! `cell`: the grid's cell size in pixels, the grid anchored at `frame`'s corner.
  ScreenPieceGraph(const std::vector<Rect>& rects, const Rect& frame, int cell);

  const std::vector<ScreenPiece>& pieces() const { return pieces_; }
  //! The pieces that wait for piece `p` (each once).
  const std::size_t* dependentsBegin(std::size_t p) const { return dependents_.data() + offsets_[p]; }
  const std::size_t* dependentsEnd(std::size_t p) const { return dependents_.data() + offsets_[p + 1]; }
  //! How many pieces piece `p` waits for.
  int waitsFor(std::size_t p) const { return waitsFor_[p]; }
  //! The pieces that wait for none, in the order of `pieces()`.
  std::vector<std::size_t> ready() const;
  //! How many pieces brick `i` was cut into.
  int piecesOf(std::size_t brick) const { return piecesPerBrick_[brick]; }

 private:
  std::vector<ScreenPiece> pieces_;
  std::vector<std::size_t> offsets_, dependents_;  // dependents of p: [offsets_[p], offsets_[p + 1])
  std::vector<int> waitsFor_, piecesPerBrick_;
};

}  // namespace kdswap
