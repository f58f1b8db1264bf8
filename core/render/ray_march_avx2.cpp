// AVX2 ray march: eight consecutive lattice samples at once. [Sections] shading of eight samples
// | the march (empty-space test per group of eight, visible samples packed eight to a shading,
// the rays' last few samples packed across rays; before it, eight rays at a time hop over the
// empty space in front of their first visible samples).
// Each step is the scalar reference's operation (ray_march.cpp, sample_shader.h) in the same
// order; nothing is fused (this file enables AVX2 only, not FMA, and the build compiles with
// -ffp-contract=off), so every lane rounds as the scalar code does and images are equal bit for
// bit. With float storage a sample's eight corner voxels are 4-float vectors (value, gradient), so
// interpolation runs on 4 lanes per sample, as TrilinearCell does (two samples per register); with
// compact storage each (y, z) pair of x corners is one 16-byte load of 16-bit integers, blended
// along x in integers (exact) and then converted, as interpolateCompact does (four samples per
// 512-bit register in the wide build, two per 256-bit one in the others). Either ends with one
// register per quantity; everything after it runs on eight samples per instruction. Samples in
// uniform cells (Brick::uniformCells) take their floor voxel's record instead, as the scalar march
// does (uniformRecord), and eight of one ray with one record are shaded once. The march is a
// template on the voxel type, so each format gets its own code without a test per sample.
#include "core/render/ray_march.h"

#include <climits>
#include <cstddef>
#include <cstring>
#include <type_traits>

#include "core/util/cpu_features.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>

namespace kdswap {
namespace {

// (Helpers are functions, not lambdas: a lambda does not inherit its enclosing function's target.)
// ray_march_avx512vl.cpp compiles this file again for CPUs with AVX-512 VL: the same 256-bit
// intrinsics, so the same operations and bits, but GCC may then use 32 vector registers (this
// march spills with 16) and masked forms; no 512-bit vectors (prefer-vector-width=256), which
// Intel cores pay for. ray_march_avx512.cpp compiles it a third time with KDSWAP_MARCH_WIDE as
// well: compact voxels are then interpolated four samples to a 512-bit register, which AMD's
// Zen 4 and Zen 5 run at full speed and an Intel Xeon (Sapphire Rapids class) does not.
#if defined(KDSWAP_MARCH_AVX512VL)
#define KDSWAP_AVX2 __attribute__((target("avx2,avx512f,avx512vl,avx512dq,avx512bw,prefer-vector-width=256")))
#if defined(KDSWAP_MARCH_WIDE)
#define KDSWAP_MARCH_ENTRY avx512MarchFunction
#else
#define KDSWAP_MARCH_ENTRY avx512vlMarchFunction
#endif
#define KDSWAP_MARCH_CPU cpuHasAvx512vl
#else
#define KDSWAP_AVX2 __attribute__((target("avx2")))
#define KDSWAP_MARCH_ENTRY avx2MarchFunction
#define KDSWAP_MARCH_CPU cpuHasAvx2
#endif

constexpr int kLanes = 8;

// ---- [Shading of eight samples] -----------------------------------------------------------------

//! Four floats at `low` in the low half and four at `high` in the high half.
KDSWAP_AVX2 inline __m256 loadPair(const float* low, const float* high) {
  return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_loadu_ps(low)), _mm_loadu_ps(high), 1);
}

//! Corner voxel at `offset` from sample j's floor voxel `a` (low half) and sample j + 4's `b`
//! (high half): 4-float vectors (value, gradient).
KDSWAP_AVX2 inline __m256 cornerPair(const Voxel* a, const Voxel* b, std::ptrdiff_t offset) {
  return loadPair(&a[offset].value, &b[offset].value);
}

//! Lane j of each 128-bit half of v, in every lane of that half: sample j's weight in the low half,
//! sample j + 4's in the high half. An in-lane shuffle (one cycle), not a cross-lane permute.
template <int j>
KDSWAP_AVX2 inline __m256 laneOfEachHalf(__m256 v) {
  return _mm256_permute_ps(v, _MM_SHUFFLE(j, j, j, j));
}

//! One corner's weighted voxels for samples j and j + 4 (their weights picked from eight).
template <int j>
KDSWAP_AVX2 inline __m256 term(__m256 weights, __m256 corners) {
  return _mm256_mul_ps(laneOfEachHalf<j>(weights), corners);
}

//! Value and gradient of samples j (low half) and j + 4 (high half) at once, whose floor voxels are
//! corner[j] and corner[j + 4]. `w[c]` holds corner c's weight of the eight samples.
//! Corners 000 100 010 110 001 101 011 111, summed in that order (as TrilinearCell).
template <int j>
KDSWAP_AVX2 inline __m256 interpolatePair(const Voxel* const* corner, std::ptrdiff_t sy, std::ptrdiff_t sz,
                                          const __m256* w) {
  const Voxel* a = corner[j];
  const Voxel* b = corner[j + 4];
  __m256 sum = _mm256_add_ps(term<j>(w[0], cornerPair(a, b, 0)), term<j>(w[1], cornerPair(a, b, 1)));
  sum = _mm256_add_ps(sum, term<j>(w[2], cornerPair(a, b, sy)));
  sum = _mm256_add_ps(sum, term<j>(w[3], cornerPair(a, b, sy + 1)));
  sum = _mm256_add_ps(sum, term<j>(w[4], cornerPair(a, b, sz)));
  sum = _mm256_add_ps(sum, term<j>(w[5], cornerPair(a, b, sz + 1)));
  sum = _mm256_add_ps(sum, term<j>(w[6], cornerPair(a, b, sz + sy)));
  return _mm256_add_ps(sum, term<j>(w[7], cornerPair(a, b, sz + sy + 1)));
}

//! Registers j = 0..3 each hold a 4-vector of lane j (low half) and of lane j + 4 (high half);
//! out[q] gets component q of all eight lanes, in lane order (a 4x4 transpose in each half).
KDSWAP_AVX2 inline void transposeHalves(const __m256* in, __m256* out) {
  const __m256 u0 = _mm256_unpacklo_ps(in[0], in[1]), u1 = _mm256_unpackhi_ps(in[0], in[1]);
  const __m256 u2 = _mm256_unpacklo_ps(in[2], in[3]), u3 = _mm256_unpackhi_ps(in[2], in[3]);
  out[0] = _mm256_shuffle_ps(u0, u2, _MM_SHUFFLE(1, 0, 1, 0));
  out[1] = _mm256_shuffle_ps(u0, u2, _MM_SHUFFLE(3, 2, 3, 2));
  out[2] = _mm256_shuffle_ps(u1, u3, _MM_SHUFFLE(1, 0, 1, 0));
  out[3] = _mm256_shuffle_ps(u1, u3, _MM_SHUFFLE(3, 2, 3, 2));
}

//! The eight lanes of `v` in `at`, for eight plain loads at those indices: through memory, where
//! GCC would otherwise extract the lanes one by one (~26 instructions against 10). The empty asm
//! keeps the compiler from folding the store back into lane extracts.
KDSWAP_AVX2 inline void lanesThroughMemory(__m256i v, int (&at)[kLanes]) {
  _mm256_store_si256(reinterpret_cast<__m256i*>(at), v);
  asm("" : "+m"(at));
}

//! TransferTable::lookup of eight samples at entries `index` (already clamped) and fractions
//! `frac`: each lane's entries i and i + 1 are adjacent (the table repeats its last entry), so
//! they are loaded as vectors and transposed, rather than gathered channel by channel.
//! out[0..3] = r, g, b, a, each e0 + frac * (e1 - e0).
KDSWAP_AVX2 inline void lookup8(const glm::vec4* entries, __m256i index, __m256 frac, __m256* out) {
  alignas(32) int at[kLanes];  // byte offsets: 16 per entry
  lanesThroughMemory(_mm256_slli_epi32(index, 4), at);
  const char* base = reinterpret_cast<const char*>(entries);
  __m256 first[4], second[4];
  for (int j = 0; j < 4; ++j) {
    const float* a = reinterpret_cast<const float*>(base + at[j]);
    const float* b = reinterpret_cast<const float*>(base + at[j + 4]);
    first[j] = loadPair(a, b);
    second[j] = loadPair(a + 4, b + 4);
  }
  __m256 e0[4], e1[4];
  transposeHalves(first, e0);
  transposeHalves(second, e1);
  for (int c = 0; c < 4; ++c) out[c] = _mm256_add_ps(e0[c], _mm256_mul_ps(frac, _mm256_sub_ps(e1[c], e0[c])));
}

//! min(1, c * light + highlight), as glm::min(colour * light + highlight, vec3(1)).
KDSWAP_AVX2 inline __m256 lit(__m256 c, __m256 light, __m256 highlight) {
  return _mm256_min_ps(_mm256_set1_ps(1.0f), _mm256_add_ps(_mm256_mul_ps(c, light), highlight));
}

