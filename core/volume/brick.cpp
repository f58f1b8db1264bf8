// Brick storage and per-voxel gradients; the gradient formula matches the whole volume's exactly
// (central differences inside, one-sided at the volume's faces), which is what makes split rays
// equal whole rays next to a cut.
#include "core/volume/brick.h"

#include <algorithm>

#include <glm/common.hpp>
#include <glm/vector_relational.hpp>

#include "core/util/check.h"

namespace kdswap {

VoxelBox Brick::storedBoxFor(const VoxelBox& owned, const glm::ivec3& dims) {
  if (owned.empty()) return VoxelBox{};
  return VoxelBox{glm::max(owned.lo - 1, glm::ivec3(0)), glm::min(owned.hi + 2, dims)};
}

VoxelBox Brick::ownedVoxelsFor(const VoxelBox& owned, const glm::ivec3& dims) {
  if (owned.empty()) return VoxelBox{};
  VoxelBox v = owned;
  for (int a = 0; a < 3; ++a)
    if (owned.hi[a] == dims[a] - 1) v.hi[a] = dims[a];
  return v;
}

Brick::Brick(const VoxelBox& owned, const glm::ivec3& dims, const glm::vec3& spacing, std::vector<float> raw)
    : owned_(owned), stored_(storedBoxFor(owned, dims)), dims_(dims), spacing_(spacing) {
  if (owned_.empty()) return;
  const glm::ivec3 s = stored_.size();
  strideY_ = std::size_t(s.x);
  strideZ_ = std::size_t(s.x) * s.y;
  KDSWAP_CHECK_EQ(raw.size(), std::size_t(stored_.count()));
  voxels_.resize(raw.size());
  auto at = [&](int x, int y, int z) {
    return raw[std::size_t(z - stored_.lo.z) * strideZ_ + std::size_t(y - stored_.lo.y) * strideY_ + (x - stored_.lo.x)];
  };
  // Gradients are needed at the voxels of [owned.lo, owned.hi]; the outer ghost layer only feeds them.
  const glm::ivec3 gLo = owned_.lo, gHi = glm::min(owned_.hi, dims - 1);
  for (int z = stored_.lo.z; z < stored_.hi.z; ++z)
    for (int y = stored_.lo.y; y < stored_.hi.y; ++y)
      for (int x = stored_.lo.x; x < stored_.hi.x; ++x) {
        Voxel& out = voxels_[std::size_t(z - stored_.lo.z) * strideZ_ + std::size_t(y - stored_.lo.y) * strideY_ +
                             (x - stored_.lo.x)];
        out.value = at(x, y, z);
        out.gradient = glm::vec3(0.0f);
        const glm::ivec3 p(x, y, z);
        if (glm::any(glm::lessThan(p, gLo)) || glm::any(glm::greaterThan(p, gHi))) continue;
        for (int a = 0; a < 3; ++a) {
          glm::ivec3 lo = p, hi = p;
          lo[a] = std::max(p[a] - 1, 0);
          hi[a] = std::min(p[a] + 1, dims[a] - 1);
          const float span = float(hi[a] - lo[a]) * spacing[a];
          out.gradient[a] = (at(hi.x, hi.y, hi.z) - at(lo.x, lo.y, lo.z)) / span;
        }
      }
}

}  // namespace kdswap
