// The pixel pool hands large buffers back for reuse (already mapped, no page faults), never a
// buffer far too big, and keeps nothing small; images draw on it transparently.
#include <doctest/doctest.h>

#include "core/image/image.h"
#include "core/image/pixel_pool.h"

using namespace kdswap;

TEST_CASE("a large pixel buffer given back is handed out again for a similar size, a small one is not kept") {
#if defined(KDSWAP_SANITIZED)
  MESSAGE("sanitizer build: pooling is off so that a use after free is still caught");
  std::vector<float> big = pixel_pool::take(1 << 20);
  CHECK(big.capacity() >= std::size_t(1) << 20);
#else
  const std::size_t n = (std::size_t(1) << 20) + 12345;  // a size no other buffer here has
  std::vector<float> big = pixel_pool::take(n);
  big.resize(n, 1.0f);
  const float* storage = big.data();
  const std::size_t before = pixel_pool::pooledBytes();
  pixel_pool::give(big);
  CHECK(big.empty());
  CHECK(pixel_pool::pooledBytes() == before + n * sizeof(float));
  // Far smaller requests do not get it (it would waste memory); a close one does, empty.
  std::vector<float> small = pixel_pool::take(1000);
  CHECK(small.data() != storage);
  std::vector<float> again = pixel_pool::take(n - 100);
  CHECK(again.data() == storage);
  CHECK(again.empty());
  CHECK(again.capacity() >= n);
  CHECK(pixel_pool::pooledBytes() == before);
  // Small buffers are simply freed.
  small.resize(1000);
  pixel_pool::give(small);
  CHECK(pixel_pool::pooledBytes() == before);
  pixel_pool::give(again);
#endif
}

TEST_CASE("images built on pooled storage start transparent and copy exactly") {
  const Rect r{0, 0, 512, 512};
  {
    Image dirty(r);
    for (int y = 0; y < r.h; ++y)
      for (int x = 0; x < r.w; ++x) dirty.at(x, y) = Rgba{1, 2, 3, 4};
  }  // its storage goes back to the pool
  Image fresh(r);  // likely the same storage: must still be all transparent
  float worst = 0;
  for (int y = 0; y < r.h; ++y)
    for (int x = 0; x < r.w; ++x) worst = std::max(worst, fresh.at(x, y).a + fresh.at(x, y).r);
  CHECK(worst == 0.0f);
  fresh.at(7, 9) = Rgba{0.5f, 0.25f, 0.125f, 0.5f};
  const Image copy = fresh;
  CHECK(maxAbsDifference(copy, fresh, r) == 0.0f);
  Image assigned(Rect{0, 0, 3, 3});
  assigned = copy;
  CHECK(assigned.rect() == r);
  CHECK(maxAbsDifference(assigned, fresh, r) == 0.0f);
  Image moved(Rect{0, 0, 600, 600});
  moved = std::move(assigned);
  CHECK(moved.rect() == r);
  CHECK(moved.at(7, 9).b == 0.125f);
}

TEST_CASE("an image extended over a larger rect keeps its pixels and is transparent around them") {
  const Rect big{-3, 5, 300, 280};
  {
    Image dirty(big);  // pooled storage full of non-zero values, likely handed out again below
    for (int y = big.y; y < big.bottom(); ++y)
      for (int x = big.x; x < big.right(); ++x) dirty.at(x, y) = Rgba{1, 2, 3, 4};
  }
  // Own rect in the middle, touching the left/top corner, touching the right/bottom corner, equal.
  for (const Rect own : {Rect{40, 60, 100, 90}, Rect{-3, 5, 20, 10}, Rect{250, 240, 47, 45}, big}) {
    CAPTURE(own.x);
    CAPTURE(own.y);
    CAPTURE(own.w);
    CAPTURE(own.h);
    Image small(own);
    for (int y = own.y; y < own.bottom(); ++y)
      for (int x = own.x; x < own.right(); ++x) small.at(x, y) = Rgba{float(x), float(y), 0.5f, 1.0f};
    const Image extended = small.extendedTo(big);
    REQUIRE(extended.rect() == big);
    REQUIRE(extended.values().size() == std::size_t(big.area()) * 4);
    int wrong = 0;
    for (int y = big.y; y < big.bottom(); ++y)
      for (int x = big.x; x < big.right(); ++x) {
        const Rgba expected = own.contains(x, y) ? Rgba{float(x), float(y), 0.5f, 1.0f} : Rgba{};
        const Rgba& got = extended.at(x, y);
        wrong += got.r != expected.r || got.g != expected.g || got.b != expected.b || got.a != expected.a;
      }
    CHECK(wrong == 0);
  }
  const Image none = Image().extendedTo(Rect{0, 0, 4, 4});
  CHECK(none.rect() == (Rect{0, 0, 4, 4}));
  CHECK(none.at(3, 3).a == 0.0f);
}
