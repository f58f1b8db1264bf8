// "over" on premultiplied colour is associative, which is what lets compositing regroup.
#include <doctest/doctest.h>

#include <cstring>
#include <random>

#include "core/image/image.h"

using namespace kdswap;

namespace {

Rgba randomPremultiplied(std::mt19937& rng) {
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  const float a = u(rng);
  return Rgba{u(rng) * a, u(rng) * a, u(rng) * a, a};
}

}  // namespace

TEST_CASE("over is associative on random premultiplied colours to float rounding") {
  std::mt19937 rng(1234);
  float worst = 0.0f;
  for (int i = 0; i < 100000; ++i) {
    const Rgba a = randomPremultiplied(rng), b = randomPremultiplied(rng), c = randomPremultiplied(rng);
    const Rgba left = over(over(a, b), c), right = over(a, over(b, c));
    worst = std::max({worst, std::fabs(left.r - right.r), std::fabs(left.g - right.g), std::fabs(left.b - right.b),
                      std::fabs(left.a - right.a)});
  }
  CHECK(worst <= 1e-6f);
}

TEST_CASE("over with an opaque front hides the back and a transparent front shows it") {
  const Rgba back{0.2f, 0.3f, 0.4f, 0.5f};
  const Rgba opaque{0.9f, 0.1f, 0.1f, 1.0f};
  const Rgba hidden = over(opaque, back);
  CHECK(hidden.r == doctest::Approx(0.9f));
  CHECK(hidden.a == doctest::Approx(1.0f));
  const Rgba shown = over(Rgba{}, back);
  CHECK(shown.g == doctest::Approx(0.3f));
  CHECK(shown.a == doctest::Approx(0.5f));
}

TEST_CASE("compositeInto blends only the other image's rectangle, in the order given") {
  Image dst(Rect{0, 0, 4, 4});
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 4; ++x) dst.at(x, y) = Rgba{0.5f, 0.0f, 0.0f, 0.5f};
  Image front(Rect{1, 1, 2, 2});
  for (int y = 1; y < 3; ++y)
    for (int x = 1; x < 3; ++x) front.at(x, y) = Rgba{0.0f, 0.5f, 0.0f, 0.5f};
  CHECK(compositeInto(dst, front, true) == 4);
  CHECK(dst.at(1, 1).g == doctest::Approx(0.5f));
  CHECK(dst.at(1, 1).r == doctest::Approx(0.25f));
  CHECK(dst.at(0, 0).g == 0.0f);
  CHECK(dst.at(0, 0).r == doctest::Approx(0.5f));
}

TEST_CASE("overOf equals extending one image to the union and compositing the other into it") {
  std::mt19937 rng(77);
  std::uniform_int_distribution<int> pos(0, 12), size(0, 9);
  auto randomImage = [&](const Rect& r) {
    Image image(r);
    for (int y = r.y; y < r.bottom(); ++y)
      for (int x = r.x; x < r.right(); ++x) image.at(x, y) = randomPremultiplied(rng);
    return image;
  };
  int overlapping = 0, disjoint = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const Image a = randomImage(Rect{pos(rng), pos(rng), size(rng) + 1, size(rng) + 1});
    const Image b = randomImage(Rect{pos(rng), pos(rng), size(rng) + 1, size(rng) + 1});
    const Rect both = a.rect().unite(b.rect());
    (a.rect().intersect(b.rect()).empty() ? disjoint : overlapping) += 1;
    for (const bool aInFront : {true, false}) {
      Image expected = b.extendedTo(both);
      compositeInto(expected, a, aInFront);
      const Image got = aInFront ? overOf(a.view(), b.view()) : overOf(b.view(), a.view());
      REQUIRE(got.rect() == both);
      // Bit for bit: compositing may take either path for the same frame.
      REQUIRE(std::memcmp(got.data(), expected.data(), expected.bytes()) == 0);
    }
  }
  CHECK(overlapping > 50);
  CHECK(disjoint > 50);
  // Views with a row stride wider than the rect (parts of larger images).
  const Image big = randomImage(Rect{0, 0, 16, 16});
  const ImageView front = big.view(Rect{2, 3, 5, 6}), back = big.view(Rect{4, 1, 9, 4});
  Image expected = Image(back).extendedTo(front.rect.unite(back.rect));
  compositeInto(expected, front, true);
  const Image got = overOf(front, back);
  CHECK(std::memcmp(got.data(), expected.data(), expected.bytes()) == 0);
}
