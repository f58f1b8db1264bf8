// OcclusionMap: for one frame, per pixel, the lattice index from which the single-node ray's
// samples certainly no longer count (OcclusionGrid::occludedFrom). The summary is replicated and
// the view is broadcast, so every node could compute the pixels it needs; in one process the map is
// computed once per frame and shared read-only, which costs one march per pixel instead of one per
// pixel and brick (the march from the eye to a deep brick crosses most of the volume).
#pragma once

#include <climits>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "core/camera/camera.h"
#include "core/image/rect.h"
#include "core/render/occlusion_grid.h"
#include "core/render/render_settings.h"

namespace kdswap {

class OcclusionMap {
 public:
  //! Over the pixels `camera` shows of the volume box [0, (dims-1) * spacing]; uses every worker
  //! thread of the current arena.
  OcclusionMap(const OcclusionGrid& grid, const Camera& camera, const glm::vec3& volumeWorldHi,
               const glm::vec3& spacing, const RenderSettings& settings);

  //! Samples with lattice index >= this do not count for pixel (x, y); kNever outside the volume.
  long occludedFrom(int x, int y) const {
    if (!rect_.contains(x, y)) return OcclusionGrid::kNever;
    const std::int32_t k = first_[std::size_t(y - rect_.y) * std::size_t(rect_.w) + std::size_t(x - rect_.x)];
    return k == kNeverStored ? OcclusionGrid::kNever : long(k);
  }
  //! Pixels of the map whose rays end inside the volume (for statistics and tests).
  std::size_t occludedPixels() const;

 private:
  //! Stored as 32 bits (half the memory of a frame-sized map); an index beyond that range is
  //! stored as "never", which only culls less.
  static constexpr std::int32_t kNeverStored = INT32_MAX;
  Rect rect_;
  std::vector<std::int32_t> first_;
};

}  // namespace kdswap