//! The floats at table[i], table[i + 1], table[j], table[j + 1]: two 8-byte loads.
KDSWAP_AVX2 inline __m128 twoPairs(const float* table, int i, int j) {
  return _mm_loadh_pi(_mm_loadl_pi(_mm_setzero_ps(), reinterpret_cast<const __m64*>(table + i)),
                      reinterpret_cast<const __m64*>(table + j));
}

//! Entries is[j] and is[j] + 1 of the specular table for eight lanes. Each lane's two adjacent
//! floats are one 8-byte load at an index read back from memory (lanesThroughMemory): eight plain
//! loads, not gathers. A gather cost 11% of the paper cell's frame on an Intel Xeon (Sapphire
//! Rapids class), and AMD Zen 4 issues one load per gathered element anyway.
KDSWAP_AVX2 inline void specularPairs(const float* table, __m256i is, __m256& s0, __m256& s1) {
  alignas(32) int at[kLanes];
  lanesThroughMemory(is, at);
  // low = (e0 f0 e1 f1 | e2 f2 e3 f3), high the same for lanes 4..7 (e: entry, f: the next one).
  const __m256 low = _mm256_insertf128_ps(_mm256_castps128_ps256(twoPairs(table, at[0], at[1])),
                                          twoPairs(table, at[2], at[3]), 1);
  const __m256 high = _mm256_insertf128_ps(_mm256_castps128_ps256(twoPairs(table, at[4], at[5])),
                                           twoPairs(table, at[6], at[7]), 1);
  const __m256 entries = _mm256_shuffle_ps(low, high, _MM_SHUFFLE(2, 0, 2, 0));  // e0 e1 e4 e5 | e2 e3 e6 e7
  const __m256 nexts = _mm256_shuffle_ps(low, high, _MM_SHUFFLE(3, 1, 3, 1));
  s0 = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(entries), _MM_SHUFFLE(3, 1, 2, 0)));
  s1 = _mm256_castpd_ps(_mm256_permute4x64_pd(_mm256_castps_pd(nexts), _MM_SHUFFLE(3, 1, 2, 0)));
}

//! One ray's last shading of a uniform record: its groups in one uniform region repeat it.
struct UniformShade {
  __m128 record;  //!< value, gradient
  ShadedSample shaded;
  bool valid = false;
};

struct Shaded8 {
  alignas(32) float r[kLanes], g[kLanes], b[kLanes], a[kLanes];
  int contributing = 0;  //!< bit j: !(a[j] <= 0); colour is computed only when some bit is set
};

//! A direction per lane (the light, which is at the eye: each ray's own).
struct Directions8 {
  __m256 x, y, z;
};

KDSWAP_AVX2 inline Directions8 sameDirection(const glm::vec3& d) {
  return Directions8{_mm256_set1_ps(d.x), _mm256_set1_ps(d.y), _mm256_set1_ps(d.z)};
}

//! The x and x + 1 records of a compact corner pair: one 16-byte load.
KDSWAP_AVX2 inline __m128i pairOf(const CompactVoxel* x) {
  return _mm_loadu_si128(reinterpret_cast<const __m128i*>(x));
}

//! Samples j (low half) and j + 4 (high half) of interpolateCompact8 (the 256-bit form): each (y, z)
//! pair of x corners blended by the x weights `wx`, converted, weighted by `yz` and summed in order.
template <int j>
KDSWAP_AVX2 inline __m256 compactPair(const CompactVoxel* const* corner, const std::ptrdiff_t* at, __m256i wx,
                                      const __m256* yz, __m256i shuffle) {
  const __m256i weights = _mm256_shuffle_epi32(wx, _MM_SHUFFLE(j, j, j, j));  // in-lane, as laneOfEachHalf
  __m256 sum = _mm256_setzero_ps();  // replaced by the first term: the sum is term 0 + 1 + 2 + 3, in order
  for (int c = 0; c < 4; ++c) {
    const __m256i raw =
        _mm256_inserti128_si256(_mm256_castsi128_si256(pairOf(corner[j] + at[c])), pairOf(corner[j + 4] + at[c]), 1);
    const __m256i blended = _mm256_madd_epi16(_mm256_shuffle_epi8(raw, shuffle), weights);
    const __m256 term = _mm256_mul_ps(_mm256_cvtepi32_ps(blended), laneOfEachHalf<j>(yz[c]));
    sum = c == 0 ? term : _mm256_add_ps(sum, term);
  }
  return sum;
}

//! interpolateCompact for eight samples: sample j's corner record at its floor is corner[j]. Both
//! x corners of a (y, z) pair come in one 16-byte load; a byte shuffle pairs each quantity's two
//! 16-bit words, and one multiply-add of 16-bit pairs (pmaddwd) blends them with the integer x
//! weights, exactly, into 32 bits: four quantities of a sample in 128 bits. Then each pair is
//! converted, weighted by its (y, z) weight (times 2^-14) and summed over the pairs in order.
//! out[q]: component q (value, gradient x, y, z) of the eight samples, in lane order.
KDSWAP_AVX2 inline void interpolateCompact8(const CompactVoxel* const* corner, std::ptrdiff_t sy, std::ptrdiff_t sz,
                                            __m256 fx, __m256 fy, __m256 fz, __m256* out) {
  const __m256 one = _mm256_set1_ps(1.0f), scale = _mm256_set1_ps(kCompactXWeightScale);
  const __m256 gy = _mm256_sub_ps(one, fy), gz = _mm256_mul_ps(_mm256_sub_ps(one, fz), scale);
  const __m256 fzScaled = _mm256_mul_ps(fz, scale);
  const __m256 yz[4] = {_mm256_mul_ps(gy, gz), _mm256_mul_ps(fy, gz), _mm256_mul_ps(gy, fzScaled),
                        _mm256_mul_ps(fy, fzScaled)};
  // x weights (2^14 - w, w), w = fx * 2^14 rounded to nearest even, as one 32-bit word per sample:
  // the low 16 bits multiply the x corner's word, the high 16 bits the x + 1 corner's.
  const __m256i wx1 = _mm256_cvtps_epi32(_mm256_mul_ps(fx, _mm256_set1_ps(float(1 << kCompactXWeightBits))));
  const __m256i wx0 = _mm256_sub_epi32(_mm256_set1_epi32(1 << kCompactXWeightBits), wx1);
  const __m256i wx = _mm256_or_si256(wx0, _mm256_slli_epi32(wx1, 16));
  // Words (v g0 g1 g2 | v' g0' g1' g2') of a corner pair to (v v' g0 g0' g1 g1' g2 g2').
  const __m128i pairWords = _mm_setr_epi8(0, 1, 8, 9, 2, 3, 10, 11, 4, 5, 12, 13, 6, 7, 14, 15);
  const std::ptrdiff_t at[4] = {0, sy, sz, sz + sy};
#if defined(KDSWAP_MARCH_WIDE)
  // Four samples a register, one per 128-bit lane: samples 0-3, then 4-7. The zero-masking forms
  // with every lane set are the plain instructions; GCC 12's unmasked ones warn of an undefined
  // pass-through operand.
  constexpr __mmask16 kAll16 = 0xFFFF;
  const __m512i shuffle = _mm512_maskz_broadcast_i32x4(kAll16, pairWords);
  __m512 sums[2];
  for (int h = 0; h < 2; ++h) {
    const int j = 4 * h;
    const __m512i spread = _mm512_set_epi32(j + 3, j + 3, j + 3, j + 3, j + 2, j + 2, j + 2, j + 2, j + 1, j + 1,
                                            j + 1, j + 1, j, j, j, j);
    const __m512i weights = _mm512_maskz_permutexvar_epi32(kAll16, spread, _mm512_castsi256_si512(wx));
    for (int c = 0; c < 4; ++c) {
      __m512i raw = _mm512_castsi128_si512(pairOf(corner[j] + at[c]));
      raw = _mm512_inserti32x4(raw, pairOf(corner[j + 1] + at[c]), 1);
      raw = _mm512_inserti32x4(raw, pairOf(corner[j + 2] + at[c]), 2);
      raw = _mm512_inserti32x4(raw, pairOf(corner[j + 3] + at[c]), 3);
      const __m512i words = _mm512_maskz_shuffle_epi8(~__mmask64(0), raw, shuffle);
      const __m512i blended = _mm512_maskz_madd_epi16(kAll16, words, weights);
      const __m512 term = _mm512_mul_ps(_mm512_maskz_cvtepi32_ps(kAll16, blended),
                                        _mm512_maskz_permutexvar_ps(kAll16, spread, _mm512_castps256_ps512(yz[c])));
      sums[h] = c == 0 ? term : _mm512_add_ps(sums[h], term);
    }
  }
  // Lane j of out[q] is quantity q of sample j: word 4j + q of samples 0-3, then of 4-7.
  for (int q = 0; q < 4; ++q) {
    const __m512i from =
        _mm512_setr_epi32(q, 4 + q, 8 + q, 12 + q, 16 + q, 20 + q, 24 + q, 28 + q, 0, 0, 0, 0, 0, 0, 0, 0);
    out[q] = _mm512_maskz_extractf32x8_ps(0xFF, _mm512_maskz_permutex2var_ps(kAll16, sums[0], from, sums[1]), 0);
  }
#else
  // Two samples a register: j in the low half, j + 4 in the high half, as transposeHalves takes them.
  const __m256i shuffle = _mm256_broadcastsi128_si256(pairWords);
  const __m256 t[4] = {compactPair<0>(corner, at, wx, yz, shuffle), compactPair<1>(corner, at, wx, yz, shuffle),
                       compactPair<2>(corner, at, wx, yz, shuffle), compactPair<3>(corner, at, wx, yz, shuffle)};
  transposeHalves(t, out);
#endif
}

