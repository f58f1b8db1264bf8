// Ray setup for eight neighbouring pixels of a row at once (AVX2), for RayCaster::render: the
// camera ray (Camera::ray), the voxel ray (VoxelRay), its clip to a brick's visible box and the
// lattice indices where the clip puts it (RayCaster::segmentFor). With P bricks every pixel's ray
// is set up once per brick it may cross, ~1 M times per frame for the CT head at P = 64, where
// the setup was a sixth of the frame. Each lane performs the scalar setup's IEEE operations in the
// same order (AVX2 only, no FMA; the build uses -ffp-contract=off), so every lane's numbers, and
// from them the segments, samples and images, equal the scalar setup's bit for bit
// (tests/ray_march_test.cpp compares render() with castRay pixel by pixel).
#pragma once

#include <glm/vec3.hpp>

#include "core/camera/camera.h"

namespace kdswap {

//! A brick's and a frame's constants of the setup.
struct RaySetupConstants {
  Camera::Basis camera;
  glm::vec3 inverseSpacing;  //!< world -> voxel coordinates (VoxelRay::Scale)
  float inverseStep;
  bool jitter;
  float phaseShift;          //!< RenderSettings::phaseShift
  glm::vec3 clipLo, clipHi;  //!< the box rays are clipped to, voxel coordinates
  float clipHiMagnitude;     //!< for the clip's rounding margin
  //! The brick's owned box [ownedLo, ownedHi) and the sample step (voxels per unit of t): for the
  //! ownership tests at both ends of each ray's lattice run (RayLanes8::nearOwned). An empty box
  //! (the default) leaves them all false, and the caller then searches as it would without them.
  glm::vec3 ownedLo{0.0f}, ownedHi{0.0f};
  float step = 1.0f;
};

//! Eight rays, one per lane. The lattice index bounds are floor(tNear / step - phase) and
//! ceil(tFar / step - phase) as floats, computed as the scalar setup computes them; the caller
//! converts them to integers as it does.
struct RayLanes8 {
  alignas(32) float ox[8], oy[8], oz[8];  //!< voxel coordinates
  alignas(32) float dx[8], dy[8], dz[8];  //!< voxel coordinates per unit of world t
  alignas(32) float ix[8], iy[8], iz[8];  //!< 1 / d
  alignas(32) float wx[8], wy[8], wz[8];  //!< world direction (the light is at the eye)
  alignas(32) float phase[8], firstIndex[8], lastIndex[8];
  int crosses = 0;  //!< bit j: lane j's ray crosses the clip box
  //! Where the owned run of lattice indices may start and end, tested for all lanes at once with
  //! the exact rule of RayCaster's search (p = o + d ((k + phase) step) inside [ownedLo, ownedHi)):
  //! bit i of nearOwned: index kBegin + i is owned, kBegin = max(0, firstIndex - 1); bit i of
  //! farOwned: index kEnd - 3 + i is owned, kEnd = lastIndex + 1. Valid in lanes of `windows`
  //! (indices within int range); the search's first four candidates at each end, precomputed.
  alignas(32) int nearOwned[8], farOwned[8];
  int windows = 0;
};

//! Just the voxel rays of eight pixels (Camera::ray, then VoxelRay), for the occlusion map.
struct VoxelRays8 {
  alignas(32) float ox[8], oy[8], oz[8];  //!< voxel coordinates
  alignas(32) float dx[8], dy[8], dz[8];  //!< voxel coordinates per unit of world t
  alignas(32) float phase[8];
};

//! Whether setupRays8 runs here: AVX2 in this build and CPU, and KDSWAP_SIMD is not "scalar".
bool raySetup8Available();
//! Pixels x0 .. x0 + 7 of row y (lanes past the frame compute harmless numbers). Only when
//! raySetup8Available().
void setupRays8(const RaySetupConstants& c, int x0, int y, RayLanes8& out);
//! The rays alone of setupRays8 (only camera, inverseSpacing, jitter and phaseShift of `c` are read); the
//! same bits. Only when raySetup8Available().
void voxelRays8(const RaySetupConstants& c, int x0, int y, VoxelRays8& out);

}  // namespace kdswap
