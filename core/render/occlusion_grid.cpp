// Occlusion culling: the replicated cell summary, per-frame optical depths, and a march through the
// cells in front of a brick (3D DDA) that bounds the opacity the single-node ray has gathered.
#include "core/render/occlusion_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string_view>

#include <glm/common.hpp>
#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include "core/render/empty_space_map.h"
#include "core/util/cpu_features.h"

namespace kdswap {
namespace {

constexpr int kCell = CellRangeGrid::kSide;
constexpr int kFine = CellRangeGrid::kFinePerCell;
// Float accumulation of "over" can fall short of the exact opacity product by about one rounding
// per sample; this much opacity margin covers thousands of samples.
constexpr float kOpacityMargin = 1e-3f;
//! A block of one-voxel cells is used when its cells add, on average, at least this share of the
//! termination depth per sample over the whole cell's (see useFineCells).
constexpr double kMinFineGain = 0.04;

//! -ln(1 - a), rounded down, so a sum of them stays a lower bound of the optical depth.
float depthOfOpacity(float a) {
  return a <= 0.0f ? 0.0f : (a >= 1.0f ? 1e6f : float(-std::log1p(-double(a)) * (1.0 - 1e-6)));
}

//! The cells that keep fine ranges: those whose range is at least kFineMinWidth of the volume's,
//! the widest first, at most a kFineBudgetDivisor-th of the cells; -1 for the others.
std::vector<std::int32_t> chooseFineCells(const std::vector<glm::vec2>& ranges) {
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (const glm::vec2& r : ranges)
    if (r.x <= r.y) lo = std::min(lo, r.x), hi = std::max(hi, r.y);
  std::vector<std::int32_t> block(ranges.size(), -1);
  if (!(lo < hi) || !std::isfinite(hi - lo)) return block;
  const float minWidth = CellRangeGrid::kFineMinWidth * (hi - lo);
  std::vector<std::int32_t> wide;
  for (std::size_t i = 0; i < ranges.size(); ++i)
    if (ranges[i].y - ranges[i].x >= minWidth) wide.push_back(std::int32_t(i));
  // Block indices travel in the walk as exact floats (depth -(b + 1)): below 2^24.
  const std::size_t budget = std::min(std::max<std::size_t>(ranges.size() / CellRangeGrid::kFineBudgetDivisor, 1),
                                      std::size_t(1) << 23);
  if (wide.size() > budget) {
    auto width = [&](std::int32_t i) { return ranges[std::size_t(i)].y - ranges[std::size_t(i)].x; };
    std::nth_element(wide.begin(), wide.begin() + std::ptrdiff_t(budget), wide.end(),
                     [&](std::int32_t a, std::int32_t b) { return width(a) > width(b); });
    wide.resize(budget);
    std::sort(wide.begin(), wide.end());  // blocks in cell order, as the walks meet them
  }
  for (std::size_t b = 0; b < wide.size(); ++b) block[std::size_t(wide[b])] = std::int32_t(b);
  return block;
}

//! Fills the fine codes of the one-voxel cells whose samples `brick` owns (floors in
//! [owned.lo, owned.hi - 1]); each such cell's eight corners are kept by that brick.
void encodeFineRanges(const Brick& brick, CellRangeGrid& g) {
  const glm::ivec3 lo = brick.owned().lo, hi = glm::min(brick.owned().hi - 1, g.dims - 2);  // floors, inclusive
  if (glm::any(glm::lessThan(hi, lo))) return;
  const glm::ivec3 c0 = lo >> CellRangeGrid::kShift, c1 = hi >> CellRangeGrid::kShift;
  for (int cz = c0.z; cz <= c1.z; ++cz)
    for (int cy = c0.y; cy <= c1.y; ++cy)
      for (int cx = c0.x; cx <= c1.x; ++cx) {
        const std::size_t cell = (std::size_t(cz) * g.count.y + cy) * g.count.x + cx;
        const std::int32_t b = g.fineBlock[cell];
        if (b < 0) continue;
        const glm::vec2 r = g.ranges[cell];
        const double perCode = 255.0 / (double(r.y) - double(r.x));
        CellRangeGrid::FineCodes* codes = g.fine.data() + std::size_t(b) * kFine;
        const glm::ivec3 base(cx * kCell, cy * kCell, cz * kCell);
        const glm::ivec3 f0 = glm::max(base, lo), f1 = glm::min(base + (kCell - 1), hi);
        for (int z = f0.z; z <= f1.z; ++z)
          for (int y = f0.y; y <= f1.y; ++y)
            for (int x = f0.x; x <= f1.x; ++x) {
              float vMin = std::numeric_limits<float>::max(), vMax = std::numeric_limits<float>::lowest();
              for (int k = 0; k < 8; ++k) {
                const float v = brick.valueAt(x + (k & 1), y + (k >> 1 & 1), z + (k >> 2));
                vMin = std::min(vMin, v), vMax = std::max(vMax, v);  // NaN ignored, as in the cell ranges
              }
              if (!(vMin <= vMax)) continue;
              // Outwards: the code range contains [vMin, vMax].
              const double qLo = std::floor((double(vMin) - r.x) * perCode), qHi = std::ceil((double(vMax) - r.x) * perCode);
              CellRangeGrid::FineCodes& c = codes[((z - base.z) * kCell + (y - base.y)) * kCell + (x - base.x)];
              c.lo = std::uint8_t(std::clamp(qLo, 0.0, 255.0));
              c.hi = std::uint8_t(std::clamp(qHi, 0.0, 255.0));
            }
      }
}

}  // namespace

glm::vec2 CellRangeGrid::fineRange(std::size_t cell, FineCodes c) const {
  if (c.lo > c.hi) return glm::vec2(1.0f, 0.0f);
  const glm::vec2 r = ranges[cell];
  const double perCode = (double(r.y) - double(r.x)) / 255.0;
  // The end codes give the cell's own bounds exactly; the others are off by a float rounding at
  // most, which the transfer table's one-entry widening (minAlpha) covers.
  return glm::vec2(c.lo == 0 ? r.x : float(r.x + c.lo * perCode), c.hi == 255 ? r.y : float(r.x + c.hi * perCode));
}

glm::ivec3 CellRangeGrid::cellCount(const glm::ivec3& dims) {
  return glm::max((dims - 2) / kCell + 1, glm::ivec3(1));  // samples' floors lie in [0, dims - 2]
}

std::vector<glm::vec2> CellRangeGrid::rangesOf(const glm::ivec3& dims, const std::vector<const Brick*>& bricks) {
  const glm::ivec3 count = cellCount(dims);
  std::vector<glm::vec2> ranges(std::size_t(count.x) * count.y * count.z,
                                glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()));
  for (const Brick* b : bricks)
    if (!b->empty()) b->widenCellRanges(kShift, glm::ivec3(0), count, ranges);
  return ranges;
}