//! uniformRecord for eight samples whose floor records are corner[j]: out[q] is component q
//! (value, gradient x, y, z) of the eight, in lane order, as floats (compact: stored units).
KDSWAP_AVX2 inline void records8(const Voxel* const* corner, __m256* out) {
  const __m256 t[4] = {cornerPair(corner[0], corner[4], 0), cornerPair(corner[1], corner[5], 0),
                       cornerPair(corner[2], corner[6], 0), cornerPair(corner[3], corner[7], 0)};
  transposeHalves(t, out);
}
KDSWAP_AVX2 inline void records8(const CompactVoxel* const* corner, __m256* out) {
  __m256 t[4];
  for (int j = 0; j < 4; ++j) {  // sample j's four 16-bit words, then sample j + 4's, widened exactly
    const __m128i words = _mm_unpacklo_epi64(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(corner[j])),
                                             _mm_loadl_epi64(reinterpret_cast<const __m128i*>(corner[j + 4])));
    t[j] = _mm256_cvtepi32_ps(_mm256_cvtepi16_epi32(words));
  }
  transposeHalves(t, out);
}

//! shadeSample (or shadeCompactSample) for eight samples at points (px, py, pz) with voxels
//! corner[j] at their floors and lane j's light direction toLight lane j. Lanes set in `uniform`
//! lie in uniform cells and take their floor record instead of interpolating (uniformRecord);
//! when all do, the corners are not loaded at all. With `ray` (every lane is one ray's, with its
//! light) and all eight records equal, one sample is shaded for all eight (shadeInterpolated: the
//! same operations, so the same bits as every lane's), or taken from the ray's last such shading
//! when the record is the same.
template <typename VoxelT>
KDSWAP_AVX2 void shade8(const MarchContext& m, const Directions8& toLight, UniformShade* ray, __m256 px, __m256 py,
                        __m256 pz, const VoxelT* const* corner, __m256i uniform, Shaded8& out) {
  const ShadingParameters& params = m.shading;
  const __m256 one = _mm256_set1_ps(1.0f);
  // p >= 0: truncation is floor.
  const __m256 fx = _mm256_sub_ps(px, _mm256_cvtepi32_ps(_mm256_cvttps_epi32(px)));
  const __m256 fy = _mm256_sub_ps(py, _mm256_cvtepi32_ps(_mm256_cvttps_epi32(py)));
  const __m256 fz = _mm256_sub_ps(pz, _mm256_cvtepi32_ps(_mm256_cvttps_epi32(pz)));
  const std::ptrdiff_t sy = m.voxels.sy, sz = m.voxels.sz;
  const int uniformLanes = _mm256_movemask_ps(_mm256_castsi256_ps(uniform));
  __m256 q[4];
  if (uniformLanes == 0xFF) {
    records8(corner, q);
    if (ray) {
      __m256 same = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
      for (int c = 0; c < 4; ++c)
        same = _mm256_and_ps(same, _mm256_cmp_ps(q[c], _mm256_permutevar8x32_ps(q[c], _mm256_setzero_si256()), _CMP_EQ_OQ));
      if (_mm256_movemask_ps(same) == 0xFF) {
        const __m128 record = _mm_setr_ps(_mm256_cvtss_f32(q[0]), _mm256_cvtss_f32(q[1]), _mm256_cvtss_f32(q[2]),
                                          _mm256_cvtss_f32(q[3]));
        if (!ray->valid || _mm_movemask_ps(_mm_cmpeq_ps(record, ray->record)) != 0xF) {
          const glm::vec3 light(_mm256_cvtss_f32(toLight.x), _mm256_cvtss_f32(toLight.y), _mm256_cvtss_f32(toLight.z));
          TrilinearCell::Lanes lanes;
          std::memcpy(&lanes, &record, sizeof lanes);
          ray->shaded = shadeInterpolated(params, light, lanes);
          ray->record = record;
          ray->valid = true;
        }
        const ShadedSample& one = ray->shaded;
        out.contributing = one.a <= 0.0f ? 0 : 0xFF;
        _mm256_store_ps(out.a, _mm256_set1_ps(one.a));
        if (out.contributing != 0) {
          _mm256_store_ps(out.r, _mm256_set1_ps(one.r));
          _mm256_store_ps(out.g, _mm256_set1_ps(one.g));
          _mm256_store_ps(out.b, _mm256_set1_ps(one.b));
        }
        return;
      }
    }
  } else if constexpr (std::is_same_v<VoxelT, CompactVoxel>) {
    interpolateCompact8(corner, sy, sz, fx, fy, fz, q);
  } else {
    const __m256 gx = _mm256_sub_ps(one, fx), gy = _mm256_sub_ps(one, fy), gz = _mm256_sub_ps(one, fz);
    const __m256 w[8] = {
        _mm256_mul_ps(_mm256_mul_ps(gx, gy), gz), _mm256_mul_ps(_mm256_mul_ps(fx, gy), gz),
        _mm256_mul_ps(_mm256_mul_ps(gx, fy), gz), _mm256_mul_ps(_mm256_mul_ps(fx, fy), gz),
        _mm256_mul_ps(_mm256_mul_ps(gx, gy), fz), _mm256_mul_ps(_mm256_mul_ps(fx, gy), fz),
        _mm256_mul_ps(_mm256_mul_ps(gx, fy), fz), _mm256_mul_ps(_mm256_mul_ps(fx, fy), fz)};
    // Samples j and j + 4 share a register; a 4x4 transpose in each half then gives one register
    // per quantity with the samples in order.
    const __m256 t[4] = {interpolatePair<0>(corner, sy, sz, w), interpolatePair<1>(corner, sy, sz, w),
                         interpolatePair<2>(corner, sy, sz, w), interpolatePair<3>(corner, sy, sz, w)};
    transposeHalves(t, q);
  }
  if (uniformLanes != 0 && uniformLanes != 0xFF) {
    __m256 record[4];
    records8(corner, record);
    for (int c = 0; c < 4; ++c) q[c] = _mm256_blendv_ps(q[c], record[c], _mm256_castsi256_ps(uniform));
  }
  const __m256 value = q[0], gradX = q[1], gradY = q[2], gradZ = q[3];

  // TransferTable::lookup: clamp (NaN to 0), then linear between entries i and i + 1.
  const float last = float(TransferTable::kSize - 1);
  const __m256 s = _mm256_add_ps(_mm256_mul_ps(value, _mm256_set1_ps(params.scale)), _mm256_set1_ps(params.bias));
  __m256 f = _mm256_mul_ps(s, _mm256_set1_ps(last));
  f = _mm256_and_ps(f, _mm256_cmp_ps(f, _mm256_setzero_ps(), _CMP_GE_OQ));
  f = _mm256_blendv_ps(f, _mm256_set1_ps(last), _mm256_cmp_ps(f, _mm256_set1_ps(last), _CMP_GT_OQ));
  const __m256i i0 = _mm256_cvttps_epi32(f);
  const __m256 frac = _mm256_sub_ps(f, _mm256_cvtepi32_ps(i0));
  __m256 tf[4];
  lookup8(params.table->entries(), i0, frac, tf);
  // Where no sample is visible (common in sparse data), colour and shading are never used.
  out.contributing = _mm256_movemask_ps(_mm256_cmp_ps(tf[3], _mm256_setzero_ps(), _CMP_NLE_UQ));  // !(a <= 0), as add()
  _mm256_store_ps(out.a, tf[3]);
  if (out.contributing == 0) return;
  if (!params.shading) {
    _mm256_store_ps(out.r, tf[0]), _mm256_store_ps(out.g, tf[1]), _mm256_store_ps(out.b, tf[2]);
    return;
  }
  // Lambert term |g.l| / |g| (1 where the gradient is 0); dot products summed x + y + z, as glm::dot.
  const __m256 len2 = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(gradX, gradX), _mm256_mul_ps(gradY, gradY)),
                                    _mm256_mul_ps(gradZ, gradZ));
  const __m256 dotL = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(gradX, toLight.x), _mm256_mul_ps(gradY, toLight.y)),
                                    _mm256_mul_ps(gradZ, toLight.z));
  const __m256 absDot = _mm256_andnot_ps(_mm256_set1_ps(-0.0f), dotL);
  const __m256 lambert = _mm256_blendv_ps(one, _mm256_div_ps(absDot, _mm256_sqrt_ps(len2)),
                                          _mm256_cmp_ps(len2, _mm256_setzero_ps(), _CMP_GT_OQ));
  // Specular table, linear between entries; std::min(x, 1.0f) is minps(1, x).
  const __m256 fs = _mm256_mul_ps(_mm256_min_ps(one, lambert), _mm256_set1_ps(float(kSpecularEntries)));
  const __m256i is = _mm256_min_epi32(_mm256_cvttps_epi32(fs), _mm256_set1_epi32(kSpecularEntries - 1));
  __m256 s0, s1;
  specularPairs(params.specularTable, is, s0, s1);
  const __m256 highlight = _mm256_mul_ps(
      _mm256_set1_ps(params.specular),
      _mm256_add_ps(s0, _mm256_mul_ps(_mm256_sub_ps(fs, _mm256_cvtepi32_ps(is)), _mm256_sub_ps(s1, s0))));
  const __m256 light =
      _mm256_add_ps(_mm256_set1_ps(params.ambient), _mm256_mul_ps(_mm256_set1_ps(params.diffuse), lambert));
  _mm256_store_ps(out.r, lit(tf[0], light, highlight));
  _mm256_store_ps(out.g, lit(tf[1], light, highlight));
  _mm256_store_ps(out.b, lit(tf[2], light, highlight));
}

