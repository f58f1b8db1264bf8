// Pieces are made cell by cell; within a cell the bricks come nearest first, so each new piece is
// compared with the cell's earlier pieces only (k^2 / 2 rectangle tests for k bricks in a cell).
#include "core/cluster/screen_piece_graph.h"

#include <algorithm>
#include <utility>

#include "core/util/error.h"

namespace kdswap {

ScreenPieceGraph::ScreenPieceGraph(const std::vector<Rect>& rects, const Rect& frame, int cell)
    : piecesPerBrick_(rects.size(), 0) {
  if (cell <= 0) throw Error("screen piece grid: the cell size must be positive");
  const int columns = std::max(1, (frame.w + cell - 1) / cell), rows = std::max(1, (frame.h + cell - 1) / cell);
  // inCell[c]: the pieces of cell c so far, nearest brick first.
  std::vector<std::vector<std::size_t>> inCell(std::size_t(columns) * std::size_t(rows));
  std::vector<std::pair<std::size_t, std::size_t>> edges;  // (before, after)
  for (std::size_t i = 0; i < rects.size(); ++i) {
    const Rect r = rects[i].intersect(frame);
    if (r.empty()) continue;
    const int c0 = (r.x - frame.x) / cell, c1 = (r.right() - 1 - frame.x) / cell;
    const int r0 = (r.y - frame.y) / cell, r1 = (r.bottom() - 1 - frame.y) / cell;
    for (int row = r0; row <= r1; ++row)
      for (int column = c0; column <= c1; ++column) {
        const Rect cellRect{frame.x + column * cell, frame.y + row * cell, cell, cell};
        const std::size_t p = pieces_.size();
        pieces_.push_back(ScreenPiece{i, r.intersect(cellRect)});
        ++piecesPerBrick_[i];
        std::vector<std::size_t>& earlier = inCell[std::size_t(row) * std::size_t(columns) + std::size_t(column)];
        for (std::size_t q : earlier)
          if (!pieces_[q].rect.intersect(pieces_[p].rect).empty()) edges.emplace_back(q, p);
        earlier.push_back(p);
      }
  }
  // Compressed rows: the dependents of each piece, contiguous.
  offsets_.assign(pieces_.size() + 1, 0);
  waitsFor_.assign(pieces_.size(), 0);
  for (const auto& [before, after] : edges) ++offsets_[before + 1], ++waitsFor_[after];
  for (std::size_t p = 0; p < pieces_.size(); ++p) offsets_[p + 1] += offsets_[p];
  dependents_.resize(edges.size());
  std::vector<std::size_t> filled(offsets_.begin(), offsets_.end() - 1);
  for (const auto& [before, after] : edges) dependents_[filled[before]++] = after;
}

std::vector<std::size_t> ScreenPieceGraph::ready() const {
  std::vector<std::size_t> out;
  for (std::size_t p = 0; p < pieces_.size(); ++p)
    if (waitsFor_[p] == 0) out.push_back(p);
  return out;
}

}  // namespace kdswap
