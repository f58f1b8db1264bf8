// Ray casting of one brick. [Sections] ray setup (clip to the owned box, find the run of owned
// lattice indices) | tiles over the brick's screen rectangle. The sample loop itself is the ray
// march (ray_march.h: scalar reference or AVX2, equal bit for bit).
#include "core/render/ray_caster.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif
#include <oneapi/tbb/blocked_range2d.h>
#include <oneapi/tbb/combinable.h>
#include <oneapi/tbb/parallel_for.h>
#include <oneapi/tbb/task_arena.h>

#include "core/render/ray_setup.h"
#include "core/render/specular_table.h"
#include "core/render/trilinear.h"
#include "core/render/voxel_ray.h"
#include "core/util/check.h"
#include "core/util/clock.h"

#if defined(__GNUC__)
#define KDSWAP_ALWAYS_INLINE __attribute__((always_inline))
#else
#define KDSWAP_ALWAYS_INLINE
#endif

namespace kdswap {
namespace {

constexpr int kTileSize = 16;
constexpr std::size_t kBatch = 64;  //!< rays per call of the march
// Direction components smaller than this count as parallel to the box's faces: their reciprocal
// could overflow, and over any distance a ray can travel in a volume they move it by nothing.
constexpr float kTinyDirection = 1e-30f;

//! The run of owned lattice indices of a ray within [from, to]: its ends are where the exact
//! per-sample rule (p = o + d ((k + phase) step) inside [lo, hi)) first and last holds. The search
//! starts a lattice index or two outside the run, so the ends are found a few candidates at a time:
//! four per test with SSE (the same operations per lane as the scalar rule), not one per
//! mispredicted loop turn.
struct OwnedRun {
  glm::vec3 o, d, lo, hi;
  float phase, step;

