// Cell range codes: every decoded range contains the true one (so skipping built on them never
// loses a visible sample) and is at most one level of the brick's range wider on each side.
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <random>
#include <vector>

#include "core/volume/cell_range_codes.h"

using namespace kdswap;

TEST_CASE("cell range codes decode to ranges that contain the true ones, at most a level wider") {
  std::mt19937 rng(17);
  struct Case {
    float offset, span;
  };
  // Unit data, CT-like integers, float data far from zero, a tiny span on a large offset.
  const Case cases[] = {{0.0f, 1.0f}, {-1024.0f, 4095.0f}, {1.0e6f, 250.0f}, {5000.0f, 0.01f}, {-3.0e-5f, 6.0e-5f}};
  for (const Case& c : cases) {
    std::uniform_real_distribution<float> value(c.offset, c.offset + c.span);
    std::vector<glm::vec2> ranges(4000);
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      if (i % 97 == 5) {  // a cell no voxel reaches
        ranges[i] = glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest());
        continue;
      }
      float a = value(rng), b = value(rng);
      if (i % 13 == 0) b = a;  // a constant cell
      ranges[i] = glm::vec2(std::min(a, b), std::max(a, b));
    }
    const CellRangeCodes codes(ranges);
    REQUIRE(codes.size() == ranges.size());
    CHECK(codes.bytes() == 2 * ranges.size());
    float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
    for (const glm::vec2& r : ranges)
      if (r.x <= r.y) lo = std::min(lo, r.x), hi = std::max(hi, r.y);
    const double level = (double(hi) - double(lo)) / 255.0;
    int contained = 0, tight = 0, emptyKept = 0;
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      const glm::vec2 d = codes.range(i), r = ranges[i];
      if (!(r.x <= r.y)) {
        emptyKept += !(d.x <= d.y);
        continue;
      }
      contained += d.x <= r.x && r.y <= d.y;
      const double slack = level + 4.0 * std::numeric_limits<float>::epsilon() * std::fabs(double(hi));
      tight += double(r.x) - double(d.x) <= slack && double(d.y) - double(r.y) <= slack;
    }
    CAPTURE(c.offset);
    CAPTURE(c.span);
    const int cells = int(ranges.size()) - (int(ranges.size()) + 91) / 97;
    CHECK(contained == cells);
    CHECK(tight == cells);
    CHECK(emptyKept == int(ranges.size()) - cells);
  }
}

TEST_CASE("cell range codes of a constant brick decode to its one value") {
  const std::vector<glm::vec2> ranges(10, glm::vec2(7.25f, 7.25f));
  const CellRangeCodes codes(ranges);
  for (std::size_t i = 0; i < ranges.size(); ++i) CHECK(codes.range(i) == glm::vec2(7.25f, 7.25f));
}