CellRangeGrid CellRangeGrid::withRanges(const glm::ivec3& dims, std::vector<glm::vec2> ranges,
                                        const std::vector<const Brick*>& bricks) {
  CellRangeGrid g;
  g.dims = dims;
  g.count = cellCount(dims);
  g.ranges = std::move(ranges);
  g.fineBlock = chooseFineCells(g.ranges);
  const std::size_t blocks = std::size_t(std::count_if(g.fineBlock.begin(), g.fineBlock.end(), [](std::int32_t b) { return b >= 0; }));
  g.fine.assign(blocks * kFine, FineCodes{255, 0});
  if (blocks > 0)
    tbb::parallel_for(std::size_t(0), bricks.size(), [&](std::size_t i) {
      if (!bricks[i]->empty()) encodeFineRanges(*bricks[i], g);  // each one-voxel cell has one owner
    });
  return g;
}

CellRangeGrid CellRangeGrid::fromBricks(const glm::ivec3& dims, const std::vector<const Brick*>& bricks) {
  return withRanges(dims, rangesOf(dims, bricks), bricks);
}

OcclusionGrid::OcclusionGrid(const CellRangeGrid& cells, const TransferTable& table, float scale, float bias,
                             float stopAt)
    : count_(cells.count), domainHi_(glm::vec3(cells.dims - 1)) {
  if (!(stopAt > 0.0f && stopAt + kOpacityMargin < 1.0f) || cells.ranges.empty()) return;
  active_ = true;
  const std::string_view request = simdRequest();
  sixteen_ = cpuHasAvx512vl() && request != "avx2" && request != "avx512vl" &&
             (request == "avx512" || cpuRunsWideVectorsAtFullSpeed());
  threshold_ = float(-std::log1p(-double(stopAt + kOpacityMargin)));
  depth_.resize(cells.ranges.size());
  for (std::size_t i = 0; i < depth_.size(); ++i) {
    const glm::vec2 r = cells.ranges[i];
    depth_[i] = depthOfOpacity(r.x <= r.y ? table.minAlpha(r.x * scale + bias, r.y * scale + bias) : 0.0f);
  }
  useFineCells(cells, table, scale, bias);
  // The box of cells that add depth: rays march only through it, since nothing outside counts.
  // With none (a translucent transfer function), nothing can be culled: the grid is inactive and
  // the per-frame map costs nothing.
  glm::ivec3 lo(std::numeric_limits<int>::max()), hi(-1);
  for (int z = 0; z < count_.z; ++z)
    for (int y = 0; y < count_.y; ++y)
      for (int x = 0; x < count_.x; ++x)
        if (depth_[(std::size_t(z) * count_.y + y) * count_.x + x] != 0.0f) {
          lo = glm::min(lo, glm::ivec3(x, y, z));
          hi = glm::max(hi, glm::ivec3(x, y, z));
        }
  if (hi.x < 0) {
    active_ = false;
    depth_.clear();
    return;
  }
  depthLo_ = glm::vec3(lo * kCell);
  depthHi_ = glm::min(glm::vec3((hi + 1) * kCell), domainHi_);
  // How far the cells without depth around each one reach (0 where a cell has depth): the walks
  // cross such a region in one step (the phantom's air: 80% of its cell steps).
  std::vector<std::uint8_t> zeroWhereDepth(depth_.size());
  for (std::size_t i = 0; i < depth_.size(); ++i) zeroWhereDepth[i] = depth_[i] != 0.0f ? 0 : 1;
  const std::vector<std::uint8_t> reach = EmptySpaceMap::chessboardDistance(std::move(zeroWhereDepth), count_);
  for (std::size_t i = 0; i < depth_.size(); ++i)
    if (depth_[i] == 0.0f) depth_[i] = -(kReachBase + float(reach[i]));
}

