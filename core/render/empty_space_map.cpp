// Empty-space map: per-cell visibility from the brick's value ranges and the transfer table, then a
// two-pass chamfer distance transform with the 26-neighbourhood (exact for the chessboard metric).
#include "core/render/empty_space_map.h"

#include <algorithm>
#include <limits>

#include <glm/common.hpp>

namespace kdswap {

std::vector<std::uint8_t> EmptySpaceMap::chessboardDistance(std::vector<std::uint8_t> d, const glm::ivec3& n) {
  for (std::uint8_t& v : d) v = v == 0 ? 0 : 255;
  auto at = [&](int x, int y, int z) -> std::uint8_t& { return d[(std::size_t(z) * n.y + y) * n.x + x]; };
  // One raster pass: each cell takes 1 + the smallest distance among the 13 neighbours already
  // visited (sign = -1: those before it in x-fastest order; +1: the mirror pass).
  auto pass = [&](int sign) {
    const int z0 = sign < 0 ? 0 : n.z - 1, y0 = sign < 0 ? 0 : n.y - 1, x0 = sign < 0 ? 0 : n.x - 1;
    for (int iz = 0, z = z0; iz < n.z; ++iz, z -= sign)
      for (int iy = 0, y = y0; iy < n.y; ++iy, y -= sign)
        for (int ix = 0, x = x0; ix < n.x; ++ix, x -= sign) {
          std::uint8_t& here = at(x, y, z);
          if (here == 0) continue;
          int best = here;
          for (int dz = -1; dz <= 1; ++dz)
            for (int dy = -1; dy <= 1; ++dy)
              for (int dx = -1; dx <= 1; ++dx) {
                // Visited neighbours: lexicographically before (z, y, x) in the pass's order.
                const int order = dz != 0 ? dz : (dy != 0 ? dy : dx);
                if (order != sign) continue;
                const int nx = x + dx, ny = y + dy, nz = z + dz;
                if (nx < 0 || ny < 0 || nz < 0 || nx >= n.x || ny >= n.y || nz >= n.z) continue;
                best = std::min(best, at(nx, ny, nz) + 1);
              }
          here = std::uint8_t(std::min(best, 255));
        }
  };
  pass(-1);
  pass(+1);
  return d;
}

EmptySpaceMap::EmptySpaceMap(const Brick& brick, const TransferTable& table, float scale, float bias, bool enabled,
                             bool uniformCells)
    : cellCount_(brick.cellCount()) {
  if (brick.empty()) return;
  const CellRangeCodes& ranges = brick.cellRanges();
  std::vector<std::uint8_t> invisible(ranges.size(), 0);
  if (enabled)
    for (std::size_t i = 0; i < ranges.size(); ++i) {
      const glm::vec2 r = ranges.range(i);
      invisible[i] = r.x <= r.y && !table.anyVisible(r.x * scale + bias, r.y * scale + bias);
    }
  // Tight box around the cells that can be visible: outside it every sample is invisible.
  const glm::ivec3 n = cellCount_, c0 = brick.cellLo();
  glm::ivec3 lo(std::numeric_limits<int>::max()), hi(std::numeric_limits<int>::min());
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x)
        if (!invisible[cellIndex(glm::ivec3(x, y, z))]) {
          lo = glm::min(lo, glm::ivec3(x, y, z));
          hi = glm::max(hi, glm::ivec3(x, y, z));
        }
  anyVisible_ = lo.x <= hi.x;
  if (!anyVisible_) return;
  const int shift = brick.cellShift();
  visibleLo_ = glm::max(glm::vec3((lo + c0) << shift), glm::vec3(brick.owned().lo));
  visibleHi_ = glm::min(glm::vec3((hi + c0 + 1) << shift), glm::vec3(brick.owned().hi));
  allVisible_ = std::find(invisible.begin(), invisible.end(), std::uint8_t(1)) == invisible.end();
  std::size_t emptyInBox = 0;
  for (int z = lo.z; z <= hi.z; ++z)
    for (int y = lo.y; y <= hi.y; ++y)
      for (int x = lo.x; x <= hi.x; ++x) emptyInBox += invisible[cellIndex(glm::ivec3(x, y, z))];
  const glm::ivec3 box = hi - lo + 1;
  marchesEverySample_ = emptyInBox * kFewEmptyCells <= std::size_t(box.x) * box.y * box.z;
  reach_ = chessboardDistance(std::move(invisible), n);
  const std::vector<std::uint8_t>& uniform = brick.uniformCells();
  marchCodes_.resize(reach_.size() + kReachPadding, 0);
  for (std::size_t i = 0; i < reach_.size(); ++i) {
    const bool uniformVisible = uniformCells && reach_[i] == 0 && uniform[i] != 0;
    marchCodes_[i] = uniformVisible ? kUniformBit : marchesEverySample_ ? 0 : std::min(reach_[i], kReachMask);
    anyUniform_ = anyUniform_ || uniformVisible;
  }
  if (!allVisible_) groups_ = CellGroups(reach_.data(), n);
  reach_.resize(reach_.size() + kReachPadding, 0);
}

}  // namespace kdswap
