// Ray casting of one brick. [Sections] ray setup (clip to the owned box) | sample loop
// (trilinear value and gradient, transfer function, Phong, front-to-back over, early termination)
// | tiles over the brick's screen rectangle.
#include "core/render/ray_caster.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <oneapi/tbb/blocked_range2d.h>
#include <oneapi/tbb/combinable.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "core/render/trilinear.h"
#include "core/render/voxel_ray.h"
#include "core/util/clock.h"

namespace kdswap {
namespace {

constexpr int kTileSize = 16;
constexpr int kSpecularEntries = 256;

}  // namespace

RayCaster::RayCaster(const Brick& brick, const TransferTable& table, const RenderSettings& settings, glm::vec2 valueRange,
                     const OcclusionMap* occlusion)
    : brick_(brick),
      table_(table),
      settings_(settings),
      scale_(normalisingScaleBias(valueRange).x),
      bias_(normalisingScaleBias(valueRange).y),
      emptySpace_(brick, table, scale_, bias_, settings.skipEmptySpace),
      occlusion_(occlusion) {
  specular_.resize(kSpecularEntries + 1);
  for (int i = 0; i <= kSpecularEntries; ++i) specular_[i] = std::pow(float(i) / kSpecularEntries, settings.shininess);
}

Rgba RayCaster::castRay(const Ray& ray, RenderCounters& counters, long occludedFrom) const {
  if (!emptySpace_.anyVisible()) return Rgba{};
  // Ray in voxel coordinates: every brick computes these identically for the same pixel.
  const VoxelRay voxelRay(ray, brick_.spacing(), settings_);
  const glm::vec3 o = voxelRay.origin;
  const glm::vec3 d = voxelRay.direction;
  const glm::vec3 lo(brick_.owned().lo), hi(brick_.owned().hi);
  const glm::vec3 clipLo = emptySpace_.visibleLo(), clipHi = emptySpace_.visibleHi();

  // Clip to the visible part of the owned box, grown by more than the rounding error of p = o + d * t, to bound the
  // lattice indices; membership is then decided per sample on the computed p. The margin matters
  // for rays nearly parallel to a face, where a tiny error in p is a large error in t.
  const float magnitude = std::max({std::fabs(o.x), std::fabs(o.y), std::fabs(o.z)}) +
                          std::max({std::fabs(hi.x), std::fabs(hi.y), std::fabs(hi.z)}) + 1.0f;
  const float margin = 4e-6f * magnitude;
  float tNear = 0.0f, tFar = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (d[a] == 0.0f) {
      if (o[a] < clipLo[a] - margin || o[a] > clipHi[a] + margin) return Rgba{};
      continue;
    }
    float t1 = (clipLo[a] - margin - o[a]) / d[a], t2 = (clipHi[a] + margin - o[a]) / d[a];
    if (t1 > t2) std::swap(t1, t2);
    tNear = std::max(tNear, t1);
    tFar = std::min(tFar, t2);
  }
  if (tNear > tFar) return Rgba{};
  ++counters.rays;

  const float step = voxelRay.step;
  const float phase = voxelRay.phase;
  // One lattice index of slack on each side: the ownership test below is the exact rule.
  const long kBegin = std::max(0L, long(std::floor(tNear / step - phase)) - 1);
  if (kBegin >= occludedFrom) {  // the single-node ray ends before this brick
    ++counters.occluded;
    return Rgba{};
  }
  const long kEnd = std::min(long(std::ceil(tFar / step - phase)) + 1, occludedFrom - 1);

  // The owned samples form one run of lattice indices: each coordinate of p = o + d t is monotone
  // in k (rounding is monotone), so membership of the half-open box [lo, hi) is an interval. Its
  // ends are found with the exact per-sample rule (each lattice point belongs to exactly one
  // brick); the walk between them needs no test.
  const auto samplePoint = [&](long k) { return o + d * ((float(k) + phase) * step); };
  const auto owned = [&](const glm::vec3& p) {
    return p.x >= lo.x && p.x < hi.x && p.y >= lo.y && p.y < hi.y && p.z >= lo.z && p.z < hi.z;
  };
  long kFirst = kBegin, kLast = kEnd;
  while (kFirst <= kLast && !owned(samplePoint(kFirst))) ++kFirst;
  while (kLast >= kFirst && !owned(samplePoint(kLast))) --kLast;

  const glm::vec3 toLight = -ray.direction;  // light at the eye
  const bool shading = settings_.shading;
  const float ka = settings_.ambient, kd = settings_.diffuse, ks = settings_.specular;
  const float stopAt = settings_.earlyTermination;
  const float scale = scale_, bias = bias_;
  const TransferTable& table = table_;
  const EmptySpaceMap& emptySpace = emptySpace_;
  const VoxelAddressing voxels(brick_);

