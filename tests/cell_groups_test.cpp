// CellGroups: a group is visible exactly when one of its cells has reach 0, whatever the reach of
// the invisible cells lets the scan skip; checked against a plain look at every cell, on reach
// fields made the way the empty-space map makes them (chessboard distance to a visible cell).
#include <doctest/doctest.h>

#include <random>

#include "core/render/cell_groups.h"
#include "core/render/empty_space_map.h"

using namespace kdswap;

TEST_CASE("cell groups: a group is visible exactly when one of its cells can be") {
  std::mt19937 rng(47);
  for (const glm::ivec3 cells : {glm::ivec3(1, 1, 1), glm::ivec3(5, 3, 7), glm::ivec3(12, 12, 12),
                                 glm::ivec3(13, 9, 30), glm::ivec3(32, 32, 32), glm::ivec3(70, 5, 25)}) {
    for (const double visibleShare : {0.0, 0.002, 0.05, 0.5}) {
      CAPTURE(cells.x);
      CAPTURE(cells.y);
      CAPTURE(cells.z);
      CAPTURE(visibleShare);
      const std::size_t n = std::size_t(cells.x) * std::size_t(cells.y) * std::size_t(cells.z);
      std::bernoulli_distribution visible(visibleShare);
      std::vector<std::uint8_t> zeroWhereVisible(n);
      for (std::uint8_t& v : zeroWhereVisible) v = visible(rng) ? 0 : 1;
      const std::vector<std::uint8_t> reach = EmptySpaceMap::chessboardDistance(zeroWhereVisible, cells);

      const CellGroups groups(reach.data(), cells);
      for (int a = 0; a < 3; ++a) {
        CHECK(groups.count[a] <= CellGroups::kMaxPerAxis);
        CHECK(groups.size[a] == 1 << groups.shift[a]);
        CHECK(groups.count[a] * groups.size[a] >= cells[a]);
        CHECK((groups.count[a] - 1) * groups.size[a] < cells[a]);
      }
      std::vector<std::uint8_t> expected(groups.visible.size(), 0);
      for (int z = 0; z < cells.z; ++z)
        for (int y = 0; y < cells.y; ++y)
          for (int x = 0; x < cells.x; ++x)
            if (reach[(std::size_t(z) * std::size_t(cells.y) + std::size_t(y)) * std::size_t(cells.x) +
                      std::size_t(x)] == 0)
              expected[groups.index(x >> groups.shift.x, y >> groups.shift.y, z >> groups.shift.z)] = 1;
      CHECK(groups.visible == expected);
      std::size_t count = 0;
      for (const std::uint8_t v : expected) count += v;
      CHECK(groups.visibleCount == count);
    }
  }
}