// ---- [The march] --------------------------------------------------------------------------------
// Every group of eight consecutive lattice samples is tested against the empty-space map at once;
// its visible samples are packed, in order, behind those still waiting from earlier groups, and
// each time eight are waiting they are shaded and composited together (FrontToBack::addEight, in
// lanes). The groups are therefore exactly the scalar march's (every sample in a visible cell, in
// lattice order, eight at a time). A ray's last, partial eight is handed back to the batch, which
// packs the tails of several rays into one shading (TailPacker), so few lanes idle there either.
// Where a group ends in empty space the ray jumps to the farthest exit of the empty cubes around
// its invisible samples. In a brick with no empty cell the map is not read at all (kAllVisible).

//! Samples k .. k + 7 of a ray (those up to `last`): points, cells, the cells' reach, voxel offsets.
struct Group {
  __m256 px, py, pz;
  __m256i cx, cy, cz, reach, offset;
  __m256i uniform;  //!< all ones in lanes whose cell is uniform (kUniformBit; only with kUniform)
  int n, visible;  //!< samples in the segment; bit j: sample k + j lies in a cell that can be visible
};

//! A brick's march constants in registers, set up once per batch of rays.
struct BrickConstants {
  __m256i lane, cellLoX, cellLoY, cellLoZ, countX, countY, loX, loY, loZ, sy, sz;
  __m256 boxLoX, boxLoY, boxLoZ, boxHiX, boxHiY, boxHiZ;  //!< owned box, for the empty cubes' faces
  __m128i cellShift;  //!< shift count: voxel index -> cell index
};

KDSWAP_AVX2 inline BrickConstants brickConstants(const MarchContext& m) {
  BrickConstants c;
  c.lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  c.cellLoX = _mm256_set1_epi32(m.cellLo.x), c.cellLoY = _mm256_set1_epi32(m.cellLo.y),
  c.cellLoZ = _mm256_set1_epi32(m.cellLo.z);
  c.countX = _mm256_set1_epi32(m.cellCount.x), c.countY = _mm256_set1_epi32(m.cellCount.y);
  c.loX = _mm256_set1_epi32(m.storedLo.x), c.loY = _mm256_set1_epi32(m.storedLo.y), c.loZ = _mm256_set1_epi32(m.storedLo.z);
  c.sy = _mm256_set1_epi32(int(m.voxels.sy)), c.sz = _mm256_set1_epi32(int(m.voxels.sz));
  c.boxLoX = _mm256_set1_ps(m.lo.x), c.boxLoY = _mm256_set1_ps(m.lo.y), c.boxLoZ = _mm256_set1_ps(m.lo.z);
  c.boxHiX = _mm256_set1_ps(m.hi.x), c.boxHiY = _mm256_set1_ps(m.hi.y), c.boxHiZ = _mm256_set1_ps(m.hi.z);
  c.cellShift = _mm_cvtsi32_si128(m.cellShift);
  return c;
}

//! One ray's lattice in registers.
struct RayLanes {
  __m256 ox, oy, oz, dx, dy, dz, phase, step;
};

//! The cell (relative to the brick's first) of voxel indices (ix, iy, iz) along one axis.
KDSWAP_AVX2 inline __m256i cellAxis(__m256i voxel, __m128i shift, __m256i cellLo) {
  return _mm256_sub_epi32(_mm256_sra_epi32(voxel, shift), cellLo);
}

//! The march codes (MarchContext::cellCodes) at relative cells (cx, cy, cz); lanes outside `lanes` read
//! cell 0's.
KDSWAP_AVX2 __attribute__((always_inline)) inline __m256i codeAt(const BrickConstants& bc, const std::uint8_t* codes,
                                                                 __m256i cx, __m256i cy, __m256i cz, __m256i lanes) {
  const __m256i cell = _mm256_and_si256(
      _mm256_add_epi32(_mm256_mullo_epi32(_mm256_add_epi32(_mm256_mullo_epi32(cz, bc.countY), cy), bc.countX), cx), lanes);
  return _mm256_and_si256(_mm256_i32gather_epi32(reinterpret_cast<const int*>(codes), cell, 1), _mm256_set1_epi32(0xFF));
}

//! The reach part of codes.
KDSWAP_AVX2 inline __m256i reachOf(__m256i codes) {
  return _mm256_and_si256(codes, _mm256_set1_epi32(EmptySpaceMap::kReachMask));
}

template <bool kAllVisible, bool kUniform>
KDSWAP_AVX2 __attribute__((always_inline)) inline void groupAt(const BrickConstants& bc, const RayLanes& r,
                                                               const std::uint8_t* codeMap, long k, long last, Group& g) {
  g.n = int(std::min<long>(kLanes, last - k + 1));
  // Points k .. k + 7 exactly as RaySegment::point computes them (k + j fits an int: it is a
  // sample index along one ray).
  const __m256 t =
      _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(_mm256_add_epi32(_mm256_set1_epi32(int(k)), bc.lane)), r.phase), r.step);
  g.px = _mm256_add_ps(r.ox, _mm256_mul_ps(r.dx, t)), g.py = _mm256_add_ps(r.oy, _mm256_mul_ps(r.dy, t)),
  g.pz = _mm256_add_ps(r.oz, _mm256_mul_ps(r.dz, t));
  const __m256i ix = _mm256_cvttps_epi32(g.px), iy = _mm256_cvttps_epi32(g.py), iz = _mm256_cvttps_epi32(g.pz);
  g.cx = cellAxis(ix, bc.cellShift, bc.cellLoX), g.cy = cellAxis(iy, bc.cellShift, bc.cellLoY),
  g.cz = cellAxis(iz, bc.cellShift, bc.cellLoZ);
  if constexpr (!kUniform) g.uniform = _mm256_setzero_si256();
  if constexpr (kAllVisible) {  // every reach is 0 (MarchContext::allVisible): the gather would read zeros
    g.reach = _mm256_setzero_si256();
    g.visible = (1 << g.n) - 1;
  } else {
    // Lanes past the segment look at cell 0.
    const __m256i codes = codeAt(bc, codeMap, g.cx, g.cy, g.cz, _mm256_cmpgt_epi32(_mm256_set1_epi32(g.n), bc.lane));
    g.reach = reachOf(codes);
    if constexpr (kUniform) g.uniform = _mm256_cmpgt_epi32(codes, _mm256_set1_epi32(EmptySpaceMap::kReachMask));
    g.visible =
        _mm256_movemask_ps(_mm256_castsi256_ps(_mm256_cmpeq_epi32(g.reach, _mm256_setzero_si256()))) & ((1 << g.n) - 1);
  }
  g.offset = _mm256_add_epi32(_mm256_add_epi32(_mm256_mullo_epi32(_mm256_sub_epi32(iz, bc.loZ), bc.sz),
                                               _mm256_mullo_epi32(_mm256_sub_epi32(iy, bc.loY), bc.sy)),
                              _mm256_sub_epi32(ix, bc.loX));
}