void OcclusionGrid::useFineCells(const CellRangeGrid& cells, const TransferTable& table, float scale, float bias) {
  // One-voxel depths travel as 8-bit codes (a block is one cache line): code q stands for
  // depthOfCode_[q], geometric from 1e-4 of the threshold up to the threshold. A voxel-cell gets
  // the highest code whose opacity, alphaOfCode[q] (rounded up), its smallest opacity reaches, so
  // the code's depth never exceeds its own: a lower bound stays one, and no logarithm per cell.
  depthOfCode_[0] = 0.0f;
  float alphaOfCode[256] = {0.0f};
  for (int q = 1; q < 256; ++q) {
    depthOfCode_[q] = float(double(threshold_) * std::exp(std::log(1e-4) * double(255 - q) / 254.0));
    const float a = float(-std::expm1(-double(depthOfCode_[q]) / (1.0 - 2e-6)));
    alphaOfCode[q] = std::nextafter(a, 2.0f);
  }
  auto codeOf = [&](float alpha) {  // the last q with alphaOfCode[q] <= alpha; branch-free halving
    int q = 0;
    for (int half = 128; half > 0; half /= 2) q += alphaOfCode[q + half] <= alpha ? half : 0;
    return std::uint8_t(q);
  };
  // A translucent transfer function (no sample adds the gain below) needs no block at all.
  if (depthOfOpacity(table.maxAlpha(0.0f, 1.0f)) < kMinFineGain * threshold_) return;
  std::vector<std::size_t> fineCells;
  for (std::size_t i = 0; i < cells.fineBlock.size(); ++i)
    if (cells.fineBlock[i] >= 0) fineCells.push_back(i);
  // Per block: the codes of its voxel-cells, each at least the whole cell's (both are lower
  // bounds). A block is kept where its voxel-cells prove clearly more than the whole cell: a
  // sample's step through voxels costs about what a cell's step does, and a small gain (a dense
  // field's smooth ranges, the CT head's soft tissue) buys fewer samples than it costs (measured:
  // turbulence P = 64 -6% samples but +30% time with every block; the phantom's skull keeps most
  // of its gain).
  std::vector<std::uint8_t> codes(fineCells.size() * kFine), useful(fineCells.size(), 0);
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, fineCells.size(), 256), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t k = r.begin(); k < r.end(); ++k) {
      const std::size_t cell = fineCells[k];
      const CellRangeGrid::FineCodes* ranges = cells.fine.data() + std::size_t(cells.fineBlock[cell]) * kFine;
      const glm::vec2 whole = cells.ranges[cell];
      const std::uint8_t floor = codeOf(table.minAlpha(whole.x * scale + bias, whole.y * scale + bias));
      std::uint8_t* out = codes.data() + k * kFine;
      double gain = 0.0;
      for (int i = 0; i < kFine; ++i) {
        const glm::vec2 v = cells.fineRange(cell, ranges[i]);
        out[i] = v.x <= v.y ? std::max(floor, codeOf(table.minAlpha(v.x * scale + bias, v.y * scale + bias))) : floor;
        gain += std::max(0.0f, depthOfCode_[out[i]] - depth_[cell]);
      }
      useful[k] = gain / kFine >= kMinFineGain * threshold_;
    }
  });
  const std::size_t blocks = std::size_t(std::count(useful.begin(), useful.end(), std::uint8_t(1)));
  // Blocks aligned to cache lines: the walk reads one line per cell it steps through voxel by voxel.
  // Three bytes more: the SIMD walks read each code as the low byte of four.
  fineCode_.assign(blocks * kFine + 63 + 3, 0);
  fineOffset_ = std::size_t((64 - reinterpret_cast<std::uintptr_t>(fineCode_.data()) % 64) % 64);
  std::size_t b = 0;
  for (std::size_t k = 0; k < fineCells.size(); ++k)
    if (useful[k]) {
      std::copy_n(codes.data() + k * kFine, kFine, fineCode_.data() + fineOffset_ + b * kFine);
      depth_[fineCells[k]] = -float(++b);
    }
  fineBlocks_ = blocks;
}

