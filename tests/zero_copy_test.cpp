// Zero-copy compositing: lent pixels travel in messages without being copied, stay unchanged
// however the lender composites afterwards, and every way of reading them agrees with a copy.
#include <doctest/doctest.h>

#include <random>

#include "core/comm/message.h"
#include "core/composite/image_message.h"
#include "core/composite/working_image.h"
#include "core/image/image.h"
#include "core/util/error.h"

using namespace kdswap;

namespace {

Image randomImage(const Rect& rect, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  Image image(rect);
  for (int y = rect.y; y < rect.bottom(); ++y)
    for (int x = rect.x; x < rect.right(); ++x) {
      const float a = u(rng);
      image.at(x, y) = Rgba{u(rng) * a, u(rng) * a, u(rng) * a, a};
    }
  return image;
}

bool samePixels(const ImageView& a, const Image& b) {
  if (a.rect != b.rect()) return false;
  for (int y = a.rect.y; y < a.rect.bottom(); ++y)
    for (int x = 0; x < a.rect.w; ++x) {
      const Rgba p = a.row(y)[x], q = b.at(a.rect.x + x, y);
      if (p.r != q.r || p.g != q.g || p.b != q.b || p.a != q.a) return false;
    }
  return true;
}

}  // namespace

TEST_CASE("a lent part of an image arrives as the same pixels as a cropped copy, without a copy") {
  const Image source = randomImage(Rect{3, 5, 40, 30}, 1);
  WorkingImage working{Image(source)};
  const Rect part{10, 8, 17, 12};
  Message m = working.lend(part, /*sparse=*/false);
  CHECK(m.payload.empty());  // nothing was copied into the message
  CHECK(m.loan.count() == part.area() * 4);
  CHECK(m.bytes() == 4 * sizeof(std::int64_t) + std::uint64_t(part.area()) * sizeof(Rgba));
  const ImageView view = viewOfMessage(m);
  CHECK(view.first == &working.image().at(part.x, part.y));  // read where the lender keeps it
  CHECK(samePixels(view, source.crop(part)));
  CHECK(samePixels(imageFromMessage(m).view(), source.crop(part)));
}

TEST_CASE("compositing onto a lent part copies the buffer first, so the reader's pixels never change") {
  const Image source = randomImage(Rect{0, 0, 32, 32}, 2);
  WorkingImage working{Image(source)};
  const Rect left{0, 0, 16, 32}, right{16, 0, 16, 32};
  const Message lentLeft = working.lend(left, false);
  const Image front = randomImage(Rect{0, 0, 32, 32}, 3);
  std::int64_t pixels = 0;
  // Into the kept half: in place, the lent half is untouched.
  working.merge(front.view(right), true, right, pixels);
  CHECK(pixels == right.area());
  CHECK(&working.image().at(0, 0) == viewOfMessage(lentLeft).first);
  // Onto the lent half (no strategy does this, but it must stay safe): copy on write.
  working.merge(front.view(left), true, left, pixels);
  CHECK(&working.image().at(0, 0) != viewOfMessage(lentLeft).first);
  CHECK(samePixels(viewOfMessage(lentLeft), source.crop(left)));
  CHECK(working.image().at(3, 4).a == doctest::Approx(over(front.at(3, 4), source.at(3, 4)).a));
}

TEST_CASE("merging an image that reaches outside ours keeps only the kept region of ours") {
  // Ours covers columns 0..31; the kept half is 16..31; theirs lies in the kept half and below it.
  const Image mine = randomImage(Rect{0, 0, 32, 20}, 4);
  const Image theirs = randomImage(Rect{16, 10, 16, 20}, 5);
  const Rect keep{16, 0, 16, 30};
  for (const bool theirsInFront : {true, false}) {
    CAPTURE(theirsInFront);
    WorkingImage working{Image(mine)};
    const Message lentLeft = working.lend(Rect{0, 0, 16, 20}, false);
    std::int64_t pixels = 0;
    working.merge(theirs.view(), theirsInFront, keep, pixels);
    CHECK(pixels == theirs.rect().area());
    CHECK(working.rect() == (Rect{16, 0, 16, 30}));  // the given-away columns were not copied
    CHECK(samePixels(viewOfMessage(lentLeft), mine.crop(Rect{0, 0, 16, 20})));
    for (int y = keep.y; y < keep.bottom(); ++y)
      for (int x = keep.x; x < keep.right(); ++x) {
        const Rgba m = mine.sample(x, y), t = theirs.sample(x, y);
        const Rgba want = theirsInFront ? over(t, m) : over(m, t);
        const Rgba got = working.image().at(x, y);
        CHECK(got.r == want.r);
        CHECK(got.a == want.a);
      }
  }
}

