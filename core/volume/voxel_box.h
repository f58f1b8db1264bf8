// VoxelBox: a box of integer voxel coordinates [lo, hi) per axis. Used both for sets of voxel
// indices (readers, bricks' storage) and, for k-d cells, for the continuous region [lo, hi) of
// sample positions a brick owns (corners are voxel centres, so cuts fall on voxel planes).
#pragma once

#include <cstdint>

#include <glm/vec3.hpp>

namespace kdswap {

struct VoxelBox {
  glm::ivec3 lo{0}, hi{0};

  glm::ivec3 size() const { return hi - lo; }
  bool empty() const { return hi.x <= lo.x || hi.y <= lo.y || hi.z <= lo.z; }
  std::int64_t count() const {
    return empty() ? 0 : std::int64_t(hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z);
  }
  bool contains(const glm::ivec3& p) const {
    return p.x >= lo.x && p.y >= lo.y && p.z >= lo.z && p.x < hi.x && p.y < hi.y && p.z < hi.z;
  }
  bool operator==(const VoxelBox&) const = default;
};

}  // namespace kdswap
