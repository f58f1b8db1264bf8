// Occlusion map: one march through the replicated cell summary per pixel, eight or sixteen pixels of
// a row at once (OcclusionGrid::walksSixteen), rows in parallel.
#include "core/render/occlusion_map.h"

#include <algorithm>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

#include "core/render/ray_setup.h"
#include "core/render/voxel_ray.h"

namespace kdswap {

OcclusionMap::OcclusionMap(const OcclusionGrid& grid, const Camera& camera, const glm::vec3& volumeWorldHi,
                           const glm::vec3& spacing, const RenderSettings& settings)
    : rect_(camera.projectBox(glm::vec3(0.0f), volumeWorldHi)) {
  if (rect_.empty() || !grid.active()) {
    rect_ = Rect{};
    return;
  }
  first_.resize(std::size_t(rect_.area()));
  const VoxelRay::Scale scale(spacing, settings);
  // Rays eight pixels at a time where AVX2 allows (the same numbers as VoxelRay, ray_setup.h).
  const bool simdRays = raySetup8Available();
  RaySetupConstants rays8{};
  rays8.camera = camera.basis(), rays8.inverseSpacing = scale.inverseSpacing, rays8.jitter = scale.jitter;
  rays8.phaseShift = scale.phaseShift;
  tbb::parallel_for(tbb::blocked_range<int>(rect_.y, rect_.bottom(), 4), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      std::int32_t* out = first_.data() + std::size_t(y - rect_.y) * std::size_t(rect_.w);
      long found[16];
      VoxelRays8 rays, more;
      const auto raysAt = [&](int x0, VoxelRays8& out) {
        if (simdRays) {
          voxelRays8(rays8, x0, y, out);
          return;
        }
        for (int j = 0; j < 8; ++j) {  // pixels past the row's end compute harmless rays
          const VoxelRay r(camera.ray(x0 + j, y), scale);
          out.ox[j] = r.origin.x, out.oy[j] = r.origin.y, out.oz[j] = r.origin.z;
          out.dx[j] = r.direction.x, out.dy[j] = r.direction.y, out.dz[j] = r.direction.z;
          out.phase[j] = r.phase;
        }
      };
      const int group = grid.walksSixteen() ? 16 : 8;
      for (int x0 = rect_.x; x0 < rect_.right(); x0 += group) {
        const int n = std::min(group, rect_.right() - x0);
        raysAt(x0, rays);
        if (group == 16) {
          raysAt(x0 + 8, more);
          grid.occludedFrom(rays, more, scale.step, found);
        } else {
          grid.occludedFrom(rays, scale.step, found);
        }
        for (int j = 0; j < n; ++j)
          out[x0 + j - rect_.x] = found[j] >= long(kNeverStored) ? kNeverStored : std::int32_t(found[j]);
      }
    }
  });
}

std::size_t OcclusionMap::occludedPixels() const {
  return std::size_t(std::count_if(first_.begin(), first_.end(), [](std::int32_t k) { return k != kNeverStored; }));
}

}  // namespace kdswap
