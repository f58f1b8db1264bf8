// Occlusion walk of eight rays at once (AVX2). Each lane performs the scalar walk's operations
// (occlusion_grid.cpp) in the same order, so every ray gets the same answer bit for bit; a lane
// that is done idles, masked, until the last one ends. Eight neighbouring pixels cross similar
// numbers of cells, so few lanes idle long. The lanes in cells of one-voxel depths step through
// them together (walkFineCells): one lane after another, each waited for the last one's loads
// (the phantom 256^3's map at P = 64 on an AMD Zen 5 with this build: 9.5-10.5 -> 8.4-8.7 ms).
#include "core/render/occlusion_grid.h"

#include <algorithm>
#include <cstdint>
#include <limits>

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
  bool reachedFine[kLanes] = {};  //!< reached inside a cell's one-voxel walk: the answer is known
  long answer[kLanes];
};

struct Lanes {
  alignas(32) float t[kLanes], t1[kLanes], exitX[kLanes], exitY[kLanes], exitZ[kLanes];
  alignas(32) float deltaX[kLanes], deltaY[kLanes], deltaZ[kLanes], phase[kLanes];
  alignas(32) int cx[kLanes], cy[kLanes], cz[kLanes], dirX[kLanes], dirY[kLanes], dirZ[kLanes], index[kLanes];
  alignas(32) int active[kLanes];
  alignas(32) float o[3][kLanes], d[3][kLanes];
};

//! What the one-voxel steps read: the blocks of codes (from the first block) and each code's depth.
struct FineTables {
  const std::uint8_t* codes;
  const float* depthOfCode;
};

KDSWAP_AVX2 inline __m256 asFloat(__m256i v) { return _mm256_castsi256_ps(v); }
KDSWAP_AVX2 inline __m256i asInt(__m256 v) { return _mm256_castps_si256(v); }
KDSWAP_AVX2 inline __m256 load(const float* p) { return _mm256_load_ps(p); }
KDSWAP_AVX2 inline __m256i load(const int* p) { return _mm256_load_si256(reinterpret_cast<const __m256i*>(p)); }

//! Cells a jump crosses along one axis: n (`across`) along the axis it leaves the cube by,
//! otherwise the faces before tCube, at most n - 1 (`far`); the scalar walk's jump.
KDSWAP_AVX2 inline __m256 facesCrossed(__m256 exit, __m256 delta, __m256 leave, __m256 tCube, __m256 far, __m256 across) {
  const __m256 k = _mm256_min_ps(_mm256_ceil_ps(_mm256_div_ps(_mm256_sub_ps(tCube, exit), delta)), far);
  return _mm256_blendv_ps(_mm256_and_ps(_mm256_cmp_ps(exit, tCube, _CMP_LT_OQ), k), across, leave);
}