  bool owned(long k) const {
    const glm::vec3 p = o + d * ((float(k) + phase) * step);
    return p.x >= lo.x && p.x < hi.x && p.y >= lo.y && p.y < hi.y && p.z >= lo.z && p.z < hi.z;
  }
#if defined(__SSE2__)
  //! Bit i: sample k + i is owned (k + 3 must fit an int: lattice indices along one ray do).
  int ownedFour(long k) const {
    const __m128 t = _mm_mul_ps(_mm_add_ps(_mm_cvtepi32_ps(_mm_add_epi32(_mm_set1_epi32(int(k)), _mm_setr_epi32(0, 1, 2, 3))),
                                           _mm_set1_ps(phase)),
                                _mm_set1_ps(step));
    const auto inside = [&](float oa, float da, float loa, float hia) {
      const __m128 p = _mm_add_ps(_mm_set1_ps(oa), _mm_mul_ps(_mm_set1_ps(da), t));
      return _mm_and_ps(_mm_cmpge_ps(p, _mm_set1_ps(loa)), _mm_cmplt_ps(p, _mm_set1_ps(hia)));
    };
    return _mm_movemask_ps(
        _mm_and_ps(_mm_and_ps(inside(o.x, d.x, lo.x, hi.x), inside(o.y, d.y, lo.y, hi.y)), inside(o.z, d.z, lo.z, hi.z)));
  }
#endif
  long first(long from, long to) const {
#if defined(__SSE2__)
    if (from >= 0 && to < long(std::numeric_limits<int>::max()) - 4)
      for (; from <= to; from += 4) {
        const int bits = ownedFour(from) & ((2 << std::min(3L, to - from)) - 1);
        if (bits) return from + __builtin_ctz(unsigned(bits));
      }
#endif
    while (from <= to && !owned(from)) ++from;
    return from;
  }
  long last(long from, long to) const {
#if defined(__SSE2__)
    if (from >= 0 && to < long(std::numeric_limits<int>::max()) - 4)
      for (; to >= from; to -= 4) {
        const long base = std::max(from, to - 3);
        const int bits = ownedFour(base) & ((2 << (to - base)) - 1);
        if (bits) return base + (31 - __builtin_clz(unsigned(bits)));
      }
#endif
    while (to >= from && !owned(to)) --to;
    return to;
  }
};

//! Set bits of an 8-bit mask, without a library call where the build's baseline has no popcnt.
constexpr int bitsSet8(int v) {
  v = v - ((v >> 1) & 0x55);
  v = (v & 0x33) + ((v >> 2) & 0x33);
  return (v + (v >> 4)) & 0x0F;
}
static_assert(bitsSet8(0) == 0 && bitsSet8(0xFF) == 8 && bitsSet8(0xA5) == 4 && bitsSet8(0x80) == 1);

}  // namespace

RayCaster::RayCaster(const Brick& brick, const TransferTable& table, const RenderSettings& settings, glm::vec2 valueRange,
                     const OcclusionMap* occlusion, std::shared_ptr<const EmptySpaceMap> emptySpace,
                     FrontTransmittance* front)
    : brick_(brick),
      table_(table),
      settings_(settings),
      scale_(normalisingScaleBias(valueRange).x),
      bias_(normalisingScaleBias(valueRange).y),
      emptySpace_(emptySpace ? std::move(emptySpace)
                             : std::make_shared<const EmptySpaceMap>(brick, table, scale_, bias_, settings.skipEmptySpace)),
      occlusion_(occlusion),
      front_(front),
      specular_(specularTableFor(settings.shininess)),
      march_{ShadingParameters{}, VoxelAddressing(brick)},
      // The SIMD march indexes voxels with 32-bit offsets.
      marchFunction_(brick.stored().count() < (std::int64_t(1) << 31) ? selectedMarchFunction() : &marchScalar) {
  KDSWAP_CHECK(emptySpace_->cellCount() == brick.cellCount());  // a map made for another brick
  ShadingParameters& shading = march_.shading;
  shading.table = &table_;
  const glm::vec2 stored = brick.storage().storedScaleBias(scale_, bias_);  // the shader reads stored values
  shading.scale = stored.x, shading.bias = stored.y;
  shading.shading = settings.shading;
  shading.ambient = settings.ambient, shading.diffuse = settings.diffuse, shading.specular = settings.specular;
  shading.specularTable = specular_->data();
  march_.storedLo = brick.stored().lo;
  march_.cellCodes = emptySpace_->marchCodes();
  march_.allVisible = emptySpace_->marchesEverySample();
  march_.anyUniform = emptySpace_->anyUniform();
  march_.cellLo = brick.cellLo();
  march_.cellShift = brick.cellShift();
  march_.cellCount = emptySpace_->cellCount();
  march_.lo = glm::vec3(brick.owned().lo), march_.hi = glm::vec3(brick.owned().hi);
  march_.stopTransmittance = std::max(0.0f, 1.0f - settings.earlyTermination);
}

void RayCaster::useMarch(MarchFunction march) {
  if (march) marchFunction_ = march;
}

Rgba RayCaster::castRay(const Ray& ray, RenderCounters& counters, long occludedFrom) const {
  if (!emptySpace_->anyVisible()) return Rgba{};
  RaySegment segment;
  if (!segmentFor(VoxelRay(ray, brick_.spacing(), settings_), -ray.direction, clipBox(), counters, occludedFrom, segment))
    return Rgba{};
  Rgba colour;
  marchFunction_(march_, &segment, 1, &colour, counters.samples);
  return colour;
}

RayCaster::ClipBox RayCaster::clipBox() const {
  const glm::vec3 hi(brick_.owned().hi);
  return ClipBox{emptySpace_->visibleLo(), emptySpace_->visibleHi(), std::max({std::fabs(hi.x), std::fabs(hi.y), std::fabs(hi.z)}) + 1.0f};
}

// Inlined into render's pixel loop: the ray then stays in registers instead of passing through
// memory once per pixel and brick.
KDSWAP_ALWAYS_INLINE inline bool RayCaster::segmentFor(const VoxelRay& voxelRay, const glm::vec3& toLight, const ClipBox& clip,
                                                       RenderCounters& counters, long occludedFrom, RaySegment& segment) const {
  const glm::vec3 o = voxelRay.origin;
  const glm::vec3 d = voxelRay.direction;
  // 1 / d: used only where d != 0 (and not so small that it overflows).
  const glm::vec3 inverse = 1.0f / d;

  // Clip to the visible part of the owned box, grown by more than the rounding error of p = o + d * t, to bound the
  // lattice indices; membership is then decided per sample on the computed p. The margin matters
  // for rays nearly parallel to a face, where a tiny error in p is a large error in t. The bound
  // multiplies by 1 / d (a rounding more than dividing): the index slack below absorbs that.
  const float magnitude = std::max({std::fabs(o.x), std::fabs(o.y), std::fabs(o.z)}) + clip.hiMagnitude;
  const float margin = 4e-6f * magnitude;
  float tNear = 0.0f, tFar = std::numeric_limits<float>::max();
  for (int a = 0; a < 3; ++a) {
    if (!(std::fabs(d[a]) >= kTinyDirection)) {  // parallel to this face, as far as the box can tell
      if (o[a] < clip.lo[a] - margin || o[a] > clip.hi[a] + margin) return false;
      continue;
    }
    float t1 = (clip.lo[a] - margin - o[a]) * inverse[a], t2 = (clip.hi[a] + margin - o[a]) * inverse[a];
    if (t1 > t2) std::swap(t1, t2);
    tNear = std::max(tNear, t1);
    tFar = std::min(tFar, t2);
  }
  if (tNear > tFar) return false;
  return segmentFromClip(o, d, inverse, voxelRay.step, voxelRay.phase, voxelRay.inverseStep,
                         std::floor(tNear * voxelRay.inverseStep - voxelRay.phase),
                         std::ceil(tFar * voxelRay.inverseStep - voxelRay.phase), toLight, counters, occludedFrom, segment);
}

KDSWAP_ALWAYS_INLINE inline bool RayCaster::segmentFromClip(const glm::vec3& o, const glm::vec3& d, const glm::vec3& inverse,
                                                            float step, float phase, float inverseStep, float firstIndex,
                                                            float lastIndex, const glm::vec3& toLight,
                                                            RenderCounters& counters, long occludedFrom,
                                                            RaySegment& segment, int nearOwned, int farOwned) const {
  ++counters.rays;
  const glm::vec3 lo(brick_.owned().lo), hi(brick_.owned().hi);
  // One lattice index of slack on each side: the ownership test below is the exact rule.
  const long kBegin = std::max(0L, long(firstIndex) - 1);
  if (kBegin >= occludedFrom) {  // the single-node ray ends before this brick
    ++counters.occluded;
    return false;
  }
  const long kEndUnclipped = long(lastIndex) + 1;
  const long kEnd = std::min(kEndUnclipped, occludedFrom - 1);

  // The owned samples form one run of lattice indices: each coordinate of p = o + d t is monotone
  // in k (rounding is monotone), so membership of the half-open box [lo, hi) is an interval. Its
  // ends are found with the exact per-sample rule (each lattice point belongs to exactly one
  // brick); the walk between them needs no test.
  const OwnedRun run{o, d, lo, hi, phase, step};
  // With the first four candidates at an end already tested (eight rays at once), the search
  // starts past them: where it would have tested exactly those four, it finds the same index.
  long kFirst;
  if (nearOwned >= 0 && kEnd - kBegin >= 3)
    kFirst = nearOwned != 0 ? kBegin + __builtin_ctz(unsigned(nearOwned)) : run.first(kBegin + 4, kEnd);
  else
    kFirst = run.first(kBegin, kEnd);
  long kLast;
  if (kFirst > kEnd)
    kLast = kEnd;
  else if (farOwned >= 0 && kEnd == kEndUnclipped && kEnd - 3 >= kFirst)
    kLast = farOwned != 0 ? kEnd - 3 + (31 - __builtin_clz(unsigned(farOwned))) : run.last(kFirst, kEnd - 4);
  else
    kLast = run.last(kFirst, kEnd);

  if (kFirst > kLast) return false;  // no owned sample (the march would take none either)
  // The light is at the eye.
  // Field by field into the batch's slot: a temporary RaySegment copied in (as `segment =
  // RaySegment{...}` compiles) reads back 16-byte pieces of narrower stores just made, which the
  // store buffer cannot forward (a stall per ray: 14% of a 64-node CT head frame's set-up).
  segment.origin = o, segment.direction = d, segment.inverseDirection = inverse;
  segment.step = step, segment.phase = phase;
  segment.first = kFirst, segment.last = kLast;
  segment.toLight = toLight;
  segment.inverseStep = inverseStep;
  segment.stopTransmittance = -1.0f;
  return true;
}

long RayCaster::firstLatticeIndexBound(const Camera& camera, float step) const {
  // Every ray's t at a point p is at least dot(p - eye, forward): the distance itself for a
  // perspective ray (unit direction), exactly it for an orthographic one (origins lie in the plane
  // through the eye). Over a box the dot product is least at a corner. The box is grown by a voxel
  // and the index lowered by three for the clip's margins and rounding: a weaker bound is still a bound.
  const glm::vec3 spacing = brick_.spacing();
  const glm::vec3 lo = (emptySpace_->visibleLo() - 1.0f) * spacing, hi = (emptySpace_->visibleHi() + 1.0f) * spacing;
  const glm::vec3 toLo = lo - camera.eye(), toHi = hi - camera.eye(), f = camera.forward();
  const float tLow = std::min(toLo.x * f.x, toHi.x * f.x) + std::min(toLo.y * f.y, toHi.y * f.y) +
                     std::min(toLo.z * f.z, toHi.z * f.z);
  if (!(tLow > 0.0f) || !(step > 0.0f)) return 0;  // the eye is at or inside the box's slab: no bound
  // Rounding of the t values compared with: a relative slack far above float error.
  const double index = double(tLow) * (1.0 - 1e-4) / double(step) - 1.0;  // phase < 1
  return index >= double(std::numeric_limits<long>::max() / 2) ? 0 : std::max(0L, long(std::floor(index)) - 3);
}

Rect RayCaster::screenRect(const EmptySpaceMap& emptySpace, const glm::vec3& spacing, const Camera& camera) {
  if (!emptySpace.anyVisible()) return Rect{};
  return camera.projectBox(emptySpace.visibleLo() * spacing, emptySpace.visibleHi() * spacing);
}

Image RayCaster::render(const Camera& camera, RenderCounters& counters, Rect* content) const {
  if (content) *content = Rect{};
  const Rect rect = screenRect(camera);  // empty when nothing in the brick is visible
  Image image(rect);
  if (rect.empty()) return image;
  const CellCoverage cover = coverage(camera);
  tbb::combinable<RenderCounters> perThread;
  tbb::combinable<Rect> contentPerThread;
  // Isolation: a thread waiting here must not pick up another node's task (it could suspend on
  // this thread's stack and would inflate this node's timings).
  tbb::this_task_arena::isolate([&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(rect.y, rect.bottom(), kTileSize, rect.x, rect.right(), kTileSize),
                      [&](const tbb::blocked_range2d<int>& tile) {
                        const int x = tile.cols().begin(), y = tile.rows().begin();
                        const Rect region{x, y, tile.cols().end() - x, tile.rows().end() - y};
                        Rect& bounds = contentPerThread.local();
                        bounds = bounds.unite(renderRegion(camera, region, image, perThread.local(), &cover));
                      });
  });
  if (content) contentPerThread.combine_each([&](const Rect& r) { *content = content->unite(r); });
  perThread.combine_each([&](const RenderCounters& c) { counters += c; });
  return image;
}

