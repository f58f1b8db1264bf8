// Occlusion map: one march through the replicated cell summary per pixel, eight pixels of a row at
// once, rows in parallel.
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
      long found[8];
      VoxelRays8 rays;
      for (int x0 = rect_.x; x0 < rect_.right(); x0 += 8) {
        const int n = std::min(8, rect_.right() - x0);
        if (simdRays) {
          voxelRays8(rays8, x0, y, rays);
        } else {
          for (int j = 0; j < 8; ++j) {  // pixels past the row's end compute harmless rays
            const VoxelRay r(camera.ray(x0 + j, y), scale);
            rays.ox[j] = r.origin.x, rays.oy[j] = r.origin.y, rays.oz[j] = r.origin.z;
            rays.dx[j] = r.direction.x, rays.dy[j] = r.direction.y, rays.dz[j] = r.direction.z;
            rays.phase[j] = r.phase;
          }
        }
        grid.occludedFrom(rays, scale.step, found);
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
