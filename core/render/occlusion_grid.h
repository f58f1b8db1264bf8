// Occlusion culling across bricks (beyond the paper). Early ray termination stops a whole ray, but
// a node rendering a brick deep inside the volume cannot see what lies in front of it, so with P
// nodes it samples behind opaque matter that one node would never reach. Every node therefore
// holds a small replicated summary of the whole volume, the value range of every 4^3 cell
// (gathered once from the bricks, 1/64 of the voxel count), and skips a ray when the samples in
// front of its brick certainly reach the termination opacity: the single-node ray stops before
// this brick, so the skipped segment adds nothing to the single-node image either. Exact, not an
// approximation: it never skips a sample the single-node image uses.
#pragma once

#include <climits>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "core/render/ray_setup.h"
#include "core/transfer/transfer_function.h"
#include "core/volume/brick.h"

namespace kdswap {

//! Value range of every cell of the whole volume: cell c holds the samples whose floor lies in
//! [4c, 4c + 4) and the range covers every voxel they touch. A cell cut by bricks takes the union
//! of their ranges. Cells of 4^3, like the bricks' empty-space cells: an opaque layer a few voxels
//! thick (a skull, a dense region of a turbulent field) fills whole 4^3 cells far more often than
//! 8^3 ones, and only cells it fills count as opaque (turbulence at P = 64: 9.4 M -> 6.2 M samples).
//! Kept as floats for the whole volume (replicated, read by every node's culling).
//!
//! A layer thinner than a cell's five voxels (the phantom's skull is 3.5) fills no cell, so the
//! cells with the widest ranges (matter against air) also keep the range of each of their 64
//! one-voxel cells, as two 8-bit codes on the cell's range: a walk crossing such a cell steps
//! through its voxels. At most a quarter of the cells keep them (128 bytes each), so the summary
//! stays a small fraction of the volume. Phantom 256^3 at P = 64: 2.84 M -> ~1.5 M samples a frame
//! (one node: 1.0 M).
struct CellRangeGrid {
  static constexpr int kShift = 2;  //!< cells of 2^kShift voxels per axis
  static constexpr int kSide = 1 << kShift;
  static constexpr int kFinePerCell = kSide * kSide * kSide;  //!< one-voxel cells in a cell
  //! At most one cell in this many keeps fine ranges (128 bytes each: 2 bytes a voxel-cell).
  static constexpr int kFineBudgetDivisor = 4;
  //! Only cells whose range spans at least this share of the volume's keep them: a sharp boundary
  //! between matter and air (the phantom's skull: its whole range). Narrower ranges (a smooth
  //! field, soft tissue) rarely gain, and every kept cell costs time whenever the transfer
  //! function changes (turbulence 256^3: 65.5 k candidate cells at 1/32, 127 at 1/2; the phantom's
  //! samples are the same either way).
  static constexpr float kFineMinWidth = 0.5f;

  //! Range of a one-voxel cell as codes on its cell's range r: [r.x + lo * w, r.x + hi * w] with
  //! w = (r.y - r.x) / 255, rounded outwards; lo > hi: no sample there.
  struct FineCodes {
    std::uint8_t lo, hi;
  };

  glm::ivec3 dims{0};   //!< volume dimensions in voxels
  glm::ivec3 count{0};  //!< cells per axis
  std::vector<glm::vec2> ranges;  //!< (min, max), x fastest; min > max: no sample there
  std::vector<std::int32_t> fineBlock;  //!< per cell: its block of fine codes, or -1
  std::vector<FineCodes> fine;          //!< kFinePerCell per block, x fastest within the cell

