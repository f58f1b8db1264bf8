// Occlusion culling: the replicated cell summary, per-frame optical depths, and a march through the
// cells in front of a brick (3D DDA) that bounds the opacity the single-node ray has gathered.
#include "core/render/occlusion_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>

namespace kdswap {
namespace {

constexpr int kCell = 1 << CellRangeGrid::kShift;
// Float accumulation of "over" can fall short of the exact opacity product by about one rounding
// per sample; this much opacity margin covers thousands of samples.
constexpr float kOpacityMargin = 1e-3f;

}  // namespace

CellRangeGrid CellRangeGrid::fromBricks(const glm::ivec3& dims, const std::vector<const Brick*>& bricks) {
  CellRangeGrid g;
  g.dims = dims;
  g.count = glm::max((dims - 2) / kCell + 1, glm::ivec3(1));  // samples' floors lie in [0, dims - 2]
  g.ranges.assign(std::size_t(g.count.x) * g.count.y * g.count.z,
                  glm::vec2(std::numeric_limits<float>::max(), std::numeric_limits<float>::lowest()));
  for (const Brick* b : bricks)
    if (!b->empty()) b->widenCellRanges(kShift, glm::ivec3(0), g.count, g.ranges);
  return g;
}

OcclusionGrid::OcclusionGrid(const CellRangeGrid& cells, const TransferTable& table, float scale, float bias,
                             float stopAt)
    : count_(cells.count), domainHi_(glm::vec3(cells.dims - 1)) {
  if (!(stopAt > 0.0f && stopAt + kOpacityMargin < 1.0f) || cells.ranges.empty()) return;
  active_ = true;
  threshold_ = float(-std::log1p(-double(stopAt + kOpacityMargin)));
  depth_.resize(cells.ranges.size());
  for (std::size_t i = 0; i < depth_.size(); ++i) {
    const glm::vec2 r = cells.ranges[i];
    const float a = r.x <= r.y ? table.minAlpha(r.x * scale + bias, r.y * scale + bias) : 0.0f;
    // Rounded down, so the sum stays a lower bound of the optical depth.
    depth_[i] = a <= 0.0f ? 0.0f : (a >= 1.0f ? 1e6f : float(-std::log1p(-double(a)) * (1.0 - 1e-6)));
  }
  // The box of cells that add depth: rays march only through it, since nothing outside counts.
  // With none (a translucent transfer function), nothing can be culled: the grid is inactive and
  // the per-frame map costs nothing.
  glm::ivec3 lo(std::numeric_limits<int>::max()), hi(-1);
  for (int z = 0; z < count_.z; ++z)
    for (int y = 0; y < count_.y; ++y)
      for (int x = 0; x < count_.x; ++x)
        if (depth_[(std::size_t(z) * count_.y + y) * count_.x + x] > 0.0f) {
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
      const float margin = 0.02f * step + 1e-6f * std::fabs(segmentEnd);
      const float first = std::ceil((t + margin) * perStep - phase);  // first lattice index counted here
      const float samples = std::ceil((segmentEnd - margin) * perStep - phase) - first;
      if (samples > 0.0f) {
        if (sum + depth * samples >= threshold_) return reachedAt(sum, depth, first, samples);
        sum += depth * samples;
      }
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

}  // namespace kdswap