  const glm::ivec3 cellLo = brick_.cellLo();
  const glm::vec3 inverseD = 1.0f / d;  // used only on axes with d != 0
  const float* specular = specular_.data();
  float r = 0, g = 0, b = 0, alpha = 0;
  std::uint64_t samples = 0;
  std::size_t lastJumpedCell = std::size_t(-1);
  for (long k = kFirst; k <= kLast; ++k) {
    const glm::vec3 p = samplePoint(k);
    const glm::ivec3 floor(int(p.x), int(p.y), int(p.z));  // p >= 0: truncation is floor
    const glm::ivec3 c = (floor >> Brick::kCellShift) - cellLo;
    const std::size_t cellIndex = emptySpace.cellIndex(c);
    if (const int reach = emptySpace.reach(cellIndex)) {
      if (cellIndex == lastJumpedCell) continue;  // landed just short of the exit: step on
      lastJumpedCell = cellIndex;
      // Jump to just before the ray leaves the invisible cube of cells around this one; samples
      // there are all invisible (a cube is convex: the ray stays inside it until it exits).
      const glm::vec3 cLo = glm::max(glm::vec3((c + cellLo - (reach - 1)) << Brick::kCellShift), lo);
      const glm::vec3 cHi = glm::min(glm::vec3((c + cellLo + reach) << Brick::kCellShift), hi);
      float tExit = std::numeric_limits<float>::max();
      for (int a = 0; a < 3; ++a)
        if (d[a] != 0.0f) tExit = std::min(tExit, ((d[a] > 0.0f ? cHi[a] : cLo[a]) - o[a]) * inverseD[a]);
      const long resume = long(std::floor(tExit / step - phase)) - 1;  // one early: rounding-safe
      if (resume > k) k = resume;
      continue;
    }
    ++samples;
    const TrilinearCell cell(voxels, p, floor);
    const TrilinearCell::Lanes both = cell.interpolate();
    const float value = both[0];
    const glm::vec4 tf = table.lookup(value * scale + bias);
    if (tf.a <= 0.0f) continue;
    glm::vec3 colour(tf.r, tf.g, tf.b);
    if (shading) {
      const glm::vec3 grad(both[1], both[2], both[3]);
      const float len2 = glm::dot(grad, grad);
      float lambert = 1.0f;  // no gradient (flat region): lit as if facing the light
      if (len2 > 0.0f) lambert = std::fabs(glm::dot(grad, toLight)) / std::sqrt(len2);
      const float fs = std::min(lambert, 1.0f) * float(kSpecularEntries);
      const int is = std::min(int(fs), kSpecularEntries - 1);
      const float highlight = ks * (specular[is] + (fs - float(is)) * (specular[is + 1] - specular[is]));
      colour = glm::min(colour * (ka + kd * lambert) + highlight, glm::vec3(1.0f));
    }
    const float w = (1.0f - alpha) * tf.a;
    r += w * colour.r;
    g += w * colour.g;
    b += w * colour.b;
    alpha += w;
    if (alpha >= stopAt) break;  // early ray termination
  }
  counters.samples += samples;
  return Rgba{r, g, b, alpha};
}

Image RayCaster::render(const Camera& camera, RenderCounters& counters) const {
  if (!emptySpace_.anyVisible()) return Image{};
  const glm::vec3 spacing = brick_.spacing();
  const Rect rect = camera.projectBox(emptySpace_.visibleLo() * spacing, emptySpace_.visibleHi() * spacing);
  Image image(rect);
  if (rect.empty()) return image;
  tbb::combinable<RenderCounters> perThread;
  // Isolation: a thread waiting here must not pick up another node's task (it could suspend on
  // this thread's stack and would inflate this node's timings).
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(
        tbb::blocked_range2d<int>(rect.y, rect.bottom(), kTileSize, rect.x, rect.right(), kTileSize),
        [&](const tbb::blocked_range2d<int>& tile) {
          const double start = nowSeconds();
          RenderCounters& local = perThread.local();
          for (int y = tile.rows().begin(); y < tile.rows().end(); ++y)
            for (int x = tile.cols().begin(); x < tile.cols().end(); ++x)
              image.at(x, y) =
                  castRay(camera.ray(x, y), local, occlusion_ ? occlusion_->occludedFrom(x, y) : OcclusionGrid::kNever);
          local.seconds += nowSeconds() - start;
        });
  });
  perThread.combine_each([&](const RenderCounters& c) {
    counters.rays += c.rays;
    counters.samples += c.samples;
    counters.occluded += c.occluded;
    counters.seconds += c.seconds;
  });
  return image;
}

}  // namespace kdswap