//! The lanes `fine` cross cells with one-voxel depths: all of them step through their samples of
//! the segment together, sample k of each at once, each lane adding its own depths in order
//! (OcclusionGrid::walkFine's sum and rule), so every lane gets the scalar walk's answer.
//! Returns the lanes' sums; lanes that reach the threshold leave `active` with their answer in `ends`.
KDSWAP_AVX2 __m256 walkFineCells(const FineTables& tables, const Lanes& in, __m256 fine, __m256 depth, __m256 first,
                                 __m256 last, __m256i cx, __m256i cy, __m256i cz, float threshold, float step,
                                 __m256 sum, __m256i& active, LaneEnds& ends) {
  const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f), stepV = _mm256_set1_ps(step);
  const __m256 thresholdV = _mm256_set1_ps(threshold), phase = load(in.phase);
  const __m256i lowest = _mm256_setzero_si256(), highest = _mm256_set1_epi32(CellRangeGrid::kSide - 1);
  constexpr int kShift = CellRangeGrid::kShift;
  // OcclusionGrid::blockOf: int(-depth) - 1, a block of kFinePerCell codes.
  const __m256i block = _mm256_sub_epi32(_mm256_cvttps_epi32(_mm256_sub_ps(zero, depth)), _mm256_set1_epi32(1));
  const __m256i blockStart = _mm256_slli_epi32(block, 3 * kShift);
  const __m256i base[3] = {_mm256_slli_epi32(cx, kShift), _mm256_slli_epi32(cy, kShift), _mm256_slli_epi32(cz, kShift)};
  const __m256 o[3] = {load(in.o[0]), load(in.o[1]), load(in.o[2])}, d[3] = {load(in.d[0]), load(in.d[1]), load(in.d[2])};
  // std::clamp(int(o + d * s) - base, 0, side - 1)
  const auto voxel = [&](int a, __m256 s) KDSWAP_AVX2 {
    const __m256i v = _mm256_sub_epi32(_mm256_cvttps_epi32(_mm256_add_ps(o[a], _mm256_mul_ps(d[a], s))), base[a]);
    return _mm256_min_epi32(_mm256_max_epi32(v, lowest), highest);
  };
  __m256 k = first, total = sum;
  __m256 stepping = _mm256_and_ps(fine, _mm256_cmp_ps(k, last, _CMP_LT_OQ));
  while (!_mm256_testz_ps(stepping, stepping)) {
    const __m256 s = _mm256_mul_ps(_mm256_add_ps(k, phase), stepV);  // (k + phase) * step
    const __m256i fx = voxel(0, s), fy = voxel(1, s), fz = voxel(2, s);
    const __m256i index =
        _mm256_add_epi32(_mm256_slli_epi32(_mm256_add_epi32(_mm256_slli_epi32(fz, kShift), fy), kShift), fx);
    // Each code is the low byte of four read from its place (the blocks end with three spare bytes).
    const __m256i codes = _mm256_and_si256(
        _mm256_mask_i32gather_epi32(lowest, reinterpret_cast<const int*>(tables.codes),
                                    _mm256_add_epi32(blockStart, index), asInt(stepping), 1),
        _mm256_set1_epi32(0xFF));
    const __m256 added = _mm256_add_ps(total, _mm256_mask_i32gather_ps(zero, tables.depthOfCode, codes, stepping, 4));
    total = _mm256_blendv_ps(total, added, stepping);
    const __m256 hit = _mm256_and_ps(stepping, _mm256_cmp_ps(total, thresholdV, _CMP_GE_OQ));
    if (const int bits = _mm256_movemask_ps(hit)) {
      alignas(32) float at[kLanes];
      _mm256_store_ps(at, k);
      for (int j = 0; j < kLanes; ++j)
        if (bits & (1 << j)) ends.answer[j] = long(at[j]) + 1, ends.reachedFine[j] = true;
      active = _mm256_andnot_si256(asInt(hit), active);
      stepping = _mm256_andnot_ps(hit, stepping);
    }
    k = _mm256_add_ps(k, one);
    stepping = _mm256_and_ps(stepping, _mm256_cmp_ps(k, last, _CMP_LT_OQ));
  }
  return _mm256_blendv_ps(sum, total, fine);
}