long OcclusionGrid::occludedFrom(const glm::vec3& o, const glm::vec3& d, float step, float phase) const {
  Walk w;
  return startWalk(o, d, step, phase, w) ? walk(w, step) : kNever;
}

void OcclusionGrid::occludedFrom(const VoxelRays8& rays, float step, long* out) const {
  if (active_ && step > 0.0f && walkRays8(rays, step, out)) return;
  for (int j = 0; j < 8; ++j)
    out[j] = occludedFrom(glm::vec3(rays.ox[j], rays.oy[j], rays.oz[j]), glm::vec3(rays.dx[j], rays.dy[j], rays.dz[j]),
                          step, rays.phase[j]);
}

void OcclusionGrid::occludedFrom(const VoxelRays8& first, const VoxelRays8& second, float step, long* out) const {
  if (active_ && step > 0.0f && walkRays16(first, second, step, out)) return;
  occludedFrom(first, step, out);
  occludedFrom(second, step, out + 8);
}

bool OcclusionGrid::startWalk(const glm::vec3& o, const glm::vec3& d, float step, float phase, Walk& w) const {
  if (!active_ || !(step > 0.0f)) return false;
  // The part of the ray inside the box of cells that add depth (samples elsewhere add none).
  float t0 = 0.0f, t1 = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) {
      if (o[a] < depthLo_[a] || o[a] > depthHi_[a]) return false;
      continue;
    }
    float ta = (depthLo_[a] - o[a]) / d[a], tb = (depthHi_[a] - o[a]) / d[a];
    if (ta > tb) std::swap(ta, tb);
    t0 = std::max(t0, ta);
    t1 = std::min(t1, tb);
  }
  if (!(t1 - t0 > 2.0f * step)) return false;

  // 3D DDA over the cells from t0 to t1. Each segment counts the lattice points at least a margin
  // inside it, so rounding in positions and cell boundaries never counts a sample twice or in the
  // wrong cell; samples left uncounted only make the bound weaker.
  const glm::vec3 start = o + d * t0;
  glm::ivec3 cell, dir;
  glm::vec3 tMax, tDelta;
  for (int a = 0; a < 3; ++a) {
    cell[a] = std::clamp(int(std::floor(start[a] / float(kCell))), 0, count_[a] - 1);
    dir[a] = d[a] > 0.0f ? 1 : -1;
    if (d[a] == 0.0f) {
      tMax[a] = std::numeric_limits<float>::infinity();
      tDelta[a] = 0.0f;
    } else {
      const float boundary = float((cell[a] + (d[a] > 0.0f ? 1 : 0)) * kCell);
      tMax[a] = (boundary - o[a]) / d[a];
      tDelta[a] = float(kCell) / std::fabs(d[a]);
    }
  }
  // The walk keeps its state in scalars and steps a linear cell index: indexing the vectors by a
  // run-time axis sent them through memory on every cell.
  w.t = t0, w.t1 = t1;
  w.exitX = tMax.x, w.exitY = tMax.y, w.exitZ = tMax.z;
  w.deltaX = tDelta.x, w.deltaY = tDelta.y, w.deltaZ = tDelta.z;
  w.phase = phase;
  w.cx = cell.x, w.cy = cell.y, w.cz = cell.z;
  w.dirX = dir.x, w.dirY = dir.y, w.dirZ = dir.z;
  w.index = (std::ptrdiff_t(cell.z) * count_.y + cell.y) * count_.x + cell.x;
  w.ray = RayLine{o.x, o.y, o.z, d.x, d.y, d.z};
  return true;
}

