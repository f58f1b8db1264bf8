// Occlusion walk of eight rays at once (AVX2). Each lane performs the scalar walk's operations
// (occlusion_grid.cpp) in the same order, so every ray gets the same answer bit for bit; a lane
// that is done idles, masked, until the last one ends. Eight neighbouring pixels cross similar
// numbers of cells, so few lanes idle long.
#include "core/render/occlusion_grid.h"

#include "core/util/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

namespace kdswap {
namespace {

#define KDSWAP_AVX2 __attribute__((target("avx2")))

constexpr int kLanes = 8;

//! How each lane's walk ended: with the threshold reached in a segment (the scalar walk's
//! reachedAt then finishes it from these values) or not at all.
struct LaneEnds {
  bool reached[kLanes] = {};
  alignas(32) float sum[kLanes], depth[kLanes], first[kLanes], samples[kLanes];
};

struct Lanes {
  alignas(32) float t[kLanes], t1[kLanes], exitX[kLanes], exitY[kLanes], exitZ[kLanes];
  alignas(32) float deltaX[kLanes], deltaY[kLanes], deltaZ[kLanes], phase[kLanes];
  alignas(32) int cx[kLanes], cy[kLanes], cz[kLanes], dirX[kLanes], dirY[kLanes], dirZ[kLanes], index[kLanes];
  alignas(32) int active[kLanes];
};

KDSWAP_AVX2 inline __m256 asFloat(__m256i v) { return _mm256_castsi256_ps(v); }
KDSWAP_AVX2 inline __m256i asInt(__m256 v) { return _mm256_castps_si256(v); }
KDSWAP_AVX2 inline __m256 load(const float* p) { return _mm256_load_ps(p); }
KDSWAP_AVX2 inline __m256i load(const int* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }

KDSWAP_AVX2 void walkEight(const float* depthOf, int countX, int countY, int countZ, float threshold, float step,
                           const Lanes& in, LaneEnds& ends) {
  __m256 t = load(in.t), exitX = load(in.exitX), exitY = load(in.exitY), exitZ = load(in.exitZ);
  const __m256 t1 = load(in.t1), deltaX = load(in.deltaX), deltaY = load(in.deltaY), deltaZ = load(in.deltaZ);
  const __m256 phase = load(in.phase);
  __m256i cx = load(in.cx), cy = load(in.cy), cz = load(in.cz), index = load(in.index);
  const __m256i dirX = load(in.dirX), dirY = load(in.dirY), dirZ = load(in.dirZ);
  const __m256i strideY = _mm256_set1_epi32(countX), strideZ = _mm256_set1_epi32(countX * countY);
  const __m256i stepX = dirX, stepY = _mm256_mullo_epi32(dirY, strideY), stepZ = _mm256_mullo_epi32(dirZ, strideZ);
  const __m256i limitX = _mm256_set1_epi32(countX), limitY = _mm256_set1_epi32(countY),
                limitZ = _mm256_set1_epi32(countZ), minusOne = _mm256_set1_epi32(-1);
  __m256i active = load(in.active);

  const float perStep = 1.0f / step;
  const __m256 marginBase = _mm256_set1_ps(0.02f * step), marginScale = _mm256_set1_ps(1e-6f);
  const __m256 perStepV = _mm256_set1_ps(perStep), thresholdV = _mm256_set1_ps(threshold);
  const __m256 zero = _mm256_setzero_ps(), signBit = _mm256_set1_ps(-0.0f);
  __m256 sum = zero;

  while (!_mm256_testz_si256(active, active)) {
    // axis = exitX <= exitY ? (exitX <= exitZ ? 0 : 2) : (exitY <= exitZ ? 1 : 2)
    const __m256 xy = _mm256_cmp_ps(exitX, exitY, _CMP_LE_OQ), xz = _mm256_cmp_ps(exitX, exitZ, _CMP_LE_OQ),
                 yz = _mm256_cmp_ps(exitY, exitZ, _CMP_LE_OQ);
    const __m256 crossX = _mm256_and_ps(xy, xz);
    const __m256 crossY = _mm256_andnot_ps(xy, yz);
    const __m256 crossZ = _mm256_andnot_ps(_mm256_or_ps(crossX, crossY), asFloat(minusOne));
    const __m256 exitNow = _mm256_blendv_ps(_mm256_blendv_ps(exitZ, exitY, crossY), exitX, crossX);
    const __m256 segmentEnd = _mm256_min_ps(t1, exitNow);  // std::min(exitNow, t1)

    const __m256 depth = _mm256_i32gather_ps(depthOf, _mm256_and_si256(index, active), 4);  // idle lanes read cell 0
    const __m256 margin = _mm256_add_ps(marginBase, _mm256_mul_ps(marginScale, _mm256_andnot_ps(signBit, segmentEnd)));
    const __m256 first = _mm256_ceil_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_add_ps(t, margin), perStepV), phase));
    const __m256 samples = _mm256_sub_ps(
        _mm256_ceil_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_sub_ps(segmentEnd, margin), perStepV), phase)), first);
    const __m256 counted = _mm256_and_ps(asFloat(active), _mm256_and_ps(_mm256_cmp_ps(depth, zero, _CMP_GT_OQ),
                                                                      _mm256_cmp_ps(samples, zero, _CMP_GT_OQ)));
    const __m256 added = _mm256_add_ps(sum, _mm256_mul_ps(depth, samples));
    const __m256 reached = _mm256_and_ps(counted, _mm256_cmp_ps(added, thresholdV, _CMP_GE_OQ));
    if (const int bits = _mm256_movemask_ps(reached)) {
      alignas(32) float s[kLanes], d[kLanes], f[kLanes], n[kLanes];
      _mm256_store_ps(s, sum), _mm256_store_ps(d, depth), _mm256_store_ps(f, first), _mm256_store_ps(n, samples);
      for (int j = 0; j < kLanes; ++j)
        if (bits & (1 << j)) ends.reached[j] = true, ends.sum[j] = s[j], ends.depth[j] = d[j], ends.first[j] = f[j],
                                                  ends.samples[j] = n[j];
      active = _mm256_andnot_si256(asInt(reached), active);
    }
    sum = _mm256_blendv_ps(sum, added, counted);
    // The walk's end, then a step across the crossed face (a step off the grid ends it too).
    active = _mm256_andnot_si256(asInt(_mm256_cmp_ps(segmentEnd, t1, _CMP_GE_OQ)), active);
    cx = _mm256_add_epi32(cx, _mm256_and_si256(asInt(crossX), dirX));
    cy = _mm256_add_epi32(cy, _mm256_and_si256(asInt(crossY), dirY));
    cz = _mm256_add_epi32(cz, _mm256_and_si256(asInt(crossZ), dirZ));
    const __m256i outside = _mm256_or_si256(
        _mm256_or_si256(_mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), cx), _mm256_cmpgt_epi32(limitX, cx) ^ minusOne),
                        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), cy), _mm256_cmpgt_epi32(limitY, cy) ^ minusOne)),
        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), cz), _mm256_cmpgt_epi32(limitZ, cz) ^ minusOne));
    active = _mm256_andnot_si256(outside, active);
    index = _mm256_add_epi32(index, _mm256_or_si256(_mm256_or_si256(_mm256_and_si256(asInt(crossX), stepX),
                                                                    _mm256_and_si256(asInt(crossY), stepY)),
                                                    _mm256_and_si256(asInt(crossZ), stepZ)));
    exitX = _mm256_blendv_ps(exitX, _mm256_add_ps(exitX, deltaX), crossX);
    exitY = _mm256_blendv_ps(exitY, _mm256_add_ps(exitY, deltaY), crossY);
    exitZ = _mm256_blendv_ps(exitZ, _mm256_add_ps(exitZ, deltaZ), crossZ);
    t = _mm256_max_ps(segmentEnd, t);  // std::max(t, segmentEnd)
  }
}

}  // namespace

