// Occlusion walk of sixteen rays at once (AVX-512). The eight-lane walk (occlusion_grid_avx2.cpp)
// is bound by the latency of each step's chain (the cell's depth gathered, compared, the next cell
// chosen), not by its instructions; sixteen lanes in one register take the same chain for twice
// the rays, and the lanes in cells of one-voxel depths step through them together rather than one
// lane after another. Each lane performs the scalar walk's operations (occlusion_grid.cpp) in the
// same order, as the eight-lane walk does, so every ray gets the same answer bit for bit. On 2
// cores of an AMD EPYC (Zen 5), the phantom 256^3 at P = 64: the map 9.2 ms a frame with eight
// lanes, 7.1 with sixteen walking one-voxel cells lane by lane, 5.6 with them together.
#include "core/render/occlusion_grid.h"

#include <limits>

#include "core/util/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

namespace kdswap {
namespace {

#define KDSWAP_AVX512 __attribute__((target("avx2,avx512f,avx512vl,avx512dq,avx512bw")))

constexpr int kLanes = 16;
constexpr __mmask16 kAll = 0xFFFF;

// The same instructions in their zero-masking forms over all lanes: GCC 12's unmasked forms start
// from an undefined register, which -Wuninitialized reports (as in the march, ray_march_avx2.cpp).
KDSWAP_AVX512 inline __m512 ceil16(__m512 x) {
  return _mm512_maskz_roundscale_ps(kAll, x, _MM_FROUND_TO_POS_INF | _MM_FROUND_NO_EXC);
}
KDSWAP_AVX512 inline __m512 floor16(__m512 x) {
  return _mm512_maskz_roundscale_ps(kAll, x, _MM_FROUND_TO_NEG_INF | _MM_FROUND_NO_EXC);
}
KDSWAP_AVX512 inline __m512 min16(__m512 a, __m512 b) { return _mm512_maskz_min_ps(kAll, a, b); }
KDSWAP_AVX512 inline __m512 max16(__m512 a, __m512 b) { return _mm512_maskz_max_ps(kAll, a, b); }
KDSWAP_AVX512 inline __m512i truncated16(__m512 x) { return _mm512_maskz_cvttps_epi32(kAll, x); }
KDSWAP_AVX512 inline __m512 toFloat16(__m512i x) { return _mm512_maskz_cvtepi32_ps(kAll, x); }

//! How each lane's walk ended (as in the eight-lane walk): the threshold reached in a cell's
//! segment (reachedAt finishes it), inside a one-voxel walk (the answer is known), or not at all.
struct LaneEnds {
  alignas(64) float sum[kLanes], depth[kLanes], first[kLanes], samples[kLanes];
  long answer[kLanes];
  __mmask16 reached = 0, reachedFine = 0;
};

struct Lanes {
  __m512 o[3], d[3];
  __m512 t, t1, exitX, exitY, exitZ, deltaX, deltaY, deltaZ, phase;
  __m512i cx, cy, cz, dirX, dirY, dirZ, index;
  __mmask16 active;
};

//! What the one-voxel steps read: the blocks of codes (from the first block) and each code's depth.
struct FineTables {
  const std::uint8_t* codes;
  const float* depthOfCode;
};

//! Cells a jump crosses along one axis: n (`across`) along the axis it leaves the cube by,
//! otherwise the faces before tCube, at most n - 1 (`far`); the scalar walk's jump.
KDSWAP_AVX512 inline __m512 facesCrossed(__m512 exit, __m512 delta, __mmask16 leave, __m512 tCube, __m512 far,
                                         __m512 across) {
  const __m512 k = min16(ceil16(_mm512_div_ps(_mm512_sub_ps(tCube, exit), delta)), far);
  const __m512 before = _mm512_maskz_mov_ps(_mm512_cmp_ps_mask(exit, tCube, _CMP_LT_OQ), k);
  return _mm512_mask_blend_ps(leave, before, across);
}

//! The lanes `fine` cross cells with one-voxel depths: all of them step through their samples of
//! the segment together, sample k of each at once, each lane adding its own depths in order
//! (OcclusionGrid::walkFine's sum and rule: positions truncated and clamped into the cell), so
//! every lane gets the scalar walk's answer; one lane after another, each lane's loads waited for
//! the last lane's. Returns the lanes' sums; lanes that reach the threshold leave `active` with
//! their answer in `ends`.
KDSWAP_AVX512 __m512 walkFineCells(const FineTables& tables, const Lanes& in, __mmask16 fine, __m512 depth, __m512 first,
                                   __m512 last, __m512i cx, __m512i cy, __m512i cz, float threshold, float step,
                                   __m512 sum, __mmask16& active, LaneEnds& ends) {
  const __m512 zero = _mm512_setzero_ps(), one = _mm512_set1_ps(1.0f), stepV = _mm512_set1_ps(step);
  const __m512 thresholdV = _mm512_set1_ps(threshold);
  const __m512i lowest = _mm512_setzero_si512(), highest = _mm512_set1_epi32(CellRangeGrid::kSide - 1);
  constexpr int kShift = CellRangeGrid::kShift;
  // OcclusionGrid::blockOf: int(-depth) - 1, a block of kFinePerCell codes.
  const __m512i block = _mm512_sub_epi32(truncated16(_mm512_sub_ps(zero, depth)), _mm512_set1_epi32(1));
  const __m512i blockStart = _mm512_maskz_slli_epi32(kAll, block, 3 * kShift);
  const __m512i base[3] = {_mm512_maskz_slli_epi32(kAll, cx, kShift), _mm512_maskz_slli_epi32(kAll, cy, kShift),
                           _mm512_maskz_slli_epi32(kAll, cz, kShift)};
  // std::clamp(int(o + d * s) - base, 0, side - 1)
  const auto voxel = [&](int a, __m512 s) KDSWAP_AVX512 {
    const __m512i v = _mm512_sub_epi32(truncated16(_mm512_add_ps(in.o[a], _mm512_mul_ps(in.d[a], s))), base[a]);
    return _mm512_maskz_min_epi32(kAll, _mm512_maskz_max_epi32(kAll, v, lowest), highest);
  };
  __m512 k = first, total = sum;
  __mmask16 stepping = fine & _mm512_cmp_ps_mask(k, last, _CMP_LT_OQ);
  while (stepping != 0) {
    const __m512 s = _mm512_mul_ps(_mm512_add_ps(k, in.phase), stepV);  // (k + phase) * step
    const __m512i fx = voxel(0, s), fy = voxel(1, s), fz = voxel(2, s);
    const __m512i index = _mm512_add_epi32(
        _mm512_maskz_slli_epi32(kAll, _mm512_add_epi32(_mm512_maskz_slli_epi32(kAll, fz, kShift), fy), kShift), fx);
    // Each code is the low byte of four read from its place (the blocks end with three spare bytes).
    const __m512i codes = _mm512_and_si512(
        _mm512_mask_i32gather_epi32(lowest, stepping, _mm512_add_epi32(blockStart, index), tables.codes, 1),
        _mm512_set1_epi32(0xFF));
    total = _mm512_mask_add_ps(total, stepping, total, _mm512_mask_i32gather_ps(zero, stepping, codes, tables.depthOfCode, 4));
    if (const __mmask16 hit = stepping & _mm512_cmp_ps_mask(total, thresholdV, _CMP_GE_OQ)) {
      alignas(64) float at[kLanes];
      _mm512_store_ps(at, k);
      for (unsigned bits = hit; bits != 0; bits &= bits - 1) {
        const int j = __builtin_ctz(bits);
        ends.answer[j] = long(at[j]) + 1;
      }
      ends.reachedFine |= hit;
      active &= __mmask16(~hit);
      stepping &= __mmask16(~hit);
    }
    k = _mm512_add_ps(k, one);
    stepping &= _mm512_cmp_ps_mask(k, last, _CMP_LT_OQ);
  }
  return _mm512_mask_blend_ps(fine, sum, total);
}

KDSWAP_AVX512 void walkSixteen(const FineTables& fineTables, const float* depthOf, int countX, int countY, int countZ,
                               float threshold, float step, const Lanes& in, LaneEnds& ends) {
  __m512 t = in.t, exitX = in.exitX, exitY = in.exitY, exitZ = in.exitZ;
  const __m512 t1 = in.t1, deltaX = in.deltaX, deltaY = in.deltaY, deltaZ = in.deltaZ, phase = in.phase;
  __m512i cx = in.cx, cy = in.cy, cz = in.cz, index = in.index;
  const __m512i dirX = in.dirX, dirY = in.dirY, dirZ = in.dirZ;
  const __m512i strideY1 = _mm512_mullo_epi32(dirY, _mm512_set1_epi32(countX)),
                strideZ1 = _mm512_mullo_epi32(dirZ, _mm512_set1_epi32(countX * countY));  // index steps
  const __m512i limitX = _mm512_set1_epi32(countX), limitY = _mm512_set1_epi32(countY),
                limitZ = _mm512_set1_epi32(countZ), zeroI = _mm512_setzero_si512();
  __mmask16 active = in.active;

  const float perStep = 1.0f / step;
  const __m512 marginBase = _mm512_set1_ps(0.02f * step), marginScale = _mm512_set1_ps(1e-6f);
  const __m512 perStepV = _mm512_set1_ps(perStep), thresholdV = _mm512_set1_ps(threshold);
  const __m512 zero = _mm512_setzero_ps(), reachBase = _mm512_set1_ps(OcclusionGrid::kReachBase);
  const __m512 minusReachBase = _mm512_sub_ps(zero, reachBase);
  __m512 sum = zero;

  while (active != 0) {
    // axis = exitX <= exitY ? (exitX <= exitZ ? 0 : 2) : (exitY <= exitZ ? 1 : 2)
    const __mmask16 xy = _mm512_cmp_ps_mask(exitX, exitY, _CMP_LE_OQ), xz = _mm512_cmp_ps_mask(exitX, exitZ, _CMP_LE_OQ),
                    yz = _mm512_cmp_ps_mask(exitY, exitZ, _CMP_LE_OQ);
    const __mmask16 crossX = xy & xz, crossY = __mmask16(~xy & yz), crossZ = __mmask16(~(crossX | crossY));
    const __m512 exitNow = _mm512_mask_blend_ps(crossX, _mm512_mask_blend_ps(crossY, exitZ, exitY), exitX);
    const __m512 segmentEnd = min16(t1, exitNow);  // std::min(exitNow, t1)

    const __m512 depth = _mm512_mask_i32gather_ps(zero, active, index, depthOf, 4);  // idle lanes read nothing
    const __m512 margin = _mm512_add_ps(marginBase, _mm512_mul_ps(marginScale, _mm512_abs_ps(segmentEnd)));
    const __m512 first = ceil16(_mm512_sub_ps(_mm512_mul_ps(_mm512_add_ps(t, margin), perStepV), phase));
    const __m512 last = ceil16(_mm512_sub_ps(_mm512_mul_ps(_mm512_sub_ps(segmentEnd, margin), perStepV), phase));
    const __m512 samples = _mm512_sub_ps(last, first);
    const __mmask16 counted = active & _mm512_cmp_ps_mask(depth, zero, _CMP_GT_OQ) &
                              _mm512_cmp_ps_mask(samples, zero, _CMP_GT_OQ);
    const __m512 added = _mm512_add_ps(sum, _mm512_mul_ps(depth, samples));
    const __mmask16 reached = counted & _mm512_cmp_ps_mask(added, thresholdV, _CMP_GE_OQ);
    if (reached != 0) {
      _mm512_mask_store_ps(ends.sum, reached, sum), _mm512_mask_store_ps(ends.depth, reached, depth);
      _mm512_mask_store_ps(ends.first, reached, first), _mm512_mask_store_ps(ends.samples, reached, samples);
      ends.reached |= reached;
      active &= __mmask16(~reached);
    }
    // Lanes in cells with one-voxel depths walk those one lane at a time (the scalar walk's code).
    const __mmask16 fine = active & _mm512_cmp_ps_mask(depth, zero, _CMP_LT_OQ) &
                           _mm512_cmp_ps_mask(depth, minusReachBase, _CMP_GE_OQ);
    if (fine != 0) sum = walkFineCells(fineTables, in, fine, depth, first, last, cx, cy, cz, threshold, step, sum,
                                       active, ends);
    sum = _mm512_mask_blend_ps(counted, sum, added);
    // Lanes in an empty cell whose empty surroundings reach n >= 2 leave that cube of cells in one
    // step (the scalar walk's jump, operation for operation); the others step one cell.
    // -depth - kReachBase: the reach of a cell without depth (below 1 for the others)
    const __m512 across = _mm512_sub_ps(_mm512_sub_ps(zero, depth), reachBase);
    const __mmask16 jump = active & _mm512_cmp_ps_mask(across, _mm512_set1_ps(2.0f), _CMP_GE_OQ);
    const __mmask16 stepX = crossX & __mmask16(~jump), stepY = crossY & __mmask16(~jump),
                    stepZ = crossZ & __mmask16(~jump);
    __mmask16 ended = _mm512_cmp_ps_mask(segmentEnd, t1, _CMP_GE_OQ);
    cx = _mm512_mask_add_epi32(cx, stepX, cx, dirX);
    cy = _mm512_mask_add_epi32(cy, stepY, cy, dirY);
    cz = _mm512_mask_add_epi32(cz, stepZ, cz, dirZ);
    // A lane steps along one axis at most, so one masked add per axis gives its index.
    index = _mm512_mask_add_epi32(index, stepX, index, dirX);
    index = _mm512_mask_add_epi32(index, stepY, index, strideY1);
    index = _mm512_mask_add_epi32(index, stepZ, index, strideZ1);
    exitX = _mm512_mask_add_ps(exitX, stepX, exitX, deltaX);
    exitY = _mm512_mask_add_ps(exitY, stepY, exitY, deltaY);
    exitZ = _mm512_mask_add_ps(exitZ, stepZ, exitZ, deltaZ);
    __m512 next = segmentEnd;
    if (jump != 0) {
      const __m512 far = _mm512_sub_ps(across, _mm512_set1_ps(1.0f));
      const __m512 cubeX = _mm512_add_ps(exitX, _mm512_mul_ps(far, deltaX)),
                   cubeY = _mm512_add_ps(exitY, _mm512_mul_ps(far, deltaY)),
                   cubeZ = _mm512_add_ps(exitZ, _mm512_mul_ps(far, deltaZ));
      const __mmask16 cxy = _mm512_cmp_ps_mask(cubeX, cubeY, _CMP_LE_OQ), cxz = _mm512_cmp_ps_mask(cubeX, cubeZ, _CMP_LE_OQ),
                      cyz = _mm512_cmp_ps_mask(cubeY, cubeZ, _CMP_LE_OQ);
      const __mmask16 leaveX = cxy & cxz, leaveY = __mmask16(~cxy & cyz), leaveZ = __mmask16(~(leaveX | leaveY));
      const __m512 tCube = _mm512_mask_blend_ps(leaveX, _mm512_mask_blend_ps(leaveY, cubeZ, cubeY), cubeX);
      const __m512 kx = facesCrossed(exitX, deltaX, leaveX, tCube, far, across),
                   ky = facesCrossed(exitY, deltaY, leaveY, tCube, far, across),
                   kz = facesCrossed(exitZ, deltaZ, leaveZ, tCube, far, across);
      cx = _mm512_mask_add_epi32(cx, jump, cx, _mm512_mullo_epi32(truncated16(kx), dirX));
      cy = _mm512_mask_add_epi32(cy, jump, cy, _mm512_mullo_epi32(truncated16(ky), dirY));
      cz = _mm512_mask_add_epi32(cz, jump, cz, _mm512_mullo_epi32(truncated16(kz), dirZ));
      // (cz * countY + cy) * countX + cx; lanes off the grid end below before their index is read
      index = _mm512_mask_mov_epi32(
          index, jump,
          _mm512_add_epi32(_mm512_mullo_epi32(_mm512_add_epi32(_mm512_mullo_epi32(cz, limitY), cy), limitX), cx));
      exitX = _mm512_mask_add_ps(exitX, jump, exitX, _mm512_mul_ps(kx, deltaX));
      exitY = _mm512_mask_add_ps(exitY, jump, exitY, _mm512_mul_ps(ky, deltaY));
      exitZ = _mm512_mask_add_ps(exitZ, jump, exitZ, _mm512_mul_ps(kz, deltaZ));
      ended = __mmask16((ended & ~jump) | (jump & _mm512_cmp_ps_mask(tCube, t1, _CMP_GE_OQ)));
      next = _mm512_mask_blend_ps(jump, segmentEnd, tCube);
    }
    // The walk's end (its last segment, or a step off the grid).
    const __mmask16 outside =
        _mm512_cmplt_epi32_mask(cx, zeroI) | _mm512_cmpge_epi32_mask(cx, limitX) | _mm512_cmplt_epi32_mask(cy, zeroI) |
        _mm512_cmpge_epi32_mask(cy, limitY) | _mm512_cmplt_epi32_mask(cz, zeroI) | _mm512_cmpge_epi32_mask(cz, limitZ);
    active &= __mmask16(~(ended | outside));
    t = max16(next, t);  // std::max(t, segmentEnd or the cube's exit)
  }
}

//! The box the walks are clipped to and the grid's size: what startWalk reads.
struct StartConstants {
  float lo[3], hi[3];  //!< depthLo_, depthHi_
  int count[3];
};

//! (a < b) ? b : a, as std::max(a, b); and (b < a) ? b : a, as std::min(a, b).
KDSWAP_AVX512 inline __m512 maxOf(__m512 a, __m512 b) {
  return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(a, b, _CMP_LT_OQ), a, b);
}
KDSWAP_AVX512 inline __m512 minOf(__m512 a, __m512 b) {
  return _mm512_mask_blend_ps(_mm512_cmp_ps_mask(b, a, _CMP_LT_OQ), a, b);
}

//! OcclusionGrid::startWalk for sixteen rays, each lane performing its operations in the same
//! order; returns the lanes that start (the scalar start returns true).
KDSWAP_AVX512 __mmask16 startSixteen(const StartConstants& c, const __m512* o, const __m512* d, __m512 phase,
                                     float step, Lanes& out) {
  const __m512 zero = _mm512_setzero_ps();
  __m512 t0 = zero, t1 = _mm512_set1_ps(std::numeric_limits<float>::max());
  __mmask16 refused = 0, flat[3];
  for (int a = 0; a < 3; ++a) {
    const __m512 lo = _mm512_set1_ps(c.lo[a]), hi = _mm512_set1_ps(c.hi[a]);
    flat[a] = _mm512_cmp_ps_mask(d[a], zero, _CMP_EQ_OQ);  // d[a] == 0: outside the slab ends the walk
    refused |= flat[a] & (_mm512_cmp_ps_mask(o[a], lo, _CMP_LT_OQ) | _mm512_cmp_ps_mask(o[a], hi, _CMP_GT_OQ));
    const __m512 ta = _mm512_div_ps(_mm512_sub_ps(lo, o[a]), d[a]), tb = _mm512_div_ps(_mm512_sub_ps(hi, o[a]), d[a]);
    const __mmask16 swap = _mm512_cmp_ps_mask(ta, tb, _CMP_GT_OQ);
    const __m512 near = _mm512_mask_blend_ps(swap, ta, tb), far = _mm512_mask_blend_ps(swap, tb, ta);
    t0 = _mm512_mask_blend_ps(flat[a], maxOf(t0, near), t0);
    t1 = _mm512_mask_blend_ps(flat[a], minOf(t1, far), t1);
  }
  // !(t1 - t0 > 2 step)
  refused |= _mm512_cmp_ps_mask(_mm512_sub_ps(t1, t0), _mm512_set1_ps(2.0f * step), _CMP_NGT_UQ);
  const __mmask16 keep = __mmask16(~refused);
  const float cellSize = float(1 << CellRangeGrid::kShift);
  __m512i cell[3], dir[3];
  __m512 exit[3], delta[3];
  for (int a = 0; a < 3; ++a) {
    const __m512 start = _mm512_add_ps(o[a], _mm512_mul_ps(d[a], t0));  // o + d * t0
    const __m512i floored = truncated16(floor16(_mm512_div_ps(start, _mm512_set1_ps(cellSize))));
    // std::clamp(v, 0, count - 1)
    cell[a] = _mm512_maskz_min_epi32(kAll, _mm512_maskz_max_epi32(kAll, floored, _mm512_setzero_si512()),
                                     _mm512_set1_epi32(c.count[a] - 1));
    const __mmask16 up = _mm512_cmp_ps_mask(d[a], zero, _CMP_GT_OQ);
    dir[a] = _mm512_mask_blend_epi32(up, _mm512_set1_epi32(-1), _mm512_set1_epi32(1));
    // boundary = float((cell + (d > 0 ? 1 : 0)) * kCell); exit = (boundary - o) / d; delta = kCell / |d|
    const __m512i face = _mm512_mask_add_epi32(cell[a], up, cell[a], _mm512_set1_epi32(1));
    const __m512 boundary = toFloat16(_mm512_maskz_slli_epi32(kAll, face, CellRangeGrid::kShift));
    exit[a] = _mm512_mask_blend_ps(flat[a], _mm512_div_ps(_mm512_sub_ps(boundary, o[a]), d[a]),
                                   _mm512_set1_ps(std::numeric_limits<float>::infinity()));
    delta[a] = _mm512_maskz_mov_ps(__mmask16(~flat[a]), _mm512_div_ps(_mm512_set1_ps(cellSize), _mm512_abs_ps(d[a])));
  }
  out.t = t0, out.t1 = t1, out.phase = phase;
  out.exitX = exit[0], out.exitY = exit[1], out.exitZ = exit[2];
  out.deltaX = delta[0], out.deltaY = delta[1], out.deltaZ = delta[2];
  out.cx = cell[0], out.cy = cell[1], out.cz = cell[2];
  out.dirX = dir[0], out.dirY = dir[1], out.dirZ = dir[2];
  // Refused lanes never walk; their index is zeroed only so that nothing reads outside the grid.
  out.index = _mm512_maskz_mov_epi32(
      keep, _mm512_add_epi32(_mm512_mullo_epi32(_mm512_add_epi32(_mm512_mullo_epi32(cell[2], _mm512_set1_epi32(c.count[1])),
                                                                   cell[1]),
                                                  _mm512_set1_epi32(c.count[0])),
                               cell[0]));
  out.active = keep;
  for (int a = 0; a < 3; ++a) out.o[a] = o[a], out.d[a] = d[a];
  return keep;
}

//! Eight rays of `a` in lanes 0-7 and eight of `b` in lanes 8-15.
KDSWAP_AVX512 inline __m512 joined(const float* a, const float* b) {
  return _mm512_insertf32x8(_mm512_castps256_ps512(_mm256_loadu_ps(a)), _mm256_loadu_ps(b), 1);
}

KDSWAP_AVX512 __mmask16 startAndWalkSixteen(const FineTables& fine, const StartConstants& c, const float* depth,
                                            float threshold, const VoxelRays8& a, const VoxelRays8& b, float step,
                                            LaneEnds& ends) {
  const __m512 o[3] = {joined(a.ox, b.ox), joined(a.oy, b.oy), joined(a.oz, b.oz)};
  const __m512 d[3] = {joined(a.dx, b.dx), joined(a.dy, b.dy), joined(a.dz, b.dz)};
  Lanes lanes;
  const __mmask16 started = startSixteen(c, o, d, joined(a.phase, b.phase), step, lanes);
  if (started != 0) walkSixteen(fine, depth, c.count[0], c.count[1], c.count[2], threshold, step, lanes, ends);
  return started;
}

}  // namespace

