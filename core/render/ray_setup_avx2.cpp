// AVX2 ray setup for eight pixels of a row (ray_setup.h). Every step names the scalar expression it
// repeats; the order of operations is theirs, so each lane rounds as the scalar code does.
#include "core/render/ray_setup.h"

#include <limits>

#include "core/util/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

namespace kdswap {
namespace {

#define KDSWAP_AVX2 __attribute__((target("avx2")))

KDSWAP_AVX2 inline __m256 splat(float v) { return _mm256_set1_ps(v); }
KDSWAP_AVX2 inline __m256 absolute(__m256 v) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), v); }

//! Camera::pixelOffset of pixels (px, py): their cells of the blue-noise tile, gathered.
KDSWAP_AVX2 inline __m256 pixelOffsets(__m256i px, int py) {
  constexpr int mask = BlueNoiseTile::kSide - 1;
  const __m256i cell = _mm256_add_epi32(_mm256_and_si256(px, _mm256_set1_epi32(mask)),
                                        _mm256_set1_epi32((py & mask) * BlueNoiseTile::kSide));
  return _mm256_i32gather_ps(BlueNoiseTile::instance().data(), cell, 4);
}

//! One axis of RayCaster::segmentFor's clip: parallel lanes (|d| < kTinyDirection) are rejected
//! when outside the slab and otherwise left alone; the others narrow [tNear, tFar].
KDSWAP_AVX2 inline void clipAxis(__m256 o, __m256 d, __m256 inverse, float lo, float hi, __m256 margin,
                                 __m256& tNear, __m256& tFar, __m256& rejected) {
  const __m256 lower = _mm256_sub_ps(splat(lo), margin), upper = _mm256_add_ps(splat(hi), margin);
  const __m256 parallel = _mm256_cmp_ps(absolute(d), splat(1e-30f), _CMP_NGE_UQ);  // !(|d| >= tiny)
  const __m256 outside = _mm256_or_ps(_mm256_cmp_ps(o, lower, _CMP_LT_OQ), _mm256_cmp_ps(o, upper, _CMP_GT_OQ));
  rejected = _mm256_or_ps(rejected, _mm256_and_ps(parallel, outside));
  const __m256 t1 = _mm256_mul_ps(_mm256_sub_ps(lower, o), inverse), t2 = _mm256_mul_ps(_mm256_sub_ps(upper, o), inverse);
  const __m256 swap = _mm256_cmp_ps(t1, t2, _CMP_GT_OQ);  // if (t1 > t2) std::swap(t1, t2)
  const __m256 near = _mm256_blendv_ps(t1, t2, swap), far = _mm256_blendv_ps(t2, t1, swap);
  // tNear = std::max(tNear, near): near where tNear < near; tFar = std::min(tFar, far): far where far < tFar.
  const __m256 raiseNear = _mm256_andnot_ps(parallel, _mm256_cmp_ps(tNear, near, _CMP_LT_OQ));
  const __m256 lowerFar = _mm256_andnot_ps(parallel, _mm256_cmp_ps(far, tFar, _CMP_LT_OQ));
  tNear = _mm256_blendv_ps(tNear, near, raiseNear);
  tFar = _mm256_blendv_ps(tFar, far, lowerFar);
}

//! lo <= v < hi, per lane.
KDSWAP_AVX2 inline __m256 within(__m256 v, float lo, float hi) {
  return _mm256_and_ps(_mm256_cmp_ps(v, splat(lo), _CMP_GE_OQ), _mm256_cmp_ps(v, splat(hi), _CMP_LT_OQ));
}

//! Bit i: lattice index k + i (i = 0..3) lies in the owned box, by RayCaster's per-sample rule:
//! t = (float(k + i) + phase) * step, p = o + d t, lo <= p < hi on every axis.
KDSWAP_AVX2 inline __m256i ownedWindow(__m256i k, __m256 phase, const RaySetupConstants& c, __m256 ox, __m256 oy,
                                       __m256 oz, __m256 dx, __m256 dy, __m256 dz) {
  __m256i bits = _mm256_setzero_si256();
  for (int i = 0; i < 4; ++i) {
    const __m256 t = _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(_mm256_add_epi32(k, _mm256_set1_epi32(i))), phase),
                                   splat(c.step));
    const __m256 px = _mm256_add_ps(ox, _mm256_mul_ps(dx, t)), py = _mm256_add_ps(oy, _mm256_mul_ps(dy, t)),
                 pz = _mm256_add_ps(oz, _mm256_mul_ps(dz, t));
    const __m256i inside = _mm256_castps_si256(_mm256_and_ps(
        _mm256_and_ps(within(px, c.ownedLo.x, c.ownedHi.x), within(py, c.ownedLo.y, c.ownedHi.y)),
        within(pz, c.ownedLo.z, c.ownedHi.z)));
    bits = _mm256_or_si256(bits, _mm256_and_si256(inside, _mm256_set1_epi32(1 << i)));
  }
  return bits;
}