Rect RayCaster::screenRect(const Camera& camera) const {
  return emptySpace_->anyVisible() ? screenRect(*emptySpace_, brick_.spacing(), camera) : Rect{};
}

CellCoverage RayCaster::coverage(const Camera& camera) const {
  return CellCoverage(brick_, *emptySpace_, camera, screenRect(camera));
}

Rect RayCaster::renderRegion(const Camera& camera, const Rect& region, Image& image, RenderCounters& local,
                             const CellCoverage* coverage) const {
  KDSWAP_CHECK(image.rect().contains(region));
  if (region.empty() || !emptySpace_->anyVisible()) return Rect{};
  const double start = nowSeconds();
  const glm::vec3 spacing = brick_.spacing();
  const ClipBox clip = clipBox();
  const VoxelRay::Scale scale(spacing, settings_);
  const long firstPossible = occlusion_ ? firstLatticeIndexBound(camera, scale.step) : 0;
  const bool simdSetup = raySetup8Available();
  const RaySetupConstants setup{camera.basis(),     scale.inverseSpacing, scale.inverseStep,
                                scale.jitter,       scale.phaseShift,     clip.lo,
                                clip.hi,            clip.hiMagnitude,     glm::vec3(brick_.owned().lo),
                                glm::vec3(brick_.owned().hi), scale.step};
  // The region's rays that reach owned samples, marched in one batch; other pixels stay clear.
  std::array<RaySegment, kBatch> segments;
  std::array<Rgba, kBatch> colours;
  std::array<Rgba*, kBatch> pixels;
  std::array<float*, kBatch> light;  // waves: the light in front of each queued pixel
  std::array<int, kBatch> xs, ys;    // each queued pixel's position, for the content bounds
  int x0Content = region.right(), y0Content = region.bottom(), x1Content = region.x - 1, y1Content = region.y - 1;
  std::size_t pending = 0;
  RayLanes8 lanes;
  const auto march = [&] {
    marchFunction_(march_, segments.data(), pending, colours.data(), local.samples);
    for (std::size_t i = 0; i < pending; ++i) *pixels[i] = colours[i];
    // Content bounds: pixels with opacity above 0, as Image::opaqueBounds tests (an unqueued
    // pixel stays clear). Without a branch: a third of a sparse volume's rays leave nothing.
    for (std::size_t i = 0; i < pending; ++i) {
      const bool on = colours[i].a > 0.0f;
      x0Content = std::min(x0Content, on ? xs[i] : x0Content), x1Content = std::max(x1Content, on ? xs[i] : x1Content);
      y0Content = std::min(y0Content, on ? ys[i] : y0Content), y1Content = std::max(y1Content, on ? ys[i] : y1Content);
    }
    // Waves: this brick's own transmittance dims the light it leaves for the bricks behind
    // (as addBehind would after the brick, without a second pass over its rectangle;
    // pixels without a ray have opacity 0 and would keep their light exactly).
    if (front_)
      for (std::size_t i = 0; i < pending; ++i) *light[i] *= 1.0f - colours[i].a;
    pending = 0;
  };
  // segments[pending] now holds pixel (x, y)'s segment: queue it for the next batch.
  const auto queue = [&](int x, int y) {
    // Waves: T_front * T_own <= stop  <=>  T_own <= stop / T_front (T_front > stop here).
    if (front_) {
      light[pending] = &front_->lightAt(x, y);
      segments[pending].stopTransmittance = march_.stopTransmittance / *light[pending];
    }
    pixels[pending] = &image.at(x, y);
    xs[pending] = x, ys[pending] = y;
    if (++pending == kBatch) march();
  };
  // Runs of eight pixels: their rays are set up together where AVX2 allows (ray_setup.h). The
  // region is walked in columns one run wide, row by row down each: a batch of 64 rays is then an
  // 8 x 8 block of pixels, whose rays cross much the same voxels, rather than two rows of a
  // 32-pixel piece (the phantom at P = 64 with waves 1-3% faster).
  for (int x0 = region.x; x0 < region.right(); x0 += 8)
    for (int y = region.y; y < region.bottom(); ++y) {
      const int n = std::min(8, region.right() - x0);
      // Pixels whose rays can meet no visible cell take no ray: not set up, not counted.
      const int covered = ((1 << n) - 1) & (coverage ? coverage->eight(x0, y) : 0xFF);
      if (covered == 0) continue;
      long occludedFrom[8];
      int live = 0;  // bit j: pixel x0 + j needs its ray set up
      if (occlusion_ == nullptr) {
        // Only the light in front (waves) can stop a pixel's ray before this brick: eight
        // pixels tested at once, no branch per pixel (a 64-node frame tests each pixel
        // once per brick whose rectangle holds it).
        const int spent = (front_ ? front_->spentIn(x0, y, n, march_.stopTransmittance) : 0) & covered;
        live = covered & ~spent;
        const int stopped = bitsSet8(spent);
        local.rays += std::uint64_t(stopped), local.occluded += std::uint64_t(stopped);
        for (int j = 0; j < 8; ++j) occludedFrom[j] = OcclusionGrid::kNever;
      } else {
        for (int j = 0; j < n; ++j) {
          if (!(covered >> j & 1)) continue;
          occludedFrom[j] = occlusion_->occludedFrom(x0 + j, y);
          if (front_ && front_->at(x0 + j, y) <= march_.stopTransmittance) occludedFrom[j] = 0;  // stopped in front
          if (occludedFrom[j] <= firstPossible)  // ends before the brick: no ray to set up
            ++local.rays, ++local.occluded;
          else
            live |= 1 << j;
        }
      }
      if (live == 0) continue;
      if (simdSetup) {
        setupRays8(setup, x0, y, lanes);
        for (int bits = live & lanes.crosses; bits != 0; bits &= bits - 1) {
          const int j = __builtin_ctz(bits);
          const glm::vec3 o(lanes.ox[j], lanes.oy[j], lanes.oz[j]), d(lanes.dx[j], lanes.dy[j], lanes.dz[j]);
          const bool window = (lanes.windows >> j) & 1;
          if (segmentFromClip(o, d, glm::vec3(lanes.ix[j], lanes.iy[j], lanes.iz[j]), scale.step, lanes.phase[j],
                              scale.inverseStep, lanes.firstIndex[j], lanes.lastIndex[j],
                              -glm::vec3(lanes.wx[j], lanes.wy[j], lanes.wz[j]), local, occludedFrom[j],
                              segments[pending], window ? lanes.nearOwned[j] : -1, window ? lanes.farOwned[j] : -1))
            queue(x0 + j, y);
        }
        continue;
      }
      for (int bits = live; bits != 0; bits &= bits - 1) {
        const int j = __builtin_ctz(bits);
        const Ray ray = camera.ray(x0 + j, y);
        if (segmentFor(VoxelRay(ray, scale), -ray.direction, clip, local, occludedFrom[j], segments[pending]))
          queue(x0 + j, y);
      }
    }
  if (pending > 0) march();
  local.seconds += nowSeconds() - start;
  if (x1Content < x0Content) return Rect{};
  return Rect{x0Content, y0Content, x1Content - x0Content + 1, y1Content - y0Content + 1};
}

}  // namespace kdswap
