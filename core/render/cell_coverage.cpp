// Cell coverage: [Sections] groups of cells | their corners projected | rectangles into row bits.
#include "core/render/cell_coverage.h"

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>

namespace kdswap {

CellCoverage::CellCoverage(const Brick& brick, const EmptySpaceMap& emptySpace, const Camera& camera,
                           const Rect& rect) {
  rect_ = rect;
  // A brick whose cells are all visible would cover its whole rectangle anyway.
  if (emptySpace.allVisible()) return;
  all_ = false;
  if (rect.empty() || !emptySpace.anyVisible()) {  // covers nothing
    rect_ = Rect{};
    return;
  }
  // [Groups] A group counts as visible when any of its cells is (found once, with the map).
  const CellGroups& groups = emptySpace.groups();
  const glm::ivec3 cells = emptySpace.cellCount();
  // Mostly visible (a dense field): the union would cover nearly every pixel, so it is not built.
  if (groups.visibleCount * kDenseDenominator > groups.visible.size() * kDenseNumerator) {
    coverAll();
    return;
  }
  wordsPerRow_ = (rect.w + 63) / 64 + 1;
  bits_.assign(std::size_t(wordsPerRow_) * std::size_t(rect.h), 0);

  // [Corners] The groups' corners lie on a lattice: per axis, group i starts at cell i * size,
  // clipped to the owned box (samples lie in it). Camera::project is linear in each coordinate
  // before its division, so each axis contributes its terms once per lattice line, not per point.
  const Camera::Basis b = camera.basis();
  const glm::vec3 spacing = brick.spacing();
  const glm::ivec3 ownedLo = brick.owned().lo, ownedHi = brick.owned().hi, cellLo = brick.cellLo();
  const int shift = brick.cellShift();
  std::array<std::vector<glm::vec3>, 3> terms;  // per axis and lattice line: (right, up, forward) terms
  for (int a = 0; a < 3; ++a) {
    terms[std::size_t(a)].resize(std::size_t(groups.count[a]) + 1);
    for (int i = 0; i <= groups.count[a]; ++i) {
      const int cell = std::min(i * groups.size[a], cells[a]);
      const int voxel = std::clamp((cellLo[a] + cell) << shift, ownedLo[a], ownedHi[a]);
      const float v = float(voxel) * spacing[a] - b.eye[a];
      terms[std::size_t(a)][std::size_t(i)] = glm::vec3(v * b.right[a], v * b.up[a], v * b.forward[a]);
    }
  }
  const int lx = groups.count.x + 1, ly = groups.count.y + 1, lz = groups.count.z + 1;
  std::vector<glm::vec2> pixel(std::size_t(lx) * std::size_t(ly) * std::size_t(lz));
  for (int k = 0; k < lz; ++k)
    for (int j = 0; j < ly; ++j)
      for (int i = 0; i < lx; ++i) {
        const glm::vec3 t = terms[0][std::size_t(i)] + terms[1][std::size_t(j)] + terms[2][std::size_t(k)];
        float sx = t.x, sy = t.y;
        if (!b.orthographic) {
          if (!(t.z > 1e-4f)) {  // a corner at or behind the eye: cover everything, as projectBox does
            coverAll();
            return;
          }
          sx /= t.z, sy /= t.z;
        }
        const glm::vec2 p = camera.pixelOfPlanePoint(sx, sy);
        if (!std::isfinite(p.x) || !std::isfinite(p.y)) {
          coverAll();
          return;
        }
        pixel[(std::size_t(k) * std::size_t(ly) + std::size_t(j)) * std::size_t(lx) + std::size_t(i)] = p;
      }

  // [Rectangles] Each visible group's bounding rectangle, with projectBox's pixel of slack.
  for (int gz = 0; gz < groups.count.z; ++gz)
    for (int gy = 0; gy < groups.count.y; ++gy)
      for (int gx = 0; gx < groups.count.x; ++gx) {
        if (!groups.visible[groups.index(gx, gy, gz)]) continue;
        glm::vec2 lo(1e30f), hi(-1e30f);
        for (int corner = 0; corner < 8; ++corner) {
          const int i = gx + (corner & 1), j = gy + (corner >> 1 & 1), k = gz + (corner >> 2 & 1);
          const glm::vec2 p = pixel[(std::size_t(k) * std::size_t(ly) + std::size_t(j)) * std::size_t(lx) + std::size_t(i)];
          lo = glm::min(lo, p), hi = glm::max(hi, p);
        }
        cover(camera.conservativePixels(lo, hi).intersect(rect));
      }
}

void CellCoverage::coverAll() {
  all_ = true;
  bits_.clear();
}

void CellCoverage::cover(const Rect& r) {
  if (r.empty()) return;
  // The rectangle's bits in its first and last word, the same for every row; whole words between.
  const int b0 = r.x - rect_.x, b1 = r.right() - rect_.x, first = b0 >> 6, last = (b1 - 1) >> 6;
  const std::uint64_t fromFirst = ~std::uint64_t(0) << (b0 & 63);
  const std::uint64_t toLast = ~std::uint64_t(0) >> (63 - ((b1 - 1) & 63));
  for (int y = r.y; y < r.bottom(); ++y) {
    std::uint64_t* row = bits_.data() + std::size_t(y - rect_.y) * std::size_t(wordsPerRow_);
    if (first == last) {
      row[first] |= fromFirst & toLast;
      continue;
    }
    row[first] |= fromFirst;
    for (int word = first + 1; word < last; ++word) row[word] = ~std::uint64_t(0);
    row[last] |= toLast;
  }
}

int CellCoverage::eightSlowly(int x, int y) const {
  int bits = 0;
  for (int j = 0; j < 8; ++j) {
    const int px = x + j;
    if (!rect_.contains(px, y)) continue;
    const int bit = px - rect_.x;
    const std::uint64_t word = bits_[std::size_t(y - rect_.y) * std::size_t(wordsPerRow_) + std::size_t(bit >> 6)];
    bits |= int(word >> (bit & 63) & 1) << j;
  }
  return bits;
}

std::int64_t CellCoverage::coveredPixels() const {
  if (all_) return rect_.area();
  std::int64_t n = 0;
  for (const std::uint64_t word : bits_) n += std::popcount(word);
  return n;
}

}  // namespace kdswap
