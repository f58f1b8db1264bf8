// Trilinear interpolation of a brick's stored values and gradients at a point in voxel
// coordinates, for either storage format. The ray caster and the tests use these definitions.
#pragma once

#include <cstddef>

#include "core/volume/brick.h"

static_assert(sizeof(kdswap::Voxel) == 4 * sizeof(float), "a Voxel must be exactly 4 floats");

namespace kdswap {

//! Where a brick's voxels are: global voxel (x, y, z) is data[origin + z * sz + y * sy + x] (float
//! storage), or compact[...] with the same index (compact storage; the other pointer is null).
//! Taken once per ray, so the sample loop does not reload the brick's box and strides.
struct VoxelAddressing {
  const Voxel* data;
  const CompactVoxel* compact;
  std::ptrdiff_t sy, sz, origin;
  explicit VoxelAddressing(const Brick& brick)
      : data(brick.voxelData()),
        compact(brick.compactData()),
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

//! The compact format's interpolation at p (floor = (int) p, inside the owned box): lane 0 the
//! stored value, lanes 1-3 the stored gradient (VoxelStorage says what they stand for). The two
//! voxels at x and x + 1 are adjacent 8-byte records, one 16-byte load in the SIMD march, so it
//! sums each x face over (y, z) first, corners 00 10 01 11 with weights gy gz, fy gz, gy fz, fy fz,
//! and then blends the faces: gx * face(x) + fx * face(x + 1).
inline TrilinearCell::Lanes interpolateCompact(const VoxelAddressing& at, const glm::vec3& p, const glm::ivec3& floor) {
  using Lanes = TrilinearCell::Lanes;
  const CompactVoxel* v = at.compact + (at.origin + floor.z * at.sz + floor.y * at.sy + floor.x);
  const float fx = p.x - float(floor.x), fy = p.y - float(floor.y), fz = p.z - float(floor.z);
  const float gx = 1.0f - fx, gy = 1.0f - fy, gz = 1.0f - fz;
  const float yz[4] = {gy * gz, fy * gz, gy * fz, fy * fz};
  const std::ptrdiff_t corner[4] = {0, at.sy, at.sz, at.sz + at.sy};
  auto load = [](const CompactVoxel& c) {
    return Lanes{float(c.value), float(c.gradient[0]), float(c.gradient[1]), float(c.gradient[2])};
  };
  Lanes face0 = yz[0] * load(v[0]), face1 = yz[0] * load(v[1]);
  for (int c = 1; c < 4; ++c) {
    face0 = face0 + yz[c] * load(v[corner[c]]);
    face1 = face1 + yz[c] * load(v[corner[c] + 1]);
  }
  return face0 * gx + face1 * fx;
}

}  // namespace kdswap