bool OcclusionGrid::walkRays16(const VoxelRays8& a, const VoxelRays8& b, float step, long* out) const {
  // Cell indices travel as 32-bit lanes.
  if (!cpuHasAvx512vl() || depth_.size() >= (std::size_t(1) << 31)) return false;
  const StartConstants constants{{depthLo_.x, depthLo_.y, depthLo_.z}, {depthHi_.x, depthHi_.y, depthHi_.z},
                                 {count_.x, count_.y, count_.z}};
  LaneEnds ends;
  const FineTables fine{fineCode_.data() + fineOffset_, depthOfCode_};
  const unsigned started = startAndWalkSixteen(fine, constants, depth_.data(), threshold_, a, b, step, ends);
  for (int j = 0; j < kLanes; ++j)
    out[j] = !(started >> j & 1u)          ? kNever
             : (ends.reachedFine >> j & 1u) ? ends.answer[j]
             : (ends.reached >> j & 1u)     ? reachedAt(ends.sum[j], ends.depth[j], ends.first[j], ends.samples[j])
                                            : kNever;
  return true;
}

}  // namespace kdswap

#else

namespace kdswap {
bool OcclusionGrid::walkRays16(const VoxelRays8&, const VoxelRays8&, float, long*) const { return false; }
}  // namespace kdswap

#endif