TEST_CASE("blending layers in place onto one's own pixels equals blending them into a new image") {
  const Rect target{0, 0, 23, 19};
  std::vector<Image> layers;
  for (unsigned i = 0; i < 5; ++i) layers.push_back(randomImage(target, 10 + i));
  for (int self = 0; self < 5; ++self) {
    CAPTURE(self);
    std::vector<ImageView> views;
    for (const Image& layer : layers) views.push_back(layer.view());
    // In place: our own layer is the working image itself.
    WorkingImage inPlace{Image(layers[std::size_t(self)])};
    views[std::size_t(self)] = inPlace.view(target);
    std::int64_t pixels = 0;
    inPlace.composeLayers(target, views, self, pixels);
    CHECK(pixels == 4 * target.area());
    // Reference: front to back, one pair at a time.
    Image expected = layers[0];
    for (std::size_t i = 1; i < layers.size(); ++i) compositeInto(expected, layers[i], /*otherInFront=*/false);
    CHECK(maxAbsDifference(inPlace.image(), expected, target) <= 1e-6f);
    // Sparse layers (smaller than the target) take the new-image path and agree too.
    std::vector<ImageView> sparse;
    for (const Image& layer : layers) sparse.push_back(layer.view(Rect{2, 3, 15, 11}));
    WorkingImage fresh;
    fresh.composeLayers(target, sparse, -1, pixels);
    Image expectedSparse(target);
    for (const ImageView& v : sparse) compositeInto(expectedSparse, v, false);
    CHECK(maxAbsDifference(fresh.image(), expectedSparse, target) <= 1e-6f);
  }
}

TEST_CASE("flattening a message copies its loan into the payload and keeps its checksum") {
  const Image source = randomImage(Rect{0, 0, 9, 7}, 4);
  WorkingImage working{Image(source)};
  Message m = working.lend(Rect{2, 1, 5, 4}, false);
  m.tag = 42;
  const std::uint64_t before = messageChecksum(m);
  m.flatten();
  CHECK(m.loan.count() == 0);
  CHECK(m.payload.size() == std::size_t(5 * 4 * 4));
  CHECK(messageChecksum(m) == before);
  CHECK(samePixels(viewOfMessage(m), source.crop(Rect{2, 1, 5, 4})));
  m.payload[7] += 0.25f;
  CHECK(messageChecksum(m) != before);
}

TEST_CASE("a sparse lend carries only the bounding rectangle of the non-empty pixels") {
  Image source(Rect{0, 0, 20, 20});
  source.at(5, 6) = Rgba{0.1f, 0.1f, 0.1f, 0.5f};
  source.at(9, 12) = Rgba{0.2f, 0.0f, 0.0f, 0.25f};
  WorkingImage working{std::move(source)};
  const Message m = working.lend(Rect{0, 0, 20, 20}, /*sparse=*/true);
  CHECK(viewOfMessage(m).rect == Rect{5, 6, 5, 7});
  const Message none = working.lend(Rect{12, 0, 8, 20}, true);
  CHECK(viewOfMessage(none).empty());
  CHECK(none.bytes() == 4 * sizeof(std::int64_t));
}

TEST_CASE("a message whose lent pixels do not match its rectangle is refused") {
  const Image source = randomImage(Rect{0, 0, 8, 8}, 5);
  WorkingImage working{Image(source)};
  Message m = working.lend(Rect{0, 0, 4, 4}, false);
  m.header[2] = 5;  // claims a wider rectangle than was lent
  CHECK_THROWS_AS(viewOfMessage(m), Error);
  m.header[2] = -3;
  CHECK_THROWS_AS(viewOfMessage(m), Error);
}

TEST_CASE("a finished tile shares the working buffer and outlives the working image") {
  const Image source = randomImage(Rect{0, 0, 16, 16}, 6);
  WorkingImage working{Image(source)};
  const Rgba* where = &working.image().at(8, 0);
  Tile tile = working.finish(Rect{8, 0, 8, 16});
  CHECK(working.empty());
  CHECK(tile.pixels.first == where);
  CHECK(samePixels(tile.pixels, source.crop(Rect{8, 0, 8, 16})));
  const Tile owned = Tile::owning(Rect{0, 0, 4, 4}, source.crop(Rect{0, 0, 10, 10}));
  CHECK(owned.pixels.rect == Rect{0, 0, 4, 4});
}
