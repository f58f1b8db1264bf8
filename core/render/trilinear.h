// Trilinear interpolation of a brick's stored values and gradients at a point in voxel
// coordinates. The ray caster and the tests use this one definition.
#pragma once

#include <cstddef>

#include "core/volume/brick.h"

static_assert(sizeof(kdswap::Voxel) == 4 * sizeof(float), "a Voxel must be exactly 4 floats");

namespace kdswap {

//! Where a brick's voxels are: global voxel (x, y, z) is data[origin + z * sz + y * sy + x]. Taken
//! once per ray, so the sample loop does not reload the brick's box and strides.
struct VoxelAddressing {
  const Voxel* data;
  std::ptrdiff_t sy, sz, origin;
  explicit VoxelAddressing(const Brick& brick)
      : data(brick.voxelData()),
        sy(std::ptrdiff_t(brick.strideY())),
        sz(std::ptrdiff_t(brick.strideZ())),
        origin(-(std::ptrdiff_t(brick.stored().lo.z) * sz + std::ptrdiff_t(brick.stored().lo.y) * sy +
                 std::ptrdiff_t(brick.stored().lo.x))) {}
};

//! Interpolation weights and the first of the 8 surrounding voxels of point p (voxel coordinates,
//! inside the brick's owned box, so all 8 voxels are stored).
struct TrilinearCell {
  const Voxel* v;  //!< voxel at floor(p)
  std::ptrdiff_t sy, sz;
  float w[8];      //!< weights of (x,y,z) corners 000 100 010 110 001 101 011 111

  TrilinearCell(const Brick& brick, const glm::vec3& p)
      : TrilinearCell(VoxelAddressing(brick), p, glm::ivec3(int(p.x), int(p.y), int(p.z))) {}
  //! `floor` = (int) p: p >= 0, so truncation is floor. The ray caster has it already.
  TrilinearCell(const VoxelAddressing& at, const glm::vec3& p, const glm::ivec3& floor)
      : TrilinearCell(at.data + (at.origin + floor.z * at.sz + floor.y * at.sy + floor.x), at.sy, at.sz, p, floor) {}
  //! `corner` = the voxel at `floor`; sy, sz its brick's strides.
  TrilinearCell(const Voxel* corner, std::ptrdiff_t sy, std::ptrdiff_t sz, const glm::vec3& p, const glm::ivec3& floor)
      : v(corner), sy(sy), sz(sz) {
    const float fx = p.x - float(floor.x), fy = p.y - float(floor.y), fz = p.z - float(floor.z);
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