//! Where t leaves, along one axis, the empty cubes of cells (absolute) `cell` with reach `reach`:
//! the far face in the ray's direction (clamped to the owned box), +infinity when the ray is
//! parallel to the axis. As RaySegment::resumeAfterEmpty.
KDSWAP_AVX2 inline __m256 cubeExit(__m256i cell, __m256i reach, __m256 boxLo, __m256 boxHi, __m128i shift, float origin,
                                   float direction, float inverse) {
  if (direction == 0.0f) return _mm256_set1_ps(std::numeric_limits<float>::infinity());
  const __m256 face =
      direction > 0.0f
          ? _mm256_min_ps(_mm256_cvtepi32_ps(_mm256_sll_epi32(_mm256_add_epi32(cell, reach), shift)), boxHi)
          : _mm256_max_ps(_mm256_cvtepi32_ps(_mm256_sll_epi32(
                              _mm256_sub_epi32(cell, _mm256_sub_epi32(reach, _mm256_set1_epi32(1))), shift)),
                          boxLo);
  return _mm256_mul_ps(_mm256_sub_ps(face, _mm256_set1_ps(origin)), _mm256_set1_ps(inverse));
}

//! The group's samples in `invisible` lie in empty cubes (see RaySegment::resumeAfterEmpty): the
//! largest lattice index the ray may step on from, i.e. every sample before it and after the
//! group's first is invisible or was in the group. Computed for all lanes at once; the farthest wins.
KDSWAP_AVX2 inline long farthestResume(const BrickConstants& bc, const RaySegment& s, const Group& g, int invisible) {
  const __m256 exitX = cubeExit(_mm256_add_epi32(g.cx, bc.cellLoX), g.reach, bc.boxLoX, bc.boxHiX, bc.cellShift,
                                s.origin.x, s.direction.x, s.inverseDirection.x);
  const __m256 exitY = cubeExit(_mm256_add_epi32(g.cy, bc.cellLoY), g.reach, bc.boxLoY, bc.boxHiY, bc.cellShift,
                                s.origin.y, s.direction.y, s.inverseDirection.y);
  const __m256 exitZ = cubeExit(_mm256_add_epi32(g.cz, bc.cellLoZ), g.reach, bc.boxLoZ, bc.boxHiZ, bc.cellShift,
                                s.origin.z, s.direction.z, s.inverseDirection.z);
  const __m256 tExit = _mm256_min_ps(_mm256_min_ps(exitX, exitY), exitZ);
  // floor(tExit / step - phase), capped past the segment's end so the conversion cannot overflow.
  __m256 index = _mm256_floor_ps(
      _mm256_sub_ps(_mm256_mul_ps(tExit, _mm256_set1_ps(s.inverseStep)), _mm256_set1_ps(s.phase)));
  index = _mm256_min_ps(index, _mm256_set1_ps(float(s.last) + 1.0f));
  alignas(32) int at[kLanes];
  _mm256_store_si256(reinterpret_cast<__m256i*>(at), _mm256_cvttps_epi32(index));
  long farthest = LONG_MIN;
  for (int bits = invisible; bits != 0; bits &= bits - 1) farthest = std::max<long>(farthest, at[__builtin_ctz(bits)]);
  return farthest - 1;  // one index early, for rounding, as the scalar rule
}

//! Lane j takes lane (j + by) mod 8 when used as a permutation: moves lanes down by `by` (up for
//! a negative `by`), wrapping around. The march and the tail packer place samples with it.
KDSWAP_AVX2 inline __m256i rotation(int by) {
  return _mm256_and_si256(_mm256_add_epi32(_mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7), _mm256_set1_epi32(by)),
                          _mm256_set1_epi32(7));
}

//! For each mask of eight lanes, the indices of its set lanes in order (lane j of the packed
//! vector takes lane idx[j]); unused entries are 0. One byte per lane.
struct PackTable {
  std::uint64_t indices[256];
  constexpr PackTable() : indices{} {
    for (int mask = 0; mask < 256; ++mask) {
      int packed = 0;
      for (int j = 0; j < kLanes; ++j)
        if (mask >> j & 1) indices[mask] |= std::uint64_t(j) << (8 * packed++);
    }
  }
};
constexpr PackTable kPackTable;

//! Visible samples waiting to be shaded: lanes 0 .. size - 1, in lattice order.
struct Waiting {
  __m256 x, y, z;
  __m256i offset, uniform;
  int size;
};

//! FrontToBack::treeSum of the eight lanes.
KDSWAP_AVX2 inline float horizontalSum(__m256 v) {
  const __m128 q = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));  // v0 + v4, ..
  const __m128 h = _mm_add_ps(q, _mm_movehl_ps(q, q));                                   // q0 + q2, q1 + q3
  return _mm_cvtss_f32(_mm_add_ss(h, _mm_shuffle_ps(h, h, 1)));
}

//! FrontToBack in registers: each lane's sums of weighted colours, and the transmittance.
struct Accumulated8 {
  __m256 r, g, b;
  float transmittance;
};

KDSWAP_AVX2 inline Accumulated8 nothingYet() {
  return Accumulated8{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(), 1.0f};
}

//! FrontToBack::rgba: the lanes' sums added across lanes.
KDSWAP_AVX2 inline Rgba rgbaOf(const Accumulated8& a) {
  return Rgba{horizontalSum(a.r), horizontalSum(a.g), horizontalSum(a.b), 1.0f - a.transmittance};
}

//! Lane j takes lane `from[j]` of v; lanes in `ones` (a blend mask) take 1.
template <int ones>
KDSWAP_AVX2 inline __m256 shifted(__m256 v, __m256i from) {
  return _mm256_blend_ps(_mm256_permutevar8x32_ps(v, from), _mm256_set1_ps(1.0f), ones);
}

//! FrontToBack::addEight on the first n shaded samples, in lanes: the same operations, so the
//! same bits; adds the samples taken to `samples`.
KDSWAP_AVX2 inline bool compositeEight(Accumulated8& result, const Shaded8& s, int n, float stopTransmittance,
                                       std::uint64_t& samples) {
  const int inGroup = (1 << n) - 1;
  if ((s.contributing & inGroup) == 0) {  // nothing visible: no change, no stop
    samples += std::uint64_t(n);
    return false;
  }
  const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  const __m256 one = _mm256_set1_ps(1.0f);
  const __m256 rawA = _mm256_load_ps(s.a);
  const __m256 counts = _mm256_and_ps(_mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(n), lane)),
                                      _mm256_cmp_ps(rawA, _mm256_setzero_ps(), _CMP_NLE_UQ));
  const __m256 a = _mm256_and_ps(rawA, counts);
  const __m256i back1 = _mm256_setr_epi32(0, 0, 1, 2, 3, 4, 5, 6), back2 = _mm256_setr_epi32(0, 0, 0, 1, 2, 3, 4, 5),
                back4 = _mm256_setr_epi32(0, 0, 0, 0, 0, 1, 2, 3);
  __m256 y = _mm256_sub_ps(one, a);
  y = _mm256_mul_ps(y, shifted<0x01>(y, back1));
  y = _mm256_mul_ps(y, shifted<0x03>(y, back2));
  y = _mm256_mul_ps(y, shifted<0x0F>(y, back4));
  const __m256 t = _mm256_set1_ps(result.transmittance);
  const __m256 inclusive = _mm256_mul_ps(t, y);
  __m256 w = _mm256_mul_ps(_mm256_mul_ps(t, shifted<0x01>(y, back1)), a);
  const int stops = _mm256_movemask_ps(_mm256_and_ps(
      _mm256_cmp_ps(inclusive, _mm256_set1_ps(stopTransmittance), _CMP_LE_OQ), counts));  // a visible sample stops it
  int last = n - 1;
  if (stops) {
    last = __builtin_ctz(unsigned(stops));
    w = _mm256_and_ps(w, _mm256_castsi256_ps(_mm256_cmpgt_epi32(_mm256_set1_epi32(last + 1), lane)));
  }
  result.r = _mm256_add_ps(result.r, _mm256_mul_ps(w, _mm256_load_ps(s.r)));
  result.g = _mm256_add_ps(result.g, _mm256_mul_ps(w, _mm256_load_ps(s.g)));
  result.b = _mm256_add_ps(result.b, _mm256_mul_ps(w, _mm256_load_ps(s.b)));
  result.transmittance = _mm_cvtss_f32(_mm256_castps256_ps128(_mm256_permutevar8x32_ps(inclusive, _mm256_set1_epi32(last))));
  samples += std::uint64_t(last + 1);
  return stops != 0;
}

//! The brick's voxels in the format VoxelT.
template <typename VoxelT>
inline const VoxelT* voxelsOf(const MarchContext& m) {
  if constexpr (std::is_same_v<VoxelT, CompactVoxel>)
    return m.voxels.compact;
  else
    return m.voxels.data;
}

