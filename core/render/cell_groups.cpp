// Cell groups: one pass over the cells, row by row, skipping along x what the reach and the groups
// already found visible allow.
#include "core/render/cell_groups.h"

#include <bit>

namespace kdswap {

int CellGroups::sizeFor(int cells) {
  int size = 1;
  while ((cells + size - 1) / size > kMaxPerAxis) size *= 2;
  return size;
}

CellGroups::CellGroups(const std::uint8_t* reach, const glm::ivec3& cells) {
  size = glm::ivec3(sizeFor(cells.x), sizeFor(cells.y), sizeFor(cells.z));
  shift = glm::ivec3(std::countr_zero(unsigned(size.x)), std::countr_zero(unsigned(size.y)),
                     std::countr_zero(unsigned(size.z)));
  count = (cells + size - 1) / size;
  visible.assign(std::size_t(count.x) * std::size_t(count.y) * std::size_t(count.z), 0);
  // Along x, a cell of reach n has n - 1 invisible cells after it, and a group found visible needs
  // no more looks, in this row or the next.
  for (int z = 0; z < cells.z; ++z)
    for (int y = 0; y < cells.y; ++y) {
      std::uint8_t* row = &visible[index(0, y >> shift.y, z >> shift.z)];
      const std::uint8_t* cell =
          reach + (std::size_t(z) * std::size_t(cells.y) + std::size_t(y)) * std::size_t(cells.x);
      for (int x = 0; x < cells.x;) {
        const int gx = x >> shift.x;
        if (row[gx]) {  // already visible: on to the next group along x
          x = (gx + 1) << shift.x;
          continue;
        }
        if (cell[x] > 0) {
          x += cell[x];
          continue;
        }
        row[gx] = 1;
        ++visibleCount;
        x = (gx + 1) << shift.x;
      }
    }
}

}  // namespace kdswap
