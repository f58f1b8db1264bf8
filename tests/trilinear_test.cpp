// Trilinear interpolation reproduces voxel values at voxel centres and is linear along edges.
#include <doctest/doctest.h>

#include "core/render/reference_render.h"
#include "core/render/trilinear.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("trilinear interpolation reproduces voxel values at voxel centres") {
  auto volume = test::makeVolume({7, 6, 5}, [](int x, int y, int z) { return float((x * 13 + y * 7 + z * 3) % 11); });
  const Brick whole = wholeVolumeBrick(*volume);
  for (int z = 0; z < 4; ++z)
    for (int y = 0; y < 5; ++y)
      for (int x = 0; x < 6; ++x) {
        const TrilinearCell cell(whole, glm::vec3(x, y, z));
        CHECK(cell.value() == float((x * 13 + y * 7 + z * 3) % 11));
      }
}

TEST_CASE("trilinear interpolation is linear along each cell edge") {
  auto volume = test::makeVolume({4, 4, 4}, [](int x, int y, int z) { return float(x * x + 3 * y * z + z); });
  const Brick whole = wholeVolumeBrick(*volume);
  auto value = [&](int x, int y, int z) { return float(x * x + 3 * y * z + z); };
  for (float t : {0.0f, 0.125f, 0.3f, 0.5f, 0.77f, 0.999f}) {
    CHECK(TrilinearCell(whole, {1.0f + t, 2.0f, 1.0f}).value() == doctest::Approx((1 - t) * value(1, 2, 1) + t * value(2, 2, 1)));
    CHECK(TrilinearCell(whole, {2.0f, 1.0f + t, 2.0f}).value() == doctest::Approx((1 - t) * value(2, 1, 2) + t * value(2, 2, 2)));
    CHECK(TrilinearCell(whole, {0.0f, 2.0f, 1.0f + t}).value() == doctest::Approx((1 - t) * value(0, 2, 1) + t * value(0, 2, 2)));
  }
}

TEST_CASE("gradients are central differences inside and one-sided at the volume faces") {
  auto volume = test::makeVolume({5, 5, 5}, [](int x, int y, int z) { return float(x * x + 2 * y + 0 * z); },
                                 glm::vec3(2.0f, 1.0f, 1.0f));
  const Brick whole = wholeVolumeBrick(*volume);
  CHECK(whole.voxel(2, 2, 2).gradient.x == doctest::Approx((9.0f - 1.0f) / 4.0f));  // (f(3)-f(1)) / (2 * 2)
  CHECK(whole.voxel(0, 2, 2).gradient.x == doctest::Approx((1.0f - 0.0f) / 2.0f));  // one-sided at x = 0
  CHECK(whole.voxel(4, 2, 2).gradient.x == doctest::Approx((16.0f - 9.0f) / 2.0f));
  CHECK(whole.voxel(3, 1, 3).gradient.y == doctest::Approx(2.0f));
  CHECK(whole.voxel(3, 1, 3).gradient.z == doctest::Approx(0.0f));
}