//! Camera::ray and VoxelRay of pixels x0 .. x0 + 7 of row y, in lanes.
struct Rays {
  __m256 ox, oy, oz, dx, dy, dz, wdx, wdy, wdz, phase;
};

KDSWAP_AVX2 inline Rays raysOf(const RaySetupConstants& c, int x0, int y) {
  const Camera::Basis& b = c.camera;
  // Camera::ray: sx per lane, sy for the row.
  const __m256i px = _mm256_add_epi32(_mm256_set1_epi32(x0), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
  const __m256 sx = _mm256_mul_ps(
      _mm256_mul_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(px), splat(0.5f)), splat(b.twoOverWidth)),
                                  splat(1.0f)),
                    splat(b.aspect)),
      splat(b.halfHeight));
  const float sy = (1.0f - (float(y) + 0.5f) * b.twoOverHeight) * b.halfHeight;
  __m256 wox, woy, woz, wdx, wdy, wdz;  // world origin and direction
  if (b.orthographic) {  // eye_ + sx * right_ + sy * up_, forward_
    wox = _mm256_add_ps(_mm256_add_ps(splat(b.eye.x), _mm256_mul_ps(sx, splat(b.right.x))), splat(sy * b.up.x));
    woy = _mm256_add_ps(_mm256_add_ps(splat(b.eye.y), _mm256_mul_ps(sx, splat(b.right.y))), splat(sy * b.up.y));
    woz = _mm256_add_ps(_mm256_add_ps(splat(b.eye.z), _mm256_mul_ps(sx, splat(b.right.z))), splat(sy * b.up.z));
    wdx = splat(b.forward.x), wdy = splat(b.forward.y), wdz = splat(b.forward.z);
  } else {  // eye_, glm::normalize(forward_ + sx * right_ + sy * up_) = v * (1 / sqrt(dot(v, v)))
    wox = splat(b.eye.x), woy = splat(b.eye.y), woz = splat(b.eye.z);
    const __m256 vx = _mm256_add_ps(_mm256_add_ps(splat(b.forward.x), _mm256_mul_ps(sx, splat(b.right.x))), splat(sy * b.up.x));
    const __m256 vy = _mm256_add_ps(_mm256_add_ps(splat(b.forward.y), _mm256_mul_ps(sx, splat(b.right.y))), splat(sy * b.up.y));
    const __m256 vz = _mm256_add_ps(_mm256_add_ps(splat(b.forward.z), _mm256_mul_ps(sx, splat(b.right.z))), splat(sy * b.up.z));
    const __m256 len2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(vx, vx), _mm256_mul_ps(vy, vy)), _mm256_mul_ps(vz, vz));
    const __m256 inverseLength = _mm256_div_ps(splat(1.0f), _mm256_sqrt_ps(len2));
    wdx = _mm256_mul_ps(vx, inverseLength), wdy = _mm256_mul_ps(vy, inverseLength), wdz = _mm256_mul_ps(vz, inverseLength);
  }
  // VoxelRay: world -> voxel coordinates; the phase is the pixel's offset when jittering.
  const __m256 ox = _mm256_mul_ps(wox, splat(c.inverseSpacing.x)), oy = _mm256_mul_ps(woy, splat(c.inverseSpacing.y)),
               oz = _mm256_mul_ps(woz, splat(c.inverseSpacing.z));
  const __m256 dx = _mm256_mul_ps(wdx, splat(c.inverseSpacing.x)), dy = _mm256_mul_ps(wdy, splat(c.inverseSpacing.y)),
               dz = _mm256_mul_ps(wdz, splat(c.inverseSpacing.z));
  // latticePhase: offset + shift, less 1 where that reaches 1.
  const __m256 sum = _mm256_add_ps(c.jitter ? pixelOffsets(px, y) : _mm256_setzero_ps(), splat(c.phaseShift));
  const __m256 phase =
      _mm256_sub_ps(sum, _mm256_and_ps(_mm256_cmp_ps(sum, splat(1.0f), _CMP_GE_OQ), splat(1.0f)));
  return Rays{ox, oy, oz, dx, dy, dz, wdx, wdy, wdz, phase};
}

KDSWAP_AVX2 void voxelRays8Avx2(const RaySetupConstants& c, int x0, int y, VoxelRays8& out) {
  const Rays r = raysOf(c, x0, y);
  _mm256_store_ps(out.ox, r.ox), _mm256_store_ps(out.oy, r.oy), _mm256_store_ps(out.oz, r.oz);
  _mm256_store_ps(out.dx, r.dx), _mm256_store_ps(out.dy, r.dy), _mm256_store_ps(out.dz, r.dz);
  _mm256_store_ps(out.phase, r.phase);
}

