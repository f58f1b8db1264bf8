// The waves' dependency graph at screen-cell granularity: pieces cut each brick's rectangle
// exactly, every pixel's pieces are ordered nearest first through the graph, and a piece waits
// only for nearer pieces it shares a pixel with. Checked pixel by pixel on random rectangles.
#include <doctest/doctest.h>

#include <random>

#include "core/cluster/screen_piece_graph.h"
#include "core/util/error.h"

using namespace kdswap;

namespace {

//! True when piece `to` can be reached from piece `from` along dependency edges.
bool reaches(const ScreenPieceGraph& graph, std::size_t from, std::size_t to) {
  std::vector<bool> seen(graph.pieces().size(), false);
  std::vector<std::size_t> stack{from};
  while (!stack.empty()) {
    const std::size_t p = stack.back();
    stack.pop_back();
    if (p == to) return true;
    for (const std::size_t* q = graph.dependentsBegin(p); q != graph.dependentsEnd(p); ++q)
      if (!seen[*q]) seen[*q] = true, stack.push_back(*q);
  }
  return false;
}

Rect randomRect(std::mt19937& rng, const Rect& frame) {
  // Some rectangles reach past the frame, some are empty.
  std::uniform_int_distribution<int> x(frame.x - 10, frame.right() + 5), y(frame.y - 10, frame.bottom() + 5);
  std::uniform_int_distribution<int> size(-3, 40);
  return Rect{x(rng), y(rng), size(rng), size(rng)};
}

}  // namespace

TEST_CASE("screen piece graph: pieces cut each brick's rectangle exactly and a pixel's pieces follow each other nearest first") {
  std::mt19937 rng(91);
  for (int trial = 0; trial < 40; ++trial) {
    const Rect frame{trial % 3, trial % 5, 20 + int(rng() % 60), 15 + int(rng() % 50)};
    const int cell = 1 + int(rng() % 24);
    std::vector<Rect> rects(1 + rng() % 12);
    for (Rect& r : rects) r = randomRect(rng, frame);
    const ScreenPieceGraph graph(rects, frame, cell);
    const auto& pieces = graph.pieces();
    const std::string what = "trial " + std::to_string(trial) + " cell " + std::to_string(cell);

    // Each brick's pieces cover its rectangle within the frame once; pieces lie in one cell.
    std::vector<int> count(rects.size(), 0);
    for (const ScreenPiece& piece : pieces) {
      REQUIRE(piece.brick < rects.size());
      ++count[piece.brick];
      CHECK_MESSAGE(!piece.rect.empty(), what);
      CHECK_MESSAGE(rects[piece.brick].intersect(frame).contains(piece.rect), what);
      CHECK_MESSAGE((piece.rect.x - frame.x) / cell == (piece.rect.right() - 1 - frame.x) / cell, what);
      CHECK_MESSAGE((piece.rect.y - frame.y) / cell == (piece.rect.bottom() - 1 - frame.y) / cell, what);
    }
    for (std::size_t i = 0; i < rects.size(); ++i) {
      CHECK_MESSAGE(graph.piecesOf(i) == count[i], what);
      if (rects[i].intersect(frame).empty()) CHECK_MESSAGE(count[i] == 0, what);
    }
    for (int y = frame.y; y < frame.bottom(); ++y)
      for (int x = frame.x; x < frame.right(); ++x) {
        std::vector<std::size_t> here;  // the pieces holding this pixel
        for (std::size_t p = 0; p < pieces.size(); ++p)
          if (pieces[p].rect.contains(x, y)) here.push_back(p);
        std::vector<int> perBrick(rects.size(), 0);
        for (std::size_t p : here) ++perBrick[pieces[p].brick];
        for (std::size_t i = 0; i < rects.size(); ++i)
          CHECK_MESSAGE(perBrick[i] == int(rects[i].contains(x, y)), what << " pixel " << x << "," << y);
        // Nearest first: each piece here runs after the one of the next nearer brick here.
        std::sort(here.begin(), here.end(), [&](std::size_t a, std::size_t b) { return pieces[a].brick < pieces[b].brick; });
        for (std::size_t k = 1; k < here.size(); ++k)
          CHECK_MESSAGE(reaches(graph, here[k - 1], here[k]), what << " pixel " << x << "," << y);
      }

    // A piece waits only for nearer pieces it shares a pixel with, each once; the counts agree.
    std::vector<int> waits(pieces.size(), 0);
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      std::vector<bool> once(pieces.size(), false);
      for (const std::size_t* q = graph.dependentsBegin(p); q != graph.dependentsEnd(p); ++q) {
        REQUIRE(*q < pieces.size());
        CHECK_MESSAGE(pieces[*q].brick > pieces[p].brick, what);
        CHECK_MESSAGE(!pieces[*q].rect.intersect(pieces[p].rect).empty(), what);
        CHECK_MESSAGE(!once[*q], what);
        once[*q] = true;
        ++waits[*q];
      }
    }
    std::size_t readyCount = 0;
    for (std::size_t p = 0; p < pieces.size(); ++p) {
      CHECK_MESSAGE(graph.waitsFor(p) == waits[p], what);
      readyCount += waits[p] == 0;
    }
    const std::vector<std::size_t> ready = graph.ready();
    CHECK(ready.size() == readyCount);
    for (std::size_t p : ready) CHECK(graph.waitsFor(p) == 0);
  }
}

TEST_CASE("screen piece graph: a brick behind another waits only in the cells they share") {
  // Two bricks overlapping in the right half of the first one's rectangle, cells of 8 pixels.
  const Rect frame{0, 0, 32, 8};
  const ScreenPieceGraph graph({Rect{0, 0, 32, 8}, Rect{16, 0, 16, 8}}, frame, 8);
  REQUIRE(graph.pieces().size() == 6u);
  CHECK(graph.piecesOf(0) == 4);
  CHECK(graph.piecesOf(1) == 2);
  CHECK(graph.ready().size() == 4u);  // the front brick's four cells
  for (std::size_t p = 4; p < 6; ++p) CHECK(graph.waitsFor(p) == 1);
  CHECK(graph.dependentsEnd(0) == graph.dependentsBegin(0));  // cells 0 and 1 hold no pixel of brick 1
  CHECK(graph.dependentsEnd(1) == graph.dependentsBegin(1));
  CHECK_THROWS_AS(ScreenPieceGraph({Rect{0, 0, 4, 4}}, frame, 0), Error);
}
