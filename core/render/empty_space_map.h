// EmptySpaceMap: which macro cells of a brick can hold a visible sample under one transfer function,
// and, for every other cell, how far the invisible region around it reaches, so a ray crosses a
// whole empty region in one jump instead of one jump per 4-voxel cell. Skipping loses nothing: only
// samples whose opacity is certainly 0 are left out, so images equal those without skipping up to
// float rounding (the samples taken are composited in groups of eight: FrontToBack::addEight).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/render/cell_groups.h"
#include "core/transfer/transfer_function.h"
#include "core/volume/brick.h"

namespace kdswap {

class EmptySpaceMap {
 public:
  //! Normalised scalar = value * scale + bias. With `enabled` false nothing is skipped (the
  //! reference for tests: every owned sample is taken); with `uniformCells` false no cell is
  //! marked uniform (the reference for tests: every sample is interpolated).
  EmptySpaceMap(const Brick& brick, const TransferTable& table, float scale, float bias, bool enabled = true,
                bool uniformCells = true);

  //! 0 when a sample in the cell can be visible. Otherwise n >= 1: every cell within n - 1 of this
  //! one along each axis (a cube of 2n - 1 cells) is invisible, as far as it lies in the brick.
  std::uint8_t reach(std::size_t cellIndex) const { return reach_[cellIndex]; }
  //! All cells' reach, x fastest, followed by kReachPadding zeros (a SIMD gather reads 4 bytes).
  const std::uint8_t* reachData() const { return reach_.data(); }
  static constexpr std::size_t kReachPadding = 3;
  //! The march's codes, one byte a cell (x fastest, padded as reachData): bits 0-6 the reach
  //! (capped at 127: a smaller cube of invisible cells is still invisible), bit 7 set on visible
  //! cells the brick marks uniform (Brick::uniformCells), whose samples take the cell's record.
  //! Where the march takes every sample (marchesEverySample), every reach here is 0.
  const std::uint8_t* marchCodes() const { return marchCodes_.data(); }
  static constexpr std::uint8_t kUniformBit = 0x80, kReachMask = 0x7F;
  //! Some visible cell is uniform (some code has kUniformBit).
  bool anyUniform() const { return anyUniform_; }
  const glm::ivec3& cellCount() const { return cellCount_; }
  std::size_t cellIndex(const glm::ivec3& cell) const {  //!< cell relative to the brick's first
    return (std::size_t(cell.z) * cellCount_.y + cell.y) * cellCount_.x + cell.x;
  }

  bool anyVisible() const { return anyVisible_; }
  //! Every cell can hold a visible sample (every reach is 0).
  bool allVisible() const { return allVisible_; }
  //! The march takes every sample, skipping nothing (its codes hold no reach), so it may skip the
  //! map: all cells are visible, or so few inside the visible box are not (at most one in
  //! kFewEmptyCells) that testing every group of eight for them would cost more than shading their
  //! samples, whose opacity is 0 (dense data: turbulence with 2^3 cells). Coverage and the
  //! visible box still use the exact reach.
  bool marchesEverySample() const { return marchesEverySample_; }
  static constexpr std::size_t kFewEmptyCells = 16;
  //! Bounds (voxel coordinates, within the owned box) of the cells that can be visible; rays and
  //! the screen rectangle are clipped to them. The owned box when skipping is off.
  const glm::vec3& visibleLo() const { return visibleLo_; }
  const glm::vec3& visibleHi() const { return visibleHi_; }
  //! The cells in groups, for the coverage of each frame; built only when some cells are visible
  //! and some are not (otherwise the coverage needs none).
  const CellGroups& groups() const { return groups_; }

  //! Chessboard distance, capped at 255, from each cell to the nearest cell marked 0 (x fastest).
  //! Cells marked 0 stay 0; with no 0 at all every cell gets 255. Exposed for its test.
  static std::vector<std::uint8_t> chessboardDistance(std::vector<std::uint8_t> visibleIsZero, const glm::ivec3& count);

 private:
  glm::ivec3 cellCount_{0};
  std::vector<std::uint8_t> reach_;
  std::vector<std::uint8_t> marchCodes_;
  glm::vec3 visibleLo_{0.0f}, visibleHi_{0.0f};
  CellGroups groups_;
  bool anyVisible_ = false;
  bool allVisible_ = false;
  bool marchesEverySample_ = false;
  bool anyUniform_ = false;
};

}  // namespace kdswap