KDSWAP_AVX2 void walkEight(const FineTables& fineTables, const float* depthOf, int countX, int countY, int countZ,
                           float threshold, float step, const Lanes& in, LaneEnds& ends) {
  __m256 t = load(in.t), exitX = load(in.exitX), exitY = load(in.exitY), exitZ = load(in.exitZ);
  const __m256 t1 = load(in.t1), deltaX = load(in.deltaX), deltaY = load(in.deltaY), deltaZ = load(in.deltaZ);
  const __m256 phase = load(in.phase);
  __m256i cx = load(in.cx), cy = load(in.cy), cz = load(in.cz), index = load(in.index);
  const __m256i dirX = load(in.dirX), dirY = load(in.dirY), dirZ = load(in.dirZ);
  const __m256i strideY = _mm256_set1_epi32(countX), strideZ = _mm256_set1_epi32(countX * countY);
  const __m256i strideX1 = dirX, strideY1 = _mm256_mullo_epi32(dirY, strideY),
                strideZ1 = _mm256_mullo_epi32(dirZ, strideZ);  // index steps along each axis
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
    const __m256 last = _mm256_ceil_ps(_mm256_sub_ps(_mm256_mul_ps(_mm256_sub_ps(segmentEnd, margin), perStepV), phase));
    const __m256 samples = _mm256_sub_ps(last, first);
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
    // Lanes in cells with one-voxel depths step through those, all such lanes together.
    const __m256 reachBase = _mm256_set1_ps(OcclusionGrid::kReachBase);
    const __m256 fine = _mm256_and_ps(asFloat(active), _mm256_and_ps(_mm256_cmp_ps(depth, zero, _CMP_LT_OQ),
                                                                     _mm256_cmp_ps(depth, _mm256_sub_ps(zero, reachBase), _CMP_GE_OQ)));
    if (!_mm256_testz_ps(fine, fine))
      sum = walkFineCells(fineTables, in, fine, depth, first, last, cx, cy, cz, threshold, step, sum, active, ends);
    sum = _mm256_blendv_ps(sum, added, counted);
    // Lanes in an empty cell whose empty surroundings reach n >= 2 leave that cube of cells in one
    // step (the scalar walk's jump, operation for operation); the others step one cell.
    // -depth - kReachBase: the reach of a cell without depth (below 1 for the others)
    const __m256 across = _mm256_sub_ps(_mm256_sub_ps(zero, depth), reachBase);
    const __m256 jump = _mm256_and_ps(asFloat(active), _mm256_cmp_ps(across, _mm256_set1_ps(2.0f), _CMP_GE_OQ));
    const __m256 stepX = _mm256_andnot_ps(jump, crossX), stepY = _mm256_andnot_ps(jump, crossY),
                 stepZ = _mm256_andnot_ps(jump, crossZ);
    __m256 ended = _mm256_cmp_ps(segmentEnd, t1, _CMP_GE_OQ);
    cx = _mm256_add_epi32(cx, _mm256_and_si256(asInt(stepX), dirX));
    cy = _mm256_add_epi32(cy, _mm256_and_si256(asInt(stepY), dirY));
    cz = _mm256_add_epi32(cz, _mm256_and_si256(asInt(stepZ), dirZ));
    index = _mm256_add_epi32(index, _mm256_or_si256(_mm256_or_si256(_mm256_and_si256(asInt(stepX), strideX1),
                                                                    _mm256_and_si256(asInt(stepY), strideY1)),
                                                    _mm256_and_si256(asInt(stepZ), strideZ1)));
    exitX = _mm256_blendv_ps(exitX, _mm256_add_ps(exitX, deltaX), stepX);
    exitY = _mm256_blendv_ps(exitY, _mm256_add_ps(exitY, deltaY), stepY);
    exitZ = _mm256_blendv_ps(exitZ, _mm256_add_ps(exitZ, deltaZ), stepZ);
    __m256 next = segmentEnd;
    if (_mm256_movemask_ps(jump) != 0) {
      const __m256 far = _mm256_sub_ps(across, _mm256_set1_ps(1.0f));
      const __m256 cubeX = _mm256_add_ps(exitX, _mm256_mul_ps(far, deltaX)),
                   cubeY = _mm256_add_ps(exitY, _mm256_mul_ps(far, deltaY)),
                   cubeZ = _mm256_add_ps(exitZ, _mm256_mul_ps(far, deltaZ));
      const __m256 cxy = _mm256_cmp_ps(cubeX, cubeY, _CMP_LE_OQ), cxz = _mm256_cmp_ps(cubeX, cubeZ, _CMP_LE_OQ),
                   cyz = _mm256_cmp_ps(cubeY, cubeZ, _CMP_LE_OQ);
      const __m256 leaveX = _mm256_and_ps(cxy, cxz), leaveY = _mm256_andnot_ps(cxy, cyz);
      const __m256 leaveZ = _mm256_andnot_ps(_mm256_or_ps(leaveX, leaveY), asFloat(minusOne));
      const __m256 tCube = _mm256_blendv_ps(_mm256_blendv_ps(cubeZ, cubeY, leaveY), cubeX, leaveX);
      const __m256 kx = facesCrossed(exitX, deltaX, leaveX, tCube, far, across),
                   ky = facesCrossed(exitY, deltaY, leaveY, tCube, far, across),
                   kz = facesCrossed(exitZ, deltaZ, leaveZ, tCube, far, across);
      const __m256i jumpI = asInt(jump);
      cx = _mm256_blendv_epi8(cx, _mm256_add_epi32(cx, _mm256_mullo_epi32(_mm256_cvttps_epi32(kx), dirX)), jumpI);
      cy = _mm256_blendv_epi8(cy, _mm256_add_epi32(cy, _mm256_mullo_epi32(_mm256_cvttps_epi32(ky), dirY)), jumpI);
      cz = _mm256_blendv_epi8(cz, _mm256_add_epi32(cz, _mm256_mullo_epi32(_mm256_cvttps_epi32(kz), dirZ)), jumpI);
      // (cz * countY + cy) * countX + cx; lanes off the grid end below before their index is read
      index = _mm256_blendv_epi8(
          index, _mm256_add_epi32(_mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(cz, limitY), cy), limitX), cx),
          jumpI);
      exitX = _mm256_blendv_ps(exitX, _mm256_add_ps(exitX, _mm256_mul_ps(kx, deltaX)), jump);
      exitY = _mm256_blendv_ps(exitY, _mm256_add_ps(exitY, _mm256_mul_ps(ky, deltaY)), jump);
      exitZ = _mm256_blendv_ps(exitZ, _mm256_add_ps(exitZ, _mm256_mul_ps(kz, deltaZ)), jump);
      ended = _mm256_blendv_ps(ended, _mm256_cmp_ps(tCube, t1, _CMP_GE_OQ), jump);
      next = _mm256_blendv_ps(segmentEnd, tCube, jump);
    }
    // The walk's end (its last segment, or a step off the grid).
    const __m256i outside = _mm256_or_si256(
        _mm256_or_si256(_mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), cx), _mm256_cmpgt_epi32(limitX, cx) ^ minusOne),
                        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), cy), _mm256_cmpgt_epi32(limitY, cy) ^ minusOne)),
        _mm256_or_si256(_mm256_cmpgt_epi32(_mm256_setzero_si256(), cz), _mm256_cmpgt_epi32(limitZ, cz) ^ minusOne));
    active = _mm256_andnot_si256(_mm256_or_si256(asInt(ended), outside), active);
    t = _mm256_max_ps(next, t);  // std::max(t, segmentEnd or the cube's exit)
  }
}


