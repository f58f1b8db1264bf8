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

#include <glm/common.hpp>
#include <glm/vec3.hpp>

#include "core/image/rgba.h"
#include "core/render/sample_shader.h"
#include "core/render/trilinear.h"
#include "core/volume/brick.h"

namespace kdswap {

//! A brick's constants for marching, shared by all its rays.
struct MarchContext {
  ShadingParameters shading;
  VoxelAddressing voxels;
  glm::ivec3 storedLo{0};           //!< first kept voxel: voxels.data[local index] is the voxel
  const std::uint8_t* reach = nullptr;  //!< EmptySpaceMap::reachData(), padded for 4-byte gathers
  glm::ivec3 cellLo{0}, cellCount{0};
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

  glm::vec3 point(long k) const { return origin + direction * ((float(k) + phase) * step); }

  //! After sample k fell in an invisible cell c (relative) whose reach is n: the lattice index to
  //! step on from, just before the ray leaves the invisible cube of cells around c (a cube is
  //! convex, so every sample before that is invisible). One index early, for rounding.
  long resumeAfterEmpty(const MarchContext& m, const glm::ivec3& c, int n) const {
    const glm::vec3 cLo = glm::max(glm::vec3((c + m.cellLo - (n - 1)) << Brick::kCellShift), m.lo);
    const glm::vec3 cHi = glm::min(glm::vec3((c + m.cellLo + n) << Brick::kCellShift), m.hi);
    float tExit = std::numeric_limits<float>::max();
    for (int a = 0; a < 3; ++a)
      if (direction[a] != 0.0f)
        tExit = std::min(tExit, ((direction[a] > 0.0f ? cHi[a] : cLo[a]) - origin[a]) * inverseDirection[a]);
    return long(std::floor(tExit * inverseStep - phase)) - 1;
  }
};

//! Front-to-back "over" of shaded samples, in lattice order. It carries the transmittance
//! T = prod(1 - a) rather than the opacity: then each sample's dependency chain is a single
//! multiply (T *= 1 - a), not a subtract, multiply and add, which bounds the march's speed.
struct FrontToBack {
  float r = 0.0f, g = 0.0f, b = 0.0f, transmittance = 1.0f;
  //! Adds one sample; true once the ray is opaque enough to stop (early ray termination).
  bool add(const ShadedSample& s, float stopTransmittance) {
    if (s.a <= 0.0f) return false;
    const float w = transmittance * s.a;
    r += w * s.r;
    g += w * s.g;
    b += w * s.b;
    transmittance *= 1.0f - s.a;
    return transmittance <= stopTransmittance;
  }
  Rgba rgba() const { return Rgba{r, g, b, 1.0f - transmittance}; }
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
//! AVX2 when available, unless the environment sets KDSWAP_SIMD=scalar.
MarchFunction selectedMarchFunction();

}  // namespace kdswap