long OcclusionGrid::reachedAt(float sum, float depth, float first, float samples) const {
  // The fewest samples of this segment that reach the threshold, by the same float sum.
  float n = std::max(1.0f, std::ceil((threshold_ - sum) / depth));
  while (n < samples && sum + depth * n < threshold_) n += 1.0f;
  return long(first) + long(n);
}

long OcclusionGrid::walk(Walk w, float step) const {
  // t / step as a product: the margin (a fiftieth of a step) dwarfs the rounding difference.
  const float perStep = 1.0f / step;
  const float phase = w.phase;
  float sum = 0.0f, t = w.t;
  const float t1 = w.t1;
  float exitX = w.exitX, exitY = w.exitY, exitZ = w.exitZ;
  int cx = w.cx, cy = w.cy, cz = w.cz;
  const std::ptrdiff_t strideY = count_.x, strideZ = std::ptrdiff_t(count_.x) * count_.y;
  std::ptrdiff_t index = w.index;
  for (;;) {
    const int axis = exitX <= exitY ? (exitX <= exitZ ? 0 : 2) : (exitY <= exitZ ? 1 : 2);
    const float segmentEnd = std::min(axis == 0 ? exitX : axis == 1 ? exitY : exitZ, t1);
    const float depth = depth_[std::size_t(index)];
    if (depth > 0.0f) {
      const CountedRange counted = countedRange(t, segmentEnd, perStep, step, phase);
      const float first = counted.first, samples = counted.last - counted.first;
      if (samples > 0.0f) {
        if (sum + depth * samples >= threshold_) return reachedAt(sum, depth, first, samples);
        sum += depth * samples;
      }
    } else if (depth >= -kReachBase) {
      long reached;
      if (walkFine(w.ray, cx, cy, cz, blockOf(depth), t, segmentEnd, step, phase, sum, reached)) return reached;
    } else if (const int n = int(-depth - kReachBase); n >= 2) {
      // Every cell within n - 1 of this one adds nothing: leave that cube in one step, to the
      // cell and face times the one-cell steps would reach (up to rounding, which the margins
      // absorb). The ray leaves by the axis whose cube face comes first; along the others it
      // crosses the faces before that time.
      const float across = -depth - kReachBase, far = across - 1.0f;
      const float cubeX = exitX + far * w.deltaX, cubeY = exitY + far * w.deltaY, cubeZ = exitZ + far * w.deltaZ;
      const int leave = cubeX <= cubeY ? (cubeX <= cubeZ ? 0 : 2) : (cubeY <= cubeZ ? 1 : 2);
      const float tCube = leave == 0 ? cubeX : leave == 1 ? cubeY : cubeZ;
      auto crossed = [&](float exit, float delta, int axis) {
        return axis == leave ? across : exit < tCube ? std::min(std::ceil((tCube - exit) / delta), far) : 0.0f;
      };
      const float kx = crossed(exitX, w.deltaX, 0), ky = crossed(exitY, w.deltaY, 1), kz = crossed(exitZ, w.deltaZ, 2);
      if (tCube >= t1) return kNever;
      cx += int(kx) * w.dirX, cy += int(ky) * w.dirY, cz += int(kz) * w.dirZ;
      if (cx < 0 || cx >= count_.x || cy < 0 || cy >= count_.y || cz < 0 || cz >= count_.z) return kNever;
      index = (std::ptrdiff_t(cz) * count_.y + cy) * count_.x + cx;
      exitX += kx * w.deltaX, exitY += ky * w.deltaY, exitZ += kz * w.deltaZ;
      t = std::max(t, tCube);
      continue;
    }
    if (segmentEnd >= t1) return kNever;
    if (axis == 0) {
      cx += w.dirX;
      if (cx < 0 || cx >= count_.x) return kNever;
      index += w.dirX;
      exitX += w.deltaX;
    } else if (axis == 1) {
      cy += w.dirY;
      if (cy < 0 || cy >= count_.y) return kNever;
      index += w.dirY * strideY;
      exitY += w.deltaY;
    } else {
      cz += w.dirZ;
      if (cz < 0 || cz >= count_.z) return kNever;
      index += w.dirZ * strideZ;
      exitZ += w.deltaZ;
    }
    t = std::max(t, segmentEnd);
  }
}

