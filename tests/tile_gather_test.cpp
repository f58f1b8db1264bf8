// The host's gather: the final frame holds each node's tile pixels where the tile has them and is
// transparent in the rest of its region (sparse or empty tiles); tiles that leave pixels out,
// overlap, or carry pixels outside their region are refused with the node named.
#include <doctest/doctest.h>

#include <memory>

#include "core/cluster/host.h"
#include "core/composite/image_message.h"
#include "core/image/image.h"
#include "core/util/error.h"

using namespace kdswap;

namespace {

Rgba valueAt(int x, int y) { return Rgba{float(x), float(y), 0.25f, 0.5f}; }

//! A tile message as a node sends it: the pixels of `own` lent (the loan keeps them alive), then
//! the region.
Message tileMessage(int node, const Rect& region, const Rect& own) {
  auto image = std::make_shared<Image>(own);
  for (int y = own.y; y < own.bottom(); ++y)
    for (int x = own.x; x < own.right(); ++x) image->at(x, y) = valueAt(x, y);
  Message m = lendPixels(image->view(), image);
  m.header.insert(m.header.end(), {region.x, region.y, region.w, region.h});
  m.source = node;
  return m;
}

}  // namespace

TEST_CASE("the gathered frame holds each tile's pixels and is transparent in the rest of its region") {
  const Rect frame{0, 0, 600, 400};
  for (int round = 0; round < 2; ++round) {
    CAPTURE(round);
    {
      // Pooled storage full of non-zero values, which the gather's frame may be built on.
      Image dirty(frame);
      for (int y = 0; y < frame.h; ++y)
        for (int x = 0; x < frame.w; ++x) dirty.at(x, y) = Rgba{9, 9, 9, 9};
    }
    // Four regions partitioning the frame; their images: the whole region, a part in the middle,
    // a part touching one corner, nothing at all.
    const Rect regions[4] = {{0, 0, 300, 200}, {300, 0, 300, 200}, {0, 200, 300, 200}, {300, 200, 300, 200}};
    const Rect owns[4] = {regions[0], {350, 40, 100, 70}, {0, 330, 45, 70}, {}};
    std::vector<Message> tiles;
    for (int i = 0; i < 4; ++i) tiles.push_back(tileMessage(i, regions[i], owns[i]));
    std::vector<Rect> gotRegions;
    const Image out = assembleTiles(tiles, frame, &gotRegions);
    REQUIRE(out.rect() == frame);
    for (int i = 0; i < 4; ++i) CHECK(gotRegions[std::size_t(i)] == regions[i]);
    int wrong = 0;
    for (int y = 0; y < frame.h; ++y)
      for (int x = 0; x < frame.w; ++x) {
        bool inImage = false;
        for (const Rect& own : owns) inImage = inImage || own.contains(x, y);
        const Rgba expected = inImage ? valueAt(x, y) : Rgba{};
        const Rgba& got = out.at(x, y);
        wrong += got.r != expected.r || got.g != expected.g || got.b != expected.b || got.a != expected.a;
      }
    CHECK(wrong == 0);
  }
}

TEST_CASE("a gather whose tiles leave pixels out, overlap or reach outside their regions is refused") {
  const Rect frame{0, 0, 64, 64};
  std::vector<Message> gap;
  gap.push_back(tileMessage(0, {0, 0, 64, 32}, {0, 0, 64, 32}));
  gap.push_back(tileMessage(1, {0, 32, 64, 31}, {}));
  CHECK_THROWS_WITH_AS(assembleTiles(gap, frame), "gather: tiles cover 4032 of 4096 pixels", Error);

  std::vector<Message> overlap;
  overlap.push_back(tileMessage(0, {0, 0, 64, 33}, {}));
  overlap.push_back(tileMessage(1, {0, 32, 64, 32}, {}));
  CHECK_THROWS_WITH_AS(assembleTiles(overlap, frame), "tile from node 1: pixel (0, 32) also belongs to another tile",
                       Error);

  std::vector<Message> outside;
  outside.push_back(tileMessage(0, {0, 0, 64, 32}, {0, 0, 64, 40}));  // pixels below its region
  outside.push_back(tileMessage(1, {0, 32, 64, 32}, {}));
  CHECK_THROWS_WITH_AS(assembleTiles(outside, frame), "tile from node 0: image lies outside its region or the frame",
                       Error);

  std::vector<Message> malformed;
  malformed.push_back(tileMessage(3, frame, frame));
  malformed.back().header.pop_back();
  CHECK_THROWS_WITH_AS(assembleTiles(malformed, frame), "tile from node 3: malformed header", Error);
}
