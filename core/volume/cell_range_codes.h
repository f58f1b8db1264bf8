// CellRangeCodes: the value range of every macro cell of a brick in two bytes instead of eight.
// Each range is rounded outwards to one of 256 levels spanning the brick's own range, so a decoded
// range always contains the true one: empty-space skipping built on it may skip a little less,
// never a sample that could be visible. Small cells (4^3) skip far more empty space than 8^3 ones,
// and at 2 bytes a cell (1/32 byte per voxel) they cost little more than 8^3 cells did in floats.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>

namespace kdswap {

class CellRangeCodes {
 public:
  CellRangeCodes() = default;
  //! From (min, max) per cell; a cell with min > max holds no voxel (it decodes that way too).
  explicit CellRangeCodes(const std::vector<glm::vec2>& ranges);

  std::size_t size() const { return codes_.size() / 2; }
  std::size_t bytes() const { return codes_.size(); }
  //! A range containing cell i's (min, max); (max float, lowest float) for a cell without voxels.
  glm::vec2 range(std::size_t i) const;

 private:
  std::vector<std::uint8_t> codes_;  //!< per cell: level of the min (rounded down), of the max (up)
  float lo_ = 0.0f, hi_ = 0.0f;      //!< the brick's range: level 0 and level 255
};

}  // namespace kdswap