bool OcclusionGrid::walk8(const Walk* walks, const bool* started, float step, long* out) const {
  // Cell indices travel as 32-bit lanes.
  if (!cpuHasAvx2() || depth_.size() >= (std::size_t(1) << 31)) return false;
  Lanes lanes;
  for (int j = 0; j < kLanes; ++j) {
    const Walk& w = walks[j];
    lanes.active[j] = started[j] ? -1 : 0;
    if (!started[j]) {  // an idle lane: harmless values, never read
      lanes.t[j] = lanes.t1[j] = lanes.exitX[j] = lanes.exitY[j] = lanes.exitZ[j] = 0.0f;
      lanes.deltaX[j] = lanes.deltaY[j] = lanes.deltaZ[j] = lanes.phase[j] = 0.0f;
      lanes.cx[j] = lanes.cy[j] = lanes.cz[j] = lanes.index[j] = 0;
      lanes.dirX[j] = lanes.dirY[j] = lanes.dirZ[j] = 1;
      continue;
    }
    lanes.t[j] = w.t, lanes.t1[j] = w.t1, lanes.exitX[j] = w.exitX, lanes.exitY[j] = w.exitY, lanes.exitZ[j] = w.exitZ;
    lanes.deltaX[j] = w.deltaX, lanes.deltaY[j] = w.deltaY, lanes.deltaZ[j] = w.deltaZ, lanes.phase[j] = w.phase;
    lanes.cx[j] = w.cx, lanes.cy[j] = w.cy, lanes.cz[j] = w.cz, lanes.index[j] = int(w.index);
    lanes.dirX[j] = w.dirX, lanes.dirY[j] = w.dirY, lanes.dirZ[j] = w.dirZ;
  }
  LaneEnds ends;
  walkEight(depth_.data(), count_.x, count_.y, count_.z, threshold_, step, lanes, ends);
  for (int j = 0; j < kLanes; ++j)
    out[j] = started[j] && ends.reached[j] ? reachedAt(ends.sum[j], ends.depth[j], ends.first[j], ends.samples[j]) : kNever;
  return true;
}

}  // namespace kdswap

#else

namespace kdswap {
bool OcclusionGrid::walk8(const Walk*, const bool*, float, long*) const { return false; }
}  // namespace kdswap

#endif