bool OcclusionGrid::walkFine(const RayLine& ray, int cx, int cy, int cz, int block, float t, float end, float step,
                             float phase, float& sum, long& reached) const {
  // The samples this segment counts (the cell walk's rule: lattice points a margin inside), each
  // credited with the depth of the one-voxel cell it falls in. A sample the renderer places a
  // rounding away, across a voxel face, interpolates a value within rounding of the face's,
  // which both cells' ranges hold; the transfer table's one-entry widening covers the rest.
  const CountedRange counted = countedRange(t, end, 1.0f / step, step, phase);
  const std::uint8_t* code = fineCode_.data() + fineOffset_ + std::size_t(block) * kFine;
  const int bx = cx * kCell, by = cy * kCell, bz = cz * kCell;
  // Truncation is floor for positions >= 0; below 0 only cell 0 is near, and the clamp picks it.
  auto voxel = [](float p, int base) { return std::clamp(int(p) - base, 0, kCell - 1); };
  float total = sum;
  for (float k = counted.first; k < counted.last; k += 1.0f) {
    const float s = (k + phase) * step;
    const int fx = voxel(ray.ox + ray.dx * s, bx), fy = voxel(ray.oy + ray.dy * s, by), fz = voxel(ray.oz + ray.dz * s, bz);
    total += depthOfCode_[code[(fz * kCell + fy) * kCell + fx]];
    if (total >= threshold_) {
      sum = total;
      reached = long(k) + 1;
      return true;
    }
  }
  sum = total;
  return false;
}

}  // namespace kdswap
