// Trilinear interpolation of a brick's stored values and gradients at a point in voxel
// coordinates. The ray caster and the tests use this one definition.
#pragma once

#include "core/volume/brick.h"

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
  const Voxel& corner(int i) const {
    return v[(i & 1 ? 1 : 0) + (i & 2 ? sy : 0) + (i & 4 ? sz : 0)];
  }
  float value() const {
    return w[0] * v[0].value + w[1] * v[1].value + w[2] * v[sy].value + w[3] * v[sy + 1].value +
           w[4] * v[sz].value + w[5] * v[sz + 1].value + w[6] * v[sz + sy].value + w[7] * v[sz + sy + 1].value;
  }
  glm::vec3 gradient() const {
    return w[0] * v[0].gradient + w[1] * v[1].gradient + w[2] * v[sy].gradient + w[3] * v[sy + 1].gradient +
           w[4] * v[sz].gradient + w[5] * v[sz + 1].gradient + w[6] * v[sz + sy].gradient +
           w[7] * v[sz + sy + 1].gradient;
  }
};

}  // namespace kdswap