  //! From bricks that together own the whole volume (each reads its own voxels):
  //! withRanges(dims, rangesOf(dims, bricks), bricks).
  static CellRangeGrid fromBricks(const glm::ivec3& dims, const std::vector<const Brick*>& bricks);
  //! Cells per axis for a volume of `dims`.
  static glm::ivec3 cellCount(const glm::ivec3& dims);
  //! The ranges these bricks give (cells they do not reach stay empty, min > max). Processes that
  //! hold different bricks of one volume (MPI ranks) merge theirs, min of minima and max of maxima,
  //! into the whole volume's.
  static std::vector<glm::vec2> rangesOf(const glm::ivec3& dims, const std::vector<const Brick*>& bricks);
  //! The grid of the whole volume's `ranges`, with the fine codes of the one-voxel cells `bricks`
  //! own; the others stay empty (lo > hi), so processes merge theirs with min of lo, max of hi.
  static CellRangeGrid withRanges(const glm::ivec3& dims, std::vector<glm::vec2> ranges,
                                  const std::vector<const Brick*>& bricks);
  //! The value range fine code `c` of cell `cell` stands for (min > max: none).
  glm::vec2 fineRange(std::size_t cell, FineCodes c) const;
};

class OcclusionGrid {
 public:
  //! For one frame: the transfer table, the value mapping (normalised = value * scale + bias) and
  //! the early-termination opacity. Inactive when early termination is off (stopAt >= 1) or no
  //! cell can add opacity for certain (then nothing could ever be culled).
  OcclusionGrid(const CellRangeGrid& cells, const TransferTable& table, float scale, float bias, float stopAt);

  static constexpr long kNever = LONG_MAX;

  bool active() const { return active_; }
  //! Cells whose walks step through their one-voxel cells (for statistics and tests).
  std::size_t fineBlocks() const { return fineBlocks_; }
  //! A lattice index K such that the samples k < K (t = (k + phase) * step) of the whole-volume ray
  //! o + d t (voxel coordinates) certainly reach opacity stopAt: the single-node ray ends before
  //! sample K, so no sample k >= K counts. The smallest such K the summary proves; kNever if none.
  long occludedFrom(const glm::vec3& o, const glm::vec3& d, float step, float phase) const;
  //! occludedFrom for eight rays given lane by lane (as the eight-pixel ray setup makes them), the
  //! same values. With AVX2 the eight walk the cells at once (the map's per-pixel walks were ~20%
  //! of a frame).
  void occludedFrom(const VoxelRays8& rays, float step, long* out) const;
  //! occludedFrom for sixteen rays, `first`'s eight then `second`'s, into out[0..15]: the same values.
  //! With AVX-512 the sixteen walk at once (occlusion_grid_avx512.cpp), which the map uses where
  //! walksSixteen(); elsewhere as two groups of eight.
  void occludedFrom(const VoxelRays8& first, const VoxelRays8& second, float step, long* out) const;
  //! The map should hand this grid sixteen rays at a time: the CPU runs AVX-512 at full speed (AMD;
  //! cpuRunsWideVectorsAtFullSpeed), or KDSWAP_SIMD=avx512 asks for it where the CPU has it.
  //! (The phantom 256^3 at P = 64 on 2 cores of an AMD EPYC, Zen 5: the map 9.2 -> 5.6 ms a frame.)
  bool walksSixteen() const { return sixteen_; }

  //! A ray as the walks hold it, for the steps through one-voxel cells.
  struct RayLine {
    float ox, oy, oz, dx, dy, dz;
  };
  //! The block of one-voxel depths a negative cell depth stands for.
  static int blockOf(float depth) { return int(-depth) - 1; }
  //! Cell depths below -kReachBase stand for a cell without depth whose empty surroundings reach
  //! -depth - kReachBase (>= 1); blocks of one-voxel depths lie above it (-1 .. -kReachBase).
  static constexpr float kReachBase = 8388608.0f;  // 2^23: both codes stay exact floats
  //! The walk's segment [t, end) crosses cell (cx, cy, cz), whose one-voxel depths are block
  //! `block` of fineCode_: adds their samples to `sum` voxel by voxel, with the cell walk's
  //! counting rule. True, with the lattice index in `reached`, when the threshold is reached.
  //! The scalar walk's step; the eight- and sixteen-lane walks step all their lanes in such cells
  //! together with the same positions, rule and order of sums (walkFineCells), so all agree bit for bit.
  bool walkFine(const RayLine& ray, int cx, int cy, int cz, int block, float t, float end, float step, float phase,
                float& sum, long& reached) const;

