// Occlusion map: one march through the replicated cell summary per pixel, rows in parallel.
#include "core/render/occlusion_map.h"

#include <algorithm>

#include <oneapi/tbb/blocked_range.h>
#include <oneapi/tbb/parallel_for.h>

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
  tbb::parallel_for(tbb::blocked_range<int>(rect_.y, rect_.bottom(), 4), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y) {
      std::int32_t* out = first_.data() + std::size_t(y - rect_.y) * std::size_t(rect_.w);
      // Runs of a row's pixels walk together (eight at once with AVX2).
      constexpr int kRun = 64;
      glm::vec3 origins[kRun], directions[kRun];
      float phases[kRun];
      long found[kRun];
      for (int x0 = rect_.x; x0 < rect_.right(); x0 += kRun) {
        const int n = std::min(kRun, rect_.right() - x0);
        for (int i = 0; i < n; ++i) {
          const VoxelRay r(camera.ray(x0 + i, y), scale);
          origins[i] = r.origin, directions[i] = r.direction, phases[i] = r.phase;
        }
        grid.occludedFrom(origins, directions, phases, n, scale.step, found);
        for (int i = 0; i < n; ++i)
          out[x0 + i - rect_.x] = found[i] >= long(kNeverStored) ? kNeverStored : std::int32_t(found[i]);
      }
    }
  });
}

std::size_t OcclusionMap::occludedPixels() const {
  return std::size_t(std::count_if(first_.begin(), first_.end(), [](std::int32_t k) { return k != kNeverStored; }));
}

}  // namespace kdswap
