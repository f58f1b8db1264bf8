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
  float w[8];      //!< weights of (x,y,z) corners 000 100 010 110 001 101 011 111

  TrilinearCell(const Brick& brick, const glm::vec3& p) : sy(brick.strideY()), sz(brick.strideZ()) {
    const int ix = int(p.x), iy = int(p.y), iz = int(p.z);  // p >= 0, so truncation is floor
    const float fx = p.x - float(ix), fy = p.y - float(iy), fz = p.z - float(iz);
    const glm::ivec3 lo = brick.stored().lo;
    v = brick.voxelData() + std::size_t(iz - lo.z) * sz + std::size_t(iy - lo.y) * sy + std::size_t(ix - lo.x);
    const float gx = 1.0f - fx, gy = 1.0f - fy, gz = 1.0f - fz;
    w[0] = gx * gy * gz, w[1] = fx * gy * gz, w[2] = gx * fy * gz, w[3] = fx * fy * gz;
    w[4] = gx * gy * fz, w[5] = fx * gy * fz, w[6] = gx * fy * fz, w[7] = fx * fy * fz;
  }
  //! Value and gradient interpolated together: a Voxel is 4 floats, so one 4-wide vector per
  //! corner (GCC/Clang vector extension; SSE on x86-64). Lane 0 is the value, lanes 1-3 the gradient.
  typedef float Lanes __attribute__((vector_size(16)));
  Lanes interpolate() const {
    auto load = [](const Voxel& voxel) {
      Lanes l;
      __builtin_memcpy(&l, &voxel, sizeof l);
      return l;
    };
    return w[0] * load(v[0]) + w[1] * load(v[1]) + w[2] * load(v[sy]) + w[3] * load(v[sy + 1]) +
           w[4] * load(v[sz]) + w[5] * load(v[sz + 1]) + w[6] * load(v[sz + sy]) + w[7] * load(v[sz + sy + 1]);
  }
  float value() const { return interpolate()[0]; }
  glm::vec3 gradient() const {
    const Lanes l = interpolate();
    return glm::vec3(l[1], l[2], l[3]);
  }
};

}  // namespace kdswap
