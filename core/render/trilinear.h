// Trilinear interpolation of a brick's stored values and gradients at a point in voxel
// coordinates, for either storage format. The ray caster and the tests use these definitions.
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>

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

//! The compact format's x weights are integers: fx * 2^14 rounded to nearest (even), and 2^14 minus
//! it. Both x corners of a (y, z) pair are adjacent 8-byte records, one 16-byte load in the SIMD
//! march, and with integer weights one multiply-add of 16-bit pairs (pmaddwd) blends them exactly,
//! four samples to a 512-bit register, before anything is converted to float. |sum| <= 2^15 * 2^14.
constexpr int kCompactXWeightBits = 14;
//! 2^-14: the (y, z) weights carry it, so the result is in stored units (an exact power of two).
constexpr float kCompactXWeightScale = 1.0f / float(1 << kCompactXWeightBits);

//! The compact format's interpolation at p (floor = (int) p, inside the owned box): lane 0 the
//! stored value, lanes 1-3 the stored gradient (VoxelStorage says what they stand for). Each (y, z)
//! pair of corners 00 10 01 11 is blended along x in integers (kCompactXWeightBits), converted to
//! float, weighted by gy gz, fy gz, gy fz, fy fz (each times 2^-14) and summed in that order.
inline TrilinearCell::Lanes interpolateCompact(const VoxelAddressing& at, const glm::vec3& p, const glm::ivec3& floor) {
  using Lanes = TrilinearCell::Lanes;
  const CompactVoxel* v = at.compact + (at.origin + floor.z * at.sz + floor.y * at.sy + floor.x);
  const float fx = p.x - float(floor.x), fy = p.y - float(floor.y), fz = p.z - float(floor.z);
  const float gy = 1.0f - fy, gz = (1.0f - fz) * kCompactXWeightScale;
  const float fzScaled = fz * kCompactXWeightScale;
  const float yz[4] = {gy * gz, fy * gz, gy * fzScaled, fy * fzScaled};
  const std::int32_t wx1 = std::int32_t(std::nearbyint(fx * float(1 << kCompactXWeightBits)));
  const std::int32_t wx0 = (1 << kCompactXWeightBits) - wx1;
  const std::ptrdiff_t corner[4] = {0, at.sy, at.sz, at.sz + at.sy};
  auto blendX = [&](const CompactVoxel& a, const CompactVoxel& b) {
    return Lanes{float(std::int32_t(a.value) * wx0 + std::int32_t(b.value) * wx1),
                 float(std::int32_t(a.gradient[0]) * wx0 + std::int32_t(b.gradient[0]) * wx1),
                 float(std::int32_t(a.gradient[1]) * wx0 + std::int32_t(b.gradient[1]) * wx1),
                 float(std::int32_t(a.gradient[2]) * wx0 + std::int32_t(b.gradient[2]) * wx1)};
  };
  Lanes sum = yz[0] * blendX(v[0], v[1]);
  for (int c = 1; c < 4; ++c) sum = sum + yz[c] * blendX(v[corner[c]], v[corner[c] + 1]);
  return sum;
}

//! Value and gradient of a sample in a uniform cell (Brick::uniformCells): the record at its floor,
//! as interpolation would give them up to rounding (stored units for compact storage, as
//! interpolateCompact). Lane 0 the value, lanes 1-3 the gradient.
inline TrilinearCell::Lanes recordOf(const CompactVoxel& v) {
  return TrilinearCell::Lanes{float(v.value), float(v.gradient[0]), float(v.gradient[1]), float(v.gradient[2])};
}
inline TrilinearCell::Lanes recordOf(const Voxel& v) {
  return TrilinearCell::Lanes{v.value, v.gradient.x, v.gradient.y, v.gradient.z};
}
inline TrilinearCell::Lanes uniformRecord(const VoxelAddressing& at, const glm::ivec3& floor) {
  const std::ptrdiff_t i = at.origin + floor.z * at.sz + floor.y * at.sy + floor.x;
  return at.compact ? recordOf(at.compact[i]) : recordOf(at.data[i]);
}

}  // namespace kdswap