//! Corner pointers of eight samples from their voxel offsets.
template <typename VoxelT>
KDSWAP_AVX2 inline void cornersOf(const VoxelT* data, __m256i offset, const VoxelT** corner) {
  alignas(32) int offsets[kLanes];
  _mm256_store_si256(reinterpret_cast<__m256i*>(offsets), offset);
  for (int j = 0; j < kLanes; ++j) corner[j] = data + offsets[j];
}

//! Shades eight samples of (x, y, z, offset) and composites them in order; true when the ray is done.
template <typename VoxelT>
KDSWAP_AVX2 inline bool shadeAndComposite(const MarchContext& m, const RaySegment& s, const VoxelT* data, __m256 x,
                                          __m256 y, __m256 z, __m256i offset, __m256i uniform, UniformShade* ray,
                                          Accumulated8& result, std::uint64_t& samples) {
  const VoxelT* corner[kLanes];
  cornersOf(data, offset, corner);
  Shaded8 shaded;
  shade8(m, sameDirection(s.toLight), ray, x, y, z, corner, uniform, shaded);
  return compositeEight(result, shaded, kLanes, s.stopFor(m), samples);
}

//! Where a ray's march stopped: done (early termination, or no samples left), or with its last
//! 1..7 visible samples still to shade and composite.
struct RayTail {
  Accumulated8 result;
  __m256 x, y, z;
  __m256i offset, uniform;
  int size = 0;  //!< samples waiting in lanes 0 .. size - 1; 0 when the ray is done
};

//! The last few samples of several rays, packed into one eight before shading: a ray's final
//! partial eight would otherwise leave lanes idle (a sixth of the shaded lanes on a 64-node CT
//! head). Each ray's samples stay together and in order, and are composited as its last group, as
//! the scalar march does; only the shading is shared, and it is per lane.
template <typename VoxelT>
class TailPacker {
 public:
  KDSWAP_AVX2 explicit TailPacker(const MarchContext& m, Rgba* colours, std::uint64_t& samples)
      : m_(m), colours_(colours), samples_(samples) {}

  //! Ray `ray`'s tail (size 1..7) with its light direction and stop transmittance; its colour is
  //! written once shaded.
  KDSWAP_AVX2 void add(std::size_t ray, const RayTail& tail, const glm::vec3& toLight, float stop) {
    if (size_ + tail.size > kLanes) flush();
    // Lane j of the rotated tail is its sample j - size; the lanes it fills are [size, size + n).
    const __m256i lane = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
    const __m256i from = rotation(-size_);
    const __m256 mine = _mm256_castsi256_ps(_mm256_and_si256(_mm256_cmpgt_epi32(_mm256_set1_epi32(size_ + tail.size), lane),
                                                             _mm256_cmpgt_epi32(lane, _mm256_set1_epi32(size_ - 1))));
    x_ = _mm256_blendv_ps(x_, _mm256_permutevar8x32_ps(tail.x, from), mine);
    y_ = _mm256_blendv_ps(y_, _mm256_permutevar8x32_ps(tail.y, from), mine);
    z_ = _mm256_blendv_ps(z_, _mm256_permutevar8x32_ps(tail.z, from), mine);
    offset_ = _mm256_castps_si256(_mm256_blendv_ps(
        _mm256_castsi256_ps(offset_), _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(tail.offset, from)), mine));
    uniform_ = _mm256_castps_si256(_mm256_blendv_ps(
        _mm256_castsi256_ps(uniform_), _mm256_castsi256_ps(_mm256_permutevar8x32_epi32(tail.uniform, from)), mine));
    light_.x = _mm256_blendv_ps(light_.x, _mm256_set1_ps(toLight.x), mine);
    light_.y = _mm256_blendv_ps(light_.y, _mm256_set1_ps(toLight.y), mine);
    light_.z = _mm256_blendv_ps(light_.z, _mm256_set1_ps(toLight.z), mine);
    entries_[count_++] = Entry{ray, tail.result, size_, tail.size, stop};
    size_ += tail.size;
  }

  //! Shades what is packed and composites each ray's share onto its colour.
  KDSWAP_AVX2 void flush() {
    if (size_ == 0) return;
    const VoxelT* corner[kLanes];
    cornersOf(voxelsOf<VoxelT>(m_), offset_, corner);  // unfilled lanes keep earlier voxels of the brick
    Shaded8 shaded;
    shade8(m_, light_, nullptr, x_, y_, z_, corner, uniform_, shaded);
    for (int e = 0; e < count_; ++e) {
      Entry& entry = entries_[e];
      // The ray's lanes [start, start + n) back to lanes [0, n).
      const __m256i from = rotation(entry.start);
      Shaded8 own;
      own.contributing = (shaded.contributing >> entry.start) & ((1 << entry.n) - 1);
      _mm256_store_ps(own.a, _mm256_permutevar8x32_ps(_mm256_load_ps(shaded.a), from));
      if (own.contributing != 0) {  // colour exists only where some lane is visible
        _mm256_store_ps(own.r, _mm256_permutevar8x32_ps(_mm256_load_ps(shaded.r), from));
        _mm256_store_ps(own.g, _mm256_permutevar8x32_ps(_mm256_load_ps(shaded.g), from));
        _mm256_store_ps(own.b, _mm256_permutevar8x32_ps(_mm256_load_ps(shaded.b), from));
      }
      compositeEight(entry.result, own, entry.n, entry.stop, samples_);
      colours_[entry.ray] = rgbaOf(entry.result);
    }
    size_ = 0, count_ = 0;
    uniform_ = _mm256_setzero_si256();
  }

 private:
  struct Entry {
    std::size_t ray;
    Accumulated8 result;
    int start, n;
    float stop;
  };
  const MarchContext& m_;
  Rgba* colours_;
  std::uint64_t& samples_;
  // Lanes not yet filled hold offset 0 (a voxel of the brick) and point 0 until first written.
  __m256 x_ = _mm256_setzero_ps(), y_ = _mm256_setzero_ps(), z_ = _mm256_setzero_ps();
  __m256i offset_ = _mm256_setzero_si256();
  __m256i uniform_ = _mm256_setzero_si256();  // unfilled lanes: not uniform (their shading is unused)
  Directions8 light_{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps()};
  Entry entries_[kLanes];
  int size_ = 0, count_ = 0;
};

//! Eight rays' lattice, one ray per lane.
struct EightRays {
  __m256 ox, oy, oz, dx, dy, dz, ix, iy, iz, phase, step;
  __m256i first, last;
};

//! Rows r[0..7] of eight floats to columns: lane j of out[c] is r[j][c].
KDSWAP_AVX2 inline void transpose8(const __m256* r, __m256* out) {
  __m256 t[8], u[8];
  for (int i = 0; i < 4; ++i) {
    t[2 * i] = _mm256_unpacklo_ps(r[2 * i], r[2 * i + 1]);
    t[2 * i + 1] = _mm256_unpackhi_ps(r[2 * i], r[2 * i + 1]);
  }
  for (int h = 0; h < 2; ++h) {  // rows 0-3, then 4-7: columns c | c + 4 of four rows
    u[4 * h + 0] = _mm256_shuffle_ps(t[4 * h], t[4 * h + 2], _MM_SHUFFLE(1, 0, 1, 0));
    u[4 * h + 1] = _mm256_shuffle_ps(t[4 * h], t[4 * h + 2], _MM_SHUFFLE(3, 2, 3, 2));
    u[4 * h + 2] = _mm256_shuffle_ps(t[4 * h + 1], t[4 * h + 3], _MM_SHUFFLE(1, 0, 1, 0));
    u[4 * h + 3] = _mm256_shuffle_ps(t[4 * h + 1], t[4 * h + 3], _MM_SHUFFLE(3, 2, 3, 2));
  }
  for (int c = 0; c < 4; ++c) {
    out[c] = _mm256_permute2f128_ps(u[c], u[c + 4], 0x20);
    out[c + 4] = _mm256_permute2f128_ps(u[c], u[c + 4], 0x31);
  }
}

// eightRays reads a segment's first 64 bytes as two rows of eight 4-byte words.
static_assert(sizeof(RaySegment) % sizeof(float) == 0 && offsetof(RaySegment, inverseStep) % sizeof(float) == 0,
              "LeadingHops gathers inverseStep with a float stride");
static_assert(offsetof(RaySegment, origin) == 0 && offsetof(RaySegment, inverseDirection) == 24 &&
                  offsetof(RaySegment, step) == 36 && offsetof(RaySegment, phase) == 40 &&
                  offsetof(RaySegment, first) == 48 && offsetof(RaySegment, last) == 56 && sizeof(long) == 8,
              "RaySegment's layout changed: update eightRays");