//! The box the walks are clipped to and the grid's size: what startWalk reads.
struct StartConstants {
  float lo[3], hi[3];  //!< depthLo_, depthHi_
  int count[3];
};

//! (a < b) ? b : a, as std::max(a, b); and (b < a) ? b : a, as std::min(a, b).
KDSWAP_AVX2 inline __m256 maxOf(__m256 a, __m256 b) { return _mm256_blendv_ps(a, b, _mm256_cmp_ps(a, b, _CMP_LT_OQ)); }
KDSWAP_AVX2 inline __m256 minOf(__m256 a, __m256 b) { return _mm256_blendv_ps(a, b, _mm256_cmp_ps(b, a, _CMP_LT_OQ)); }

//! OcclusionGrid::startWalk for eight rays (o, d per axis in lanes): each lane performs its
//! operations in the same order, so `out` holds what the scalar start would give that ray. Returns
//! the lanes that start (the scalar start returns true); the others are idle and zero.
KDSWAP_AVX2 int startEight(const StartConstants& c, const __m256* o, const __m256* d, __m256 phase, float step,
                           Lanes& out) {
  const __m256 zero = _mm256_setzero_ps();
  __m256 t0 = zero, t1 = _mm256_set1_ps(std::numeric_limits<float>::max());
  __m256 refused = zero;
  __m256 flat[3];
  for (int a = 0; a < 3; ++a) {
    const __m256 lo = _mm256_set1_ps(c.lo[a]), hi = _mm256_set1_ps(c.hi[a]);
    flat[a] = _mm256_cmp_ps(d[a], zero, _CMP_EQ_OQ);  // d[a] == 0: outside the slab ends the walk
    refused = _mm256_or_ps(refused, _mm256_and_ps(flat[a], _mm256_or_ps(_mm256_cmp_ps(o[a], lo, _CMP_LT_OQ),
                                                                         _mm256_cmp_ps(o[a], hi, _CMP_GT_OQ))));
    __m256 ta = _mm256_div_ps(_mm256_sub_ps(lo, o[a]), d[a]), tb = _mm256_div_ps(_mm256_sub_ps(hi, o[a]), d[a]);
    const __m256 swap = _mm256_cmp_ps(ta, tb, _CMP_GT_OQ);
    const __m256 near = _mm256_blendv_ps(ta, tb, swap), far = _mm256_blendv_ps(tb, ta, swap);
    t0 = _mm256_blendv_ps(maxOf(t0, near), t0, flat[a]);
    t1 = _mm256_blendv_ps(minOf(t1, far), t1, flat[a]);
  }
  // !(t1 - t0 > 2 step)
  refused = _mm256_or_ps(refused, _mm256_cmp_ps(_mm256_sub_ps(t1, t0), _mm256_set1_ps(2.0f * step), _CMP_NGT_UQ));
  const int started = ~_mm256_movemask_ps(refused) & 0xFF;
  const __m256i keep = _mm256_castps_si256(_mm256_andnot_ps(refused, _mm256_castsi256_ps(_mm256_set1_epi32(-1))));
  const float cellSize = float(1 << CellRangeGrid::kShift);
  __m256i cell[3], dir[3];
  __m256 exit[3], delta[3];
  for (int a = 0; a < 3; ++a) {
    const __m256 start = _mm256_add_ps(o[a], _mm256_mul_ps(d[a], t0));  // o + d * t0
    const __m256i floored = _mm256_cvttps_epi32(_mm256_floor_ps(_mm256_div_ps(start, _mm256_set1_ps(cellSize))));
    // std::clamp(v, 0, count - 1)
    cell[a] = _mm256_min_epi32(_mm256_max_epi32(floored, _mm256_setzero_si256()), _mm256_set1_epi32(c.count[a] - 1));
    const __m256 up = _mm256_cmp_ps(d[a], zero, _CMP_GT_OQ);
    dir[a] = _mm256_blendv_epi8(_mm256_set1_epi32(-1), _mm256_set1_epi32(1), _mm256_castps_si256(up));
    // boundary = float((cell + (d > 0 ? 1 : 0)) * kCell); exit = (boundary - o) / d; delta = kCell / |d|
    const __m256i face = _mm256_sub_epi32(cell[a], _mm256_castps_si256(up));  // up lanes are -1: cell + 1
    const __m256 boundary = _mm256_cvtepi32_ps(_mm256_slli_epi32(face, CellRangeGrid::kShift));
    exit[a] = _mm256_blendv_ps(_mm256_div_ps(_mm256_sub_ps(boundary, o[a]), d[a]),
                               _mm256_set1_ps(std::numeric_limits<float>::infinity()), flat[a]);
    delta[a] = _mm256_blendv_ps(_mm256_div_ps(_mm256_set1_ps(cellSize), _mm256_andnot_ps(_mm256_set1_ps(-0.0f), d[a])),
                                zero, flat[a]);
    cell[a] = _mm256_and_si256(cell[a], keep);
  }
  const __m256i index = _mm256_add_epi32(
      _mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(cell[2], _mm256_set1_epi32(c.count[1])), cell[1]),
                         _mm256_set1_epi32(c.count[0])),
      cell[0]);
  const __m256 keepF = _mm256_castsi256_ps(keep);
  _mm256_store_ps(out.t, _mm256_and_ps(t0, keepF)), _mm256_store_ps(out.t1, _mm256_and_ps(t1, keepF));
  _mm256_store_ps(out.exitX, _mm256_and_ps(exit[0], keepF)), _mm256_store_ps(out.exitY, _mm256_and_ps(exit[1], keepF)),
  _mm256_store_ps(out.exitZ, _mm256_and_ps(exit[2], keepF));
  _mm256_store_ps(out.deltaX, _mm256_and_ps(delta[0], keepF)), _mm256_store_ps(out.deltaY, _mm256_and_ps(delta[1], keepF)),
  _mm256_store_ps(out.deltaZ, _mm256_and_ps(delta[2], keepF));
  _mm256_store_ps(out.phase, _mm256_and_ps(phase, keepF));
  __m256i* const ints[] = {reinterpret_cast<__m256i*>(out.cx), reinterpret_cast<__m256i*>(out.cy),
                           reinterpret_cast<__m256i*>(out.cz), reinterpret_cast<__m256i*>(out.dirX),
                           reinterpret_cast<__m256i*>(out.dirY), reinterpret_cast<__m256i*>(out.dirZ)};
  for (int a = 0; a < 3; ++a) _mm256_store_si256(ints[a], cell[a]), _mm256_store_si256(ints[3 + a], dir[a]);
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.index), _mm256_and_si256(index, keep));
  _mm256_store_si256(reinterpret_cast<__m256i*>(out.active), keep);
  for (int a = 0; a < 3; ++a) _mm256_store_ps(out.o[a], o[a]), _mm256_store_ps(out.d[a], d[a]);
  return started;
}

