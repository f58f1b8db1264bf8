// Ray march: the walk of one ray's run of owned lattice samples through a brick, skipping empty
// space, shading and compositing front to back with early ray termination. One interface, two
// implementations with equal results bit for bit: a portable scalar march (ray_march.cpp) and an
// AVX2 march that takes eight consecutive samples at once (ray_march_avx2.cpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <string_view>

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "core/image/rgba.h"
#include "core/render/empty_space_map.h"
#include "core/render/sample_shader.h"
#include "core/render/trilinear.h"
#include "core/volume/brick.h"

namespace kdswap {

//! A brick's constants for marching, shared by all its rays.
struct MarchContext {
  ShadingParameters shading;
  VoxelAddressing voxels;
  glm::ivec3 storedLo{0};           //!< first kept voxel: voxels.data[local index] is the voxel
  //! EmptySpaceMap::marchCodes(), padded for 4-byte gathers: per cell the reach (kReachMask bits)
  //! and whether the cell is uniform (kUniformBit: its samples take its record, uniformRecord).
  const std::uint8_t* cellCodes = nullptr;
  glm::ivec3 cellLo{0}, cellCount{0};
  int cellShift = 2;                //!< Brick::cellShift(): cells of 2^cellShift voxels a side
  bool allVisible = false;          //!< every reach is 0 (EmptySpaceMap::marchesEverySample): the march may skip the map
  bool anyUniform = false;          //!< some code has kUniformBit (EmptySpaceMap::anyUniform): the map must be read
  glm::vec3 lo{0.0f}, hi{0.0f};     //!< owned box [lo, hi), voxel coordinates
  //! Early ray termination: the ray stops once its transmittance (1 - opacity) is at most this,
  //! 1 - the termination opacity (0 with termination off: only an opaque sample ends the ray).
  float stopTransmittance = 0.0f;

  std::size_t cellIndex(const glm::ivec3& c) const {  //!< c relative to cellLo
    return (std::size_t(c.z) * cellCount.y + c.y) * cellCount.x + c.x;
  }
};

//! One ray's owned samples in a brick: lattice indices first..last, all inside the owned box.
struct RaySegment {
  glm::vec3 origin, direction, inverseDirection;  //!< voxel coordinates
  float step, phase;
  long first, last;
  glm::vec3 toLight;  //!< unit vector to the light (at the eye)
  float inverseStep;  //!< 1 / step
  //! This ray's early termination, as MarchContext::stopTransmittance; negative: the context's.
  //! Front-to-back waves give each ray its own: the brick stops once the light left in front of
  //! it times its own transmittance reaches the single-node ray's stop.
  float stopTransmittance = -1.0f;
  float stopFor(const MarchContext& m) const { return stopTransmittance >= 0.0f ? stopTransmittance : m.stopTransmittance; }

  glm::vec3 point(long k) const { return origin + direction * ((float(k) + phase) * step); }

  //! After sample k fell in an invisible cell c (relative) whose reach is n: the lattice index to
  //! step on from, just before the ray leaves the invisible cube of cells around c (a cube is
  //! convex, so every sample before that is invisible). One index early, for rounding.
  long resumeAfterEmpty(const MarchContext& m, const glm::ivec3& c, int n) const {
    const glm::vec3 cLo = glm::max(glm::vec3((c + m.cellLo - (n - 1)) << m.cellShift), m.lo);
    const glm::vec3 cHi = glm::min(glm::vec3((c + m.cellLo + n) << m.cellShift), m.hi);
    float tExit = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a)
      if (direction[a] != 0.0f)
        tExit = std::min(tExit, ((direction[a] > 0.0f ? cHi[a] : cLo[a]) - origin[a]) * inverseDirection[a]);
    return long(std::floor(tExit * inverseStep - phase)) - 1;
  }
};

//! Front-to-back "over" of shaded samples, in lattice order, eight at a time. It carries the
//! transmittance T = prod(1 - a) rather than the opacity. Within a group of eight the products are
//! formed as trees, not one sample after another, and each of the eight lanes keeps its own sum of
//! weighted colours, added across lanes once, when the colour is read: so the SIMD march does a
//! group in a few vector operations, with no serial chain of eight and no horizontal sums per
//! group. addEight is that arithmetic written out lane by lane, which the SIMD march must match
//! bit for bit. Grouping depends on which samples are taken, so images with and without
//! empty-space skipping agree to rounding, not to the bit.
struct FrontToBack {
  static constexpr int kGroup = 8;
  float r[kGroup] = {}, g[kGroup] = {}, b[kGroup] = {};  //!< per lane: the sum over groups of weight x colour
  float transmittance = 1.0f;