//! Segments s[0 .. n-1] (n <= 8) in lanes, by two 8 x 8 transposes; lanes past n repeat segment 0.
//! first and last are the low halves of the 64-bit indices (little-endian; indices along one ray
//! fit an int, as groupAt assumes).
KDSWAP_AVX2 inline EightRays eightRays(const RaySegment* s, int n) {
  __m256 rows[8], columns[8];
  for (int j = 0; j < kLanes; ++j) rows[j] = _mm256_loadu_ps(&s[j < n ? j : 0].origin.x);
  transpose8(rows, columns);
  EightRays r;
  r.ox = columns[0], r.oy = columns[1], r.oz = columns[2], r.dx = columns[3], r.dy = columns[4], r.dz = columns[5];
  r.ix = columns[6], r.iy = columns[7];
  for (int j = 0; j < kLanes; ++j) rows[j] = _mm256_loadu_ps(&s[j < n ? j : 0].origin.x + 8);
  transpose8(rows, columns);  // iz, step, phase, padding, first, first's high half, last, last's high half
  r.iz = columns[0], r.step = columns[1], r.phase = columns[2];
  r.first = _mm256_castps_si256(columns[4]), r.last = _mm256_castps_si256(columns[6]);
  return r;
}

//! cubeExit with the ray's direction per lane: the far face where the direction is positive, the
//! near one where negative, +infinity where it is 0. The same operations per lane, so the same t
//! (where it is a number; 0 where it is not, which only makes the hop shorter).
KDSWAP_AVX2 inline __m256 cubeExitLanes(__m256i cell, __m256i reach, __m256 boxLo, __m256 boxHi, __m128i shift,
                                        __m256 origin, __m256 direction, __m256 inverse) {
  const __m256 high = _mm256_min_ps(_mm256_cvtepi32_ps(_mm256_sll_epi32(_mm256_add_epi32(cell, reach), shift)), boxHi);
  const __m256 low = _mm256_max_ps(
      _mm256_cvtepi32_ps(_mm256_sll_epi32(_mm256_sub_epi32(cell, _mm256_sub_epi32(reach, _mm256_set1_epi32(1))), shift)),
      boxLo);
  const __m256 zero = _mm256_setzero_ps();
  const __m256 face = _mm256_blendv_ps(low, high, _mm256_cmp_ps(direction, zero, _CMP_GT_OQ));
  __m256 t = _mm256_mul_ps(_mm256_sub_ps(face, origin), inverse);
  t = _mm256_and_ps(t, _mm256_cmp_ps(t, t, _CMP_ORD_Q));  // 0 * infinity (a direction ~1e-39): no hop, 0
  return _mm256_blendv_ps(t, _mm256_set1_ps(std::numeric_limits<float>::infinity()),
                          _mm256_cmp_ps(direction, zero, _CMP_EQ_OQ));
}

//! Before the march, rays step over the empty space in front of their first visible sample
//! together, one ray per lane: a hop is a gather and a dozen dependent operations, which a ray
//! marched alone waits out hop after hop (a large part of the default scene's cost that does not
//! scale with its samples), while eight rays' hops share the wait, and several eights' hops,
//! interleaved, overlap. Each ray ends at an index at or before its first sample in a cell that can be visible,
//! with every sample before it invisible, by the march's own rule (RaySegment::resumeAfterEmpty),
//! or at last + 1 when there is none. The march then takes exactly the samples it would have taken
//! from the segment's first, so the image is the same.
class LeadingHops {
 public:
  //! Segments s[0 .. n-1] (n <= 8) in lanes; the first hop test is done at once.
  KDSWAP_AVX2 void start(const MarchContext& m, const BrickConstants& bc, const RaySegment* s, int n) {
    s_ = s, n_ = n;
    r_ = eightRays(s, n);
    k_ = r_.first;
    active_ = _mm256_andnot_si256(_mm256_cmpgt_epi32(k_, r_.last), _mm256_cmpgt_epi32(_mm256_set1_epi32(n), bc.lane));
    hopped_ = false;
    haveInverseStep_ = false;
    hop(m, bc);
  }
  //! True while some ray may still hop.
  KDSWAP_AVX2 bool active() const { return !_mm256_testz_si256(active_, active_); }
  //! True when some ray hopped at all (the first test found empty space).
  bool hopped() const { return hopped_; }

  //! One hop of every ray still in empty space; rays whose sample lies in a visible cell, or past
  //! their last, stop.
  KDSWAP_AVX2 void hop(const MarchContext& m, const BrickConstants& bc) {
    const __m256i one = _mm256_set1_epi32(1);
    // Sample k of each lane, exactly as RaySegment::point and groupAt compute it.
    const __m256 t = _mm256_mul_ps(_mm256_add_ps(_mm256_cvtepi32_ps(k_), r_.phase), r_.step);
    const __m256 px = _mm256_add_ps(r_.ox, _mm256_mul_ps(r_.dx, t)), py = _mm256_add_ps(r_.oy, _mm256_mul_ps(r_.dy, t)),
                 pz = _mm256_add_ps(r_.oz, _mm256_mul_ps(r_.dz, t));
    const __m256i cx = cellAxis(_mm256_cvttps_epi32(px), bc.cellShift, bc.cellLoX);
    const __m256i cy = cellAxis(_mm256_cvttps_epi32(py), bc.cellShift, bc.cellLoY);
    const __m256i cz = cellAxis(_mm256_cvttps_epi32(pz), bc.cellShift, bc.cellLoZ);
    const __m256i reach = reachOf(codeAt(bc, m.cellCodes, cx, cy, cz, active_));  // finished lanes look at cell 0
    const __m256i empty = _mm256_andnot_si256(_mm256_cmpeq_epi32(reach, _mm256_setzero_si256()), active_);
    if (_mm256_testz_si256(empty, empty)) {
      active_ = empty;
      return;
    }
    hopped_ = true;
    if (!haveInverseStep_) {  // only rays that hop need it
      const __m256i at = _mm256_mullo_epi32(_mm256_and_si256(bc.lane, _mm256_cmpgt_epi32(_mm256_set1_epi32(n_), bc.lane)),
                                            _mm256_set1_epi32(int(sizeof(RaySegment) / sizeof(float))));
      inverseStep_ = _mm256_i32gather_ps(&s_[0].inverseStep, at, 4);
      haveInverseStep_ = true;
    }
    const __m256 tExit = _mm256_min_ps(
        _mm256_min_ps(cubeExitLanes(_mm256_add_epi32(cx, bc.cellLoX), reach, bc.boxLoX, bc.boxHiX, bc.cellShift, r_.ox,
                                    r_.dx, r_.ix),
                      cubeExitLanes(_mm256_add_epi32(cy, bc.cellLoY), reach, bc.boxLoY, bc.boxHiY, bc.cellShift, r_.oy,
                                    r_.dy, r_.iy)),
        cubeExitLanes(_mm256_add_epi32(cz, bc.cellLoZ), reach, bc.boxLoZ, bc.boxHiZ, bc.cellShift, r_.oz, r_.dz, r_.iz));
    // floor(tExit / step - phase) - 1, one index early for rounding, capped past the segment's end;
    // then at least one sample on.
    __m256 index = _mm256_floor_ps(_mm256_sub_ps(_mm256_mul_ps(tExit, inverseStep_), r_.phase));
    index = _mm256_min_ps(index, _mm256_cvtepi32_ps(_mm256_add_epi32(r_.last, one)));
    const __m256i resume =
        _mm256_max_epi32(_mm256_add_epi32(k_, one), _mm256_sub_epi32(_mm256_cvttps_epi32(index), one));
    k_ = _mm256_blendv_epi8(k_, resume, empty);
    active_ = _mm256_andnot_si256(_mm256_cmpgt_epi32(k_, r_.last), empty);
  }

  //! Where each ray's march starts.
  KDSWAP_AVX2 void firsts(long* first) const {
    alignas(32) int out[kLanes];
    _mm256_store_si256(reinterpret_cast<__m256i*>(out), k_);
    for (int j = 0; j < n_; ++j) first[j] = std::min<long>(out[j], s_[j].last + 1);
  }

 private:
  const RaySegment* s_ = nullptr;
  int n_ = 0;
  EightRays r_;
  __m256i k_, active_;
  __m256 inverseStep_;
  bool hopped_ = false, haveInverseStep_ = false;
};