//! Starts (startEight) and walks (walkEight) eight rays; returns the lanes that started.
KDSWAP_AVX2 int startAndWalkEight(const FineTables& fine, const StartConstants& c, const float* depth, float threshold,
                                  const VoxelRays8& rays, float step, LaneEnds& ends) {
  const __m256 o[3] = {_mm256_load_ps(rays.ox), _mm256_load_ps(rays.oy), _mm256_load_ps(rays.oz)};
  const __m256 d[3] = {_mm256_load_ps(rays.dx), _mm256_load_ps(rays.dy), _mm256_load_ps(rays.dz)};
  Lanes lanes;
  const int started = startEight(c, o, d, _mm256_load_ps(rays.phase), step, lanes);
  if (started != 0) walkEight(fine, depth, c.count[0], c.count[1], c.count[2], threshold, step, lanes, ends);
  return started;
}

}  // namespace

bool OcclusionGrid::walkRays8(const VoxelRays8& rays, float step, long* out) const {
  // Cell indices travel as 32-bit lanes.
  if (!cpuHasAvx2() || depth_.size() >= (std::size_t(1) << 31)) return false;
  const StartConstants constants{{depthLo_.x, depthLo_.y, depthLo_.z}, {depthHi_.x, depthHi_.y, depthHi_.z},
                                 {count_.x, count_.y, count_.z}};
  LaneEnds ends;
  const FineTables fine{fineCode_.data() + fineOffset_, depthOfCode_};
  const int started = startAndWalkEight(fine, constants, depth_.data(), threshold_, rays, step, ends);
  for (int j = 0; j < kLanes; ++j)
    out[j] = !(started >> j & 1)  ? kNever
             : ends.reachedFine[j] ? ends.answer[j]
             : ends.reached[j]     ? reachedAt(ends.sum[j], ends.depth[j], ends.first[j], ends.samples[j])
                                   : kNever;
  return true;
}

}  // namespace kdswap

#else

namespace kdswap {
bool OcclusionGrid::walkRays8(const VoxelRays8&, float, long*) const { return false; }
}  // namespace kdswap

#endif