  //! Adds samples s[0 .. n-1] (n <= 8, the rest ignored). True once the ray is opaque enough to
  //! stop (early ray termination); `taken` is then the samples up to the one that stopped it,
  //! otherwise n. A group with no sample of opacity > 0 changes nothing and never stops the ray.
  bool addEight(const ShadedSample* s, int n, float stopTransmittance, int& taken) {
    float a[kGroup], y[kGroup], step[kGroup];
    bool counts[kGroup], any = false;
    for (int j = 0; j < kGroup; ++j) {
      counts[j] = j < n && !(s[j].a <= 0.0f);  // as "over": a sample of opacity 0 is no sample
      a[j] = counts[j] ? s[j].a : 0.0f;
      any = any || counts[j];
    }
    taken = n;
    if (!any) return false;
    // Inclusive prefix products of (1 - a) by doubling: lane j multiplies in lane j - 1, then
    // j - 2, then j - 4 (lanes below take 1).
    for (int j = 0; j < kGroup; ++j) y[j] = 1.0f - a[j];
    for (int shift = 1; shift < kGroup; shift *= 2) {
      for (int j = 0; j < kGroup; ++j) step[j] = y[j] * (j >= shift ? y[j - shift] : 1.0f);
      for (int j = 0; j < kGroup; ++j) y[j] = step[j];
    }
    int last = n - 1;
    bool done = false;
    for (int j = 0; j < n; ++j)
      if (counts[j] && transmittance * y[j] <= stopTransmittance) {  // only a visible sample stops it
        last = j;
        done = true;
        break;
      }
    for (int j = 0; j < kGroup; ++j) {
      const float w = j > last && done ? 0.0f : (transmittance * (j >= 1 ? y[j - 1] : 1.0f)) * a[j];
      const bool inGroup = j < n;  // samples past n may be unset: their weight is 0, their colour too
      r[j] += w * (inGroup ? s[j].r : 0.0f), g[j] += w * (inGroup ? s[j].g : 0.0f), b[j] += w * (inGroup ? s[j].b : 0.0f);
    }
    transmittance = transmittance * y[last];
    taken = last + 1;
    return done;
  }
  Rgba rgba() const { return Rgba{treeSum(r), treeSum(g), treeSum(b), 1.0f - transmittance}; }

  //! (v0 + v4) + (v2 + v6), plus (v1 + v5) + (v3 + v7): the order of a 256-bit horizontal add.
  static float treeSum(const float* v) {
    const float q0 = v[0] + v[4], q1 = v[1] + v[5], q2 = v[2] + v[6], q3 = v[3] + v[7];
    return (q0 + q2) + (q1 + q3);
  }
};

//! Marches `count` segments of one brick: colours[i] is segment i's colour. Adds the samples taken
//! (those in cells that can be visible, up to the one that ends each ray) to `samples`. A batch
//! (a tile's rays) per call: the brick's constants are set up once per batch, not once per ray.
using MarchFunction = void (*)(const MarchContext& context, const RaySegment* segments, std::size_t count,
                               Rgba* colours, std::uint64_t& samples);

void marchScalar(const MarchContext& context, const RaySegment* segments, std::size_t count, Rgba* colours,
                 std::uint64_t& samples);
//! The AVX2 march, or null when this build or CPU has no AVX2. It needs local voxel indices below
//! 2^31 (checked by the caller: bricks larger than that use the scalar march).
MarchFunction avx2MarchFunction();
//! The same AVX2 march compiled for CPUs with AVX-512 VL (ray_march_avx512vl.cpp), or null where
//! the CPU or build lacks it. Same operations, same bits; only the code generation differs.
MarchFunction avx512vlMarchFunction();
//! That build with 512-bit registers for compact voxels' interpolation (ray_march_avx512.cpp), or
//! null where the CPU or build lacks AVX-512 VL. Same operations, same bits.
MarchFunction avx512MarchFunction();

//! The builds of the march this CPU runs (null where it lacks one), and whether it runs 512-bit
//! vectors at full speed (cpuRunsWideVectorsAtFullSpeed).
struct MarchBuilds {
  MarchFunction avx2 = nullptr, avx512vl = nullptr, avx512 = nullptr;
  bool wideAtFullSpeed = false;
};
//! The march to run. With no request (""), the fastest for the CPU: the 512-bit build where
//! 512-bit vectors run at full speed, else the AVX-512 VL build, else AVX2, else scalar. A request
//! (KDSWAP_SIMD: "scalar", "avx2", "avx512vl", "avx512") takes that build, or the next narrower
//! one the CPU has; any other text counts as none.
MarchFunction chooseMarch(const MarchBuilds& builds, std::string_view request);
//! chooseMarch for this CPU and KDSWAP_SIMD, chosen once.
MarchFunction selectedMarchFunction();
//! "avx512", "avx2+avx512vl", "avx2" or "scalar", for reports.
const char* marchName(MarchFunction march);

}  // namespace kdswap
