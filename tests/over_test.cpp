// "over" on premultiplied colour is associative, which is what lets compositing regroup.
#include <doctest/doctest.h>

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