//! Where the march of each of segments[0 .. count-1] (count <= 64) starts: LeadingHops for each
//! eight, their hops interleaved. Neighbouring rays meet alike space: after eight rays with
//! nothing to hop over (dense data, small bricks), the next three eights start their march at
//! their first sample without looking, which costs only the hops the march makes itself.
KDSWAP_AVX2 inline void marchStarts(const MarchContext& m, const BrickConstants& bc, const RaySegment* segments,
                                    std::size_t count, int& quietEights, long* first) {
  LeadingHops hops[kLanes];
  int hopping[kLanes], live = 0;
  for (std::size_t i = 0; i < count; i += kLanes) {
    const int n = int(std::min<std::size_t>(kLanes, count - i));
    if (quietEights % 4 != 0) {
      for (int j = 0; j < n; ++j) first[i + std::size_t(j)] = segments[i + std::size_t(j)].first;
      ++quietEights;
      continue;
    }
    LeadingHops& h = hops[i / kLanes];
    h.start(m, bc, segments + i, n);
    quietEights = h.hopped() ? 0 : 1;
    if (h.active()) hopping[live++] = int(i / kLanes);
    else h.firsts(first + i);
  }
  while (live > 0) {  // one hop of each eight in turn: independent chains the core overlaps
    int still = 0;
    for (int e = 0; e < live; ++e) {
      LeadingHops& h = hops[hopping[e]];
      h.hop(m, bc);
      if (h.active()) hopping[still++] = hopping[e];
      else h.firsts(first + std::size_t(hopping[e]) * kLanes);
    }
    live = still;
  }
}

template <typename VoxelT, bool kAllVisible, bool kUniform>
KDSWAP_AVX2 __attribute__((always_inline)) inline void marchRay(const MarchContext& m, const BrickConstants& bc,
                                                                const RaySegment& s, long first, std::uint64_t& samples,
                                                                RayTail& tail) {
  Accumulated8& result = tail.result;
  result = nothingYet();
  tail.size = 0;
  const RayLanes r{_mm256_set1_ps(s.origin.x),    _mm256_set1_ps(s.origin.y),    _mm256_set1_ps(s.origin.z),
                   _mm256_set1_ps(s.direction.x), _mm256_set1_ps(s.direction.y), _mm256_set1_ps(s.direction.z),
                   _mm256_set1_ps(s.phase),       _mm256_set1_ps(s.step)};
  // Zeros before the first samples arrive: offset 0 is a voxel of the brick.
  Waiting waiting{_mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_ps(), _mm256_setzero_si256(),
                  _mm256_setzero_si256(), 0};
  UniformShade same;  // the ray's last uniform shading
  long k = first;
  Group g;
  if (k <= s.last) groupAt<kAllVisible, kUniform>(bc, r, m.cellCodes, k, s.last, g);
  while (k <= s.last) {
    // Where the ray goes on: past the group, or, when it ends in empty space, past the farthest
    // empty cube its invisible samples lie in. The next group's test starts before this group's
    // shading, which hides the gather's latency.
    long kNext = k + g.n;
    const int full = (1 << g.n) - 1;
    if (!(g.visible >> (g.n - 1) & 1)) kNext = std::max(kNext, farthestResume(bc, s, g, ~g.visible & full) + 1);
    Group next;
    if (kNext <= s.last) groupAt<kAllVisible, kUniform>(bc, r, m.cellCodes, kNext, s.last, next);

    if (g.visible == 0xFF && waiting.size == 0) {  // dense data: eight in a row, nothing to pack
      if (shadeAndComposite(m, s, voxelsOf<VoxelT>(m), g.px, g.py, g.pz, g.offset, g.uniform, &same, result, samples))
        return;
    } else if (g.visible != 0) {
      // Pack the visible lanes behind the waiting ones: lane j of the rotated pack takes the
      // group's (j - size) mod 8-th visible sample, so lanes below `size` keep the waiting samples
      // and any overflow wraps to the front, where it waits for the next eight.
      const int count = __builtin_popcount(unsigned(g.visible));
      const __m256i packed = _mm256_cvtepu8_epi32(_mm_cvtsi64_si128(std::int64_t(kPackTable.indices[g.visible])));
      const __m256i size = _mm256_set1_epi32(waiting.size);
      const __m256i pick =
          _mm256_permutevar8x32_epi32(packed, rotation(-waiting.size));
      const __m256 x = _mm256_permutevar8x32_ps(g.px, pick), y = _mm256_permutevar8x32_ps(g.py, pick),
                   z = _mm256_permutevar8x32_ps(g.pz, pick);
      const __m256i offset = _mm256_permutevar8x32_epi32(g.offset, pick);
      const __m256i uniform = kUniform ? _mm256_permutevar8x32_epi32(g.uniform, pick) : _mm256_setzero_si256();
      const __m256 keep = _mm256_castsi256_ps(_mm256_cmpgt_epi32(size, bc.lane));
      waiting.x = _mm256_blendv_ps(x, waiting.x, keep), waiting.y = _mm256_blendv_ps(y, waiting.y, keep),
      waiting.z = _mm256_blendv_ps(z, waiting.z, keep);
      waiting.offset = _mm256_castps_si256(
          _mm256_blendv_ps(_mm256_castsi256_ps(offset), _mm256_castsi256_ps(waiting.offset), keep));
      if constexpr (kUniform)
        waiting.uniform = _mm256_castps_si256(
            _mm256_blendv_ps(_mm256_castsi256_ps(uniform), _mm256_castsi256_ps(waiting.uniform), keep));
      waiting.size += count;
      if (waiting.size >= kLanes) {
        if (shadeAndComposite(m, s, voxelsOf<VoxelT>(m), waiting.x, waiting.y, waiting.z, waiting.offset,
                              waiting.uniform, &same, result, samples))
          return;
        waiting.size -= kLanes;
        waiting.x = x, waiting.y = y, waiting.z = z, waiting.offset = offset;  // the overflow, at the front
        waiting.uniform = uniform;
      }
    }
    k = kNext;
    g = next;
  }
  // The last few (lanes 0 .. size - 1) go back to the batch, with the ray's state.
  tail.x = waiting.x, tail.y = waiting.y, tail.z = waiting.z, tail.offset = waiting.offset;
  tail.uniform = waiting.uniform;
  tail.size = waiting.size;
}

template <typename VoxelT, bool kAllVisible, bool kUniform>
KDSWAP_AVX2 void marchBatch(const MarchContext& m, const RaySegment* segments, std::size_t count, Rgba* colours,
                            std::uint64_t& samples) {
  const BrickConstants constants = brickConstants(m);
  std::uint64_t taken = 0;  // a local: the callee's increments stay in a register
  TailPacker<VoxelT> tails(m, colours, taken);
  long first[kLanes * kLanes];
  int quietEights = 0;
  for (std::size_t i = 0; i < count; ++i) {
    if constexpr (kAllVisible) {
      first[i % (kLanes * kLanes)] = segments[i].first;  // no empty space to hop over: the hops would stop at once
    } else if (i % (kLanes * kLanes) == 0) {
      marchStarts(m, constants, segments + i, std::min<std::size_t>(kLanes * kLanes, count - i), quietEights, first);
    }
    RayTail tail;
    marchRay<VoxelT, kAllVisible, kUniform>(m, constants, segments[i], first[i % (kLanes * kLanes)], taken, tail);
    if (tail.size == 0)
      colours[i] = rgbaOf(tail.result);
    else
      tails.add(i, tail, segments[i].toLight, segments[i].stopFor(m));
  }
  tails.flush();
  samples += taken;
}

// A brick whose cells can all be visible (dense data, a small brick inside matter) gets a march
// that never reads the empty-space map: no gather of reach bytes per group of eight, no leading
// hops. The map would say "visible" everywhere, so the samples and bits are the same. Dense bricks
// are common with many nodes: turbulence 256^3 at P = 64, 3-5% less wall time with and without
// waves; the CT head with waves 1.6%; sparse scenes unchanged.
// A brick with uniform visible cells reads the map for their bit (kUniform), whether or not it has
// empty cells; the others keep their march without the uniform lanes' bookkeeping.
template <typename VoxelT>
KDSWAP_AVX2 void marchVoxels(const MarchContext& m, const RaySegment* segments, std::size_t count, Rgba* colours,
                             std::uint64_t& samples) {
  if (m.anyUniform)
    marchBatch<VoxelT, false, true>(m, segments, count, colours, samples);
  else if (m.allVisible)
    marchBatch<VoxelT, true, false>(m, segments, count, colours, samples);
  else
    marchBatch<VoxelT, false, false>(m, segments, count, colours, samples);
}

KDSWAP_AVX2 void marchAvx2(const MarchContext& m, const RaySegment* segments, std::size_t count, Rgba* colours,
                           std::uint64_t& samples) {
  if (m.voxels.compact)
    marchVoxels<CompactVoxel>(m, segments, count, colours, samples);
  else
    marchVoxels<Voxel>(m, segments, count, colours, samples);
}

}  // namespace

MarchFunction KDSWAP_MARCH_ENTRY() { return KDSWAP_MARCH_CPU() ? &marchAvx2 : nullptr; }

}  // namespace kdswap

#else

namespace kdswap {
MarchFunction KDSWAP_MARCH_ENTRY() { return nullptr; }
}  // namespace kdswap

#endif
