// CellGroups: a brick's empty-space cells gathered into at most kMaxPerAxis groups a side, each
// marked visible when any of its cells can be. CellCoverage projects the visible groups every
// frame; which groups are visible does not depend on the view, so it is found once with the
// empty-space map (per brick and transfer function) instead of once per frame. Rescanning every
// cell per frame cost 0.5 ms of a single thread at P = 1 on the phantom 256^3 (while the other
// core waited for the tiles) and 0.9 ms of CPU at P = 64.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace kdswap {

struct CellGroups {
  //! At most this many groups per axis: a brick with more cells a side is grouped by 2, 4, ...
  //! cells (the phantom 256^3 at P = 64, 32 cells a side, by 4: 8 groups a side).
  static constexpr int kMaxPerAxis = 12;

  glm::ivec3 count{0};  //!< groups per axis
  glm::ivec3 size{1};   //!< cells per group and axis, powers of two
  glm::ivec3 shift{0};  //!< log2(size): a cell's group is a shift away
  std::vector<std::uint8_t> visible;  //!< per group, x fastest: 1 when a cell in it can be visible
  std::size_t visibleCount = 0;

  CellGroups() = default;
  //! From the empty-space map's reach (0: a cell that can be visible; n >= 1: the n - 1 cells
  //! after it along x are invisible too), x fastest over `cells`.
  CellGroups(const std::uint8_t* reach, const glm::ivec3& cells);

  std::size_t index(int gx, int gy, int gz) const {
    return (std::size_t(gz) * std::size_t(count.y) + std::size_t(gy)) * std::size_t(count.x) + std::size_t(gx);
  }
  //! Cells per group along an axis with `cells` cells: the smallest power of two leaving at most
  //! kMaxPerAxis groups.
  static int sizeFor(int cells);
};

}  // namespace kdswap