  //! The lattice indices a walk counts in its segment [t, end): first, and one past the last, the
  //! points at least a margin inside (a fiftieth of a step, and rounding of t), so rounding in
  //! positions and boundaries never counts a sample twice or in the wrong cell. One rule for the
  //! cell walk and the voxel-cell walk (the eight-lane walk spells out the same operations).
  struct CountedRange {
    float first, last;
  };
  static CountedRange countedRange(float t, float end, float perStep, float step, float phase) {
    const float margin = 0.02f * step + 1e-6f * std::fabs(end);
    return {std::ceil((t + margin) * perStep - phase), std::ceil((end - margin) * perStep - phase)};
  }

 private:
  //! One ray's walk through the cells, between cell crossings (for the walks in occlusion_grid*.cpp).
  struct Walk {
    float t, t1;                  //!< where the current cell's segment starts; where the walk ends
    float exitX, exitY, exitZ;    //!< t at which the ray leaves the current cell along each axis
    float deltaX, deltaY, deltaZ; //!< t across one cell along each axis
    float phase;
    int cx, cy, cz, dirX, dirY, dirZ;
    std::ptrdiff_t index;         //!< linear index of cell (cx, cy, cz)
    RayLine ray;
  };
  //! Sets up the walk of ray o + d t; false when it cannot reach the threshold (kNever).
  bool startWalk(const glm::vec3& o, const glm::vec3& d, float step, float phase, Walk& w) const;
  //! The scalar walk from its start to the answer.
  long walk(Walk w, float step) const;
  //! The threshold is reached in the current segment: the lattice index that reaches it.
  long reachedAt(float sum, float depth, float first, float samples) const;
  //! Keeps, for the cells whose one-voxel cells prove more depth than the cell, their depths.
  void useFineCells(const CellRangeGrid& cells, const TransferTable& table, float scale, float bias);
  //! occludedFrom of eight rays, started and walked eight at once (occlusion_grid_avx2.cpp): the
  //! same answers; false when this CPU or build has no AVX2.
  bool walkRays8(const VoxelRays8& rays, float step, long* out) const;
  //! occludedFrom of sixteen rays walked at once (AVX-512): the same answers; false when this CPU or
  //! build has no AVX-512 F, VL, DQ and BW.
  bool walkRays16(const VoxelRays8& first, const VoxelRays8& second, float step, long* out) const;

  glm::ivec3 count_{0};
  glm::vec3 domainHi_{0.0f};  //!< samples lie in [0, dims - 1) per axis
  glm::vec3 depthLo_{0.0f}, depthHi_{0.0f};  //!< voxel box of the cells that add depth, within the domain
  //! Per cell: -ln(1 - smallest opacity a sample there can have); a sum over samples bounds the
  //! optical depth, so opacity >= 1 - exp(-sum). A cell whose one-voxel cells prove more stores
  //! -(b + 1) instead: block b of fineCode_ holds theirs (blockOf reads it back). A cell without
  //! depth stores -(kReachBase + n): every cell within n - 1 of it along each axis has none
  //! either (EmptySpaceMap::chessboardDistance), so the walks cross that cube in one step. One
  //! array, so a walk's step reads one value (the eight-lane gathers were the walk's cost).
  std::vector<float> depth_;
  //! CellRangeGrid::kFinePerCell codes per block (x fastest) from fineOffset_ on, a block per cache line.
  std::vector<std::uint8_t> fineCode_;
  std::size_t fineOffset_ = 0;
  std::size_t fineBlocks_ = 0;
  float depthOfCode_[256] = {};  //!< the optical depth each code stands for, rounded down
  float threshold_ = 0.0f;  //!< sum needed for opacity >= stopAt, with a margin for rounding
  bool active_ = false;
  bool sixteen_ = false;       //!< walksSixteen()
};

}  // namespace kdswap