KDSWAP_AVX2 void setupRays8Avx2(const RaySetupConstants& c, int x0, int y, RayLanes8& out) {
  const Rays r = raysOf(c, x0, y);
  const __m256 ox = r.ox, oy = r.oy, oz = r.oz, dx = r.dx, dy = r.dy, dz = r.dz, phase = r.phase;
  const __m256 wdx = r.wdx, wdy = r.wdy, wdz = r.wdz;
  // RayCaster::segmentFor: 1 / d, the rounding margin, the clip, the lattice index bounds.
  const __m256 ix = _mm256_div_ps(splat(1.0f), dx), iy = _mm256_div_ps(splat(1.0f), dy), iz = _mm256_div_ps(splat(1.0f), dz);
  const __m256 magnitude =
      _mm256_add_ps(_mm256_max_ps(_mm256_max_ps(absolute(ox), absolute(oy)), absolute(oz)), splat(c.clipHiMagnitude));
  const __m256 margin = _mm256_mul_ps(splat(4e-6f), magnitude);
  __m256 tNear = _mm256_setzero_ps(), tFar = splat(std::numeric_limits<float>::max()), rejected = _mm256_setzero_ps();
  clipAxis(ox, dx, ix, c.clipLo.x, c.clipHi.x, margin, tNear, tFar, rejected);
  clipAxis(oy, dy, iy, c.clipLo.y, c.clipHi.y, margin, tNear, tFar, rejected);
  clipAxis(oz, dz, iz, c.clipLo.z, c.clipHi.z, margin, tNear, tFar, rejected);
  const __m256 misses = _mm256_or_ps(rejected, _mm256_cmp_ps(tNear, tFar, _CMP_GT_OQ));  // tNear > tFar
  out.crosses = ~_mm256_movemask_ps(misses) & 0xFF;
  const __m256 inverseStep = splat(c.inverseStep);
  const __m256 firstIndex = _mm256_floor_ps(_mm256_sub_ps(_mm256_mul_ps(tNear, inverseStep), phase));
  const __m256 lastIndex = _mm256_ceil_ps(_mm256_sub_ps(_mm256_mul_ps(tFar, inverseStep), phase));
  _mm256_store_ps(out.firstIndex, firstIndex);
  _mm256_store_ps(out.lastIndex, lastIndex);
  // The ends of the owned run: the search's first four candidates at each end, for all lanes (in
  // lanes whose indices, and the candidates' k + 3, fit an int as the search's own SSE test needs).
  const __m256 limit = splat(float(1 << 30));
  const __m256 inRange = _mm256_and_ps(
      _mm256_andnot_ps(misses, _mm256_cmp_ps(firstIndex, splat(-2.0f), _CMP_GE_OQ)),
      _mm256_and_ps(_mm256_cmp_ps(lastIndex, limit, _CMP_LT_OQ), _mm256_cmp_ps(firstIndex, limit, _CMP_LT_OQ)));
  out.windows = _mm256_movemask_ps(inRange);
  if (out.windows != 0) {
    const __m256 safeFirst = _mm256_and_ps(firstIndex, inRange), safeLast = _mm256_and_ps(lastIndex, inRange);
    const __m256i kBegin = _mm256_max_epi32(_mm256_sub_epi32(_mm256_cvttps_epi32(safeFirst), _mm256_set1_epi32(1)),
                                            _mm256_setzero_si256());  // max(0, long(firstIndex) - 1)
    const __m256i kEnd = _mm256_add_epi32(_mm256_cvttps_epi32(safeLast), _mm256_set1_epi32(1));
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.nearOwned), ownedWindow(kBegin, phase, c, ox, oy, oz, dx, dy, dz));
    _mm256_store_si256(reinterpret_cast<__m256i*>(out.farOwned),
                       ownedWindow(_mm256_sub_epi32(kEnd, _mm256_set1_epi32(3)), phase, c, ox, oy, oz, dx, dy, dz));
  }
  _mm256_store_ps(out.ox, ox), _mm256_store_ps(out.oy, oy), _mm256_store_ps(out.oz, oz);
  _mm256_store_ps(out.dx, dx), _mm256_store_ps(out.dy, dy), _mm256_store_ps(out.dz, dz);
  _mm256_store_ps(out.ix, ix), _mm256_store_ps(out.iy, iy), _mm256_store_ps(out.iz, iz);
  _mm256_store_ps(out.wx, wdx), _mm256_store_ps(out.wy, wdy), _mm256_store_ps(out.wz, wdz);
  _mm256_store_ps(out.phase, phase);
}

}  // namespace

bool raySetup8Available() { return cpuHasAvx2() && !scalarRequested(); }

void setupRays8(const RaySetupConstants& c, int x0, int y, RayLanes8& out) { setupRays8Avx2(c, x0, y, out); }
void voxelRays8(const RaySetupConstants& c, int x0, int y, VoxelRays8& out) { voxelRays8Avx2(c, x0, y, out); }

}  // namespace kdswap

#else

namespace kdswap {
bool raySetup8Available() { return false; }
void setupRays8(const RaySetupConstants&, int, int, RayLanes8&) {}
void voxelRays8(const RaySetupConstants&, int, int, VoxelRays8&) {}
}  // namespace kdswap

#endif
