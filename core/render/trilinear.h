// Trilinear interpolation of a brick's stored values and gradients at a point in voxel
// coordinates. The ray caster and the tests use this one definition.
#pragma once

#include "core/volume/brick.h"

static_assert(sizeof(kdswap::Voxel) == 4 * sizeof(float), "a Voxel must be exactly 4 floats");

namespace kdswap {

//! Interpolation weights and the first of the 8 surrounding voxels of point p (voxel coordinates,
//! inside the brick's owned box, so all 8 voxels are stored).
struct TrilinearCell {
  const Voxel* v;  //!< voxel at floor(p)
  std::size_t sy, sz;
  float fx, fy, fz;  //!< position of p inside the cell, 0..1 per axis

  TrilinearCell(const Brick& brick, const glm::vec3& p) : sy(brick.strideY()), sz(brick.strideZ()) {
    const int ix = int(p.x), iy = int(p.y), iz = int(p.z);  // p >= 0, so truncation is floor
    fx = p.x - float(ix), fy = p.y - float(iy), fz = p.z - float(iz);
    const glm::ivec3 lo = brick.stored().lo;
    v = brick.voxelData() + std::size_t(iz - lo.z) * sz + std::size_t(iy - lo.y) * sy + std::size_t(ix - lo.x);
  }
  //! Value and gradient interpolated together: a Voxel is 4 floats, so one 4-wide vector per
  //! corner (GCC/Clang vector extension; SSE on x86-64). Lane 0 is the value, lanes 1-3 the gradient.
  //! Seven linear blends (x, then y, then z) rather than eight weighted corners: fewer operations,
  //! and exact at the voxels.
  typedef float Lanes __attribute__((vector_size(16)));
  Lanes interpolate() const {
    auto load = [](const Voxel& voxel) {
      Lanes l;
      __builtin_memcpy(&l, &voxel, sizeof l);
      return l;
    };
    auto blend = [](const Lanes& a, const Lanes& b, float f) { return a + f * (b - a); };
    const Lanes x00 = blend(load(v[0]), load(v[1]), fx), x10 = blend(load(v[sy]), load(v[sy + 1]), fx);
    const Lanes x01 = blend(load(v[sz]), load(v[sz + 1]), fx), x11 = blend(load(v[sz + sy]), load(v[sz + sy + 1]), fx);
    return blend(blend(x00, x10, fy), blend(x01, x11, fy), fz);
  }
  float value() const { return interpolate()[0]; }
  glm::vec3 gradient() const {
    const Lanes l = interpolate();
    return glm::vec3(l[1], l[2], l[3]);
  }
};

}  // namespace kdswap
