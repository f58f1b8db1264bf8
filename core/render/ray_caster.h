// RayCaster: Levoy's front-to-back ray casting of one brick (paper section 3.1), with samples on a
// global lattice: sample k of every ray sits at t = k * step from the ray origin, whichever brick
// takes it, so a ray cut into segments samples exactly the points of the whole ray (Figure 3).
// It knows nothing of nodes or messages: the whole volume is just a brick that owns everything.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include <glm/vec2.hpp>

#include "core/camera/camera.h"
#include "core/render/cell_coverage.h"
#include "core/render/empty_space_map.h"
#include "core/render/front_transmittance.h"
#include "core/render/occlusion_map.h"
#include "core/image/image.h"
#include "core/render/render_settings.h"
#include "core/render/ray_march.h"
#include "core/render/voxel_ray.h"
#include "core/transfer/transfer_function.h"
#include "core/volume/brick.h"

namespace kdswap {

struct RenderCounters {
  //! Rays that met the brick (culled ones counted, even if they would miss it). With a
  //! CellCoverage (render always uses one), rays whose pixel it leaves out are not counted.
  std::uint64_t rays = 0;
  std::uint64_t samples = 0;  //!< samples taken inside the brick
  std::uint64_t occluded = 0; //!< rays skipped: opaque matter in front of the brick ends them
  double seconds = 0.0;       //!< work time, summed over tiles (time on one processor)

  //! Adds another part's counts (tiles of one render, pieces of one brick).
  RenderCounters& operator+=(const RenderCounters& other) {
    rays += other.rays, samples += other.samples, occluded += other.occluded, seconds += other.seconds;
    return *this;
  }
};

class RayCaster {
 public:
  //! `valueRange` maps scalars to [0, 1]. The caster keeps references: all must outlive it.
  //! With `occlusion`, each ray stops at the lattice index from which the single-node ray's
  //! samples certainly no longer count (see occlusion_map.h). `emptySpace`, when given, is this
  //! brick's map under this table, mapping and settings (kept across frames by an EmptySpaceCache);
  //! otherwise the caster builds its own. With `front` (front-to-back waves), each ray stops where
  //! the light left in front of the brick times its own transmittance reaches the termination
  //! stop, pixels already stopped in front take no ray, and render multiplies each pixel's light
  //! by the brick's transmittance there (as FrontTransmittance::addBehind of its image would).
  RayCaster(const Brick& brick, const TransferTable& table, const RenderSettings& settings, glm::vec2 valueRange,
            const OcclusionMap* occlusion = nullptr, std::shared_ptr<const EmptySpaceMap> emptySpace = nullptr,
            FrontTransmittance* front = nullptr);

  //! The screen rectangle a brick's partial image covers: its visible box (under `emptySpace`,
  //! the brick's map) projected; empty when nothing in it is visible.
  static Rect screenRect(const EmptySpaceMap& emptySpace, const glm::vec3& spacing, const Camera& camera);

  //! Partial image over the screen rectangle the brick covers (empty for an empty brick).
  //! Uses every worker thread of the current arena (tiles), isolated from other tasks. With
  //! `content`, also the bounds of its pixels with opacity above 0 (Image::opaqueBounds, found
  //! as the pixels are written instead of by a scan).
  Image render(const Camera& camera, RenderCounters& counters, Rect* content = nullptr) const;

  //! The rectangle render's image covers (screenRect of the brick's visible box; empty when none).
  Rect screenRect(const Camera& camera) const;
  //! The pixels of screenRect(camera) whose rays can meet a visible cell (the others need no ray).
  CellCoverage coverage(const Camera& camera) const;

  //! render's pixels of `region` only, into `image` (over the rectangle render would cover, or
  //! holding `region`), on the calling thread; adds to `counters`. Pixels of a region are
  //! the same as render's: waves render a brick one screen cell at a time with it. With
  //! `coverage` (this caster's, for `camera`), pixels it leaves out get no ray; the counters then
  //! equal render's too. Returns the bounds of the region's pixels it left with opacity above 0.
  Rect renderRegion(const Camera& camera, const Rect& region, Image& image, RenderCounters& counters,
                    const CellCoverage* coverage = nullptr) const;

  //! One pixel: premultiplied colour and opacity of this brick's segment of the ray, from its
  //! samples with lattice index below `occludedFrom`.
  Rgba castRay(const Ray& ray, RenderCounters& counters, long occludedFrom = OcclusionGrid::kNever) const;

  //! Replaces the sample loop (tests compare the scalar and SIMD marches); null keeps the current one.
  void useMarch(MarchFunction march);

 private:
  //! The box rays are clipped to (the visible part of the owned box) and the size of its far
  //! corner, for the clip's rounding margin: per brick, not per ray.
  struct ClipBox {
    glm::vec3 lo, hi;
    float hiMagnitude;
  };
  ClipBox clipBox() const;
  //! A lattice index (samples `step` apart) no ray of `camera` reaches the brick before:
  //! where the occlusion map ends the ray at or before this index, the pixel needs no ray at all.
  long firstLatticeIndexBound(const Camera& camera, float step) const;
  //! The ray's owned samples in this brick as a segment to march; false when it has none to take
  //! (misses the visible box, ends before it, or no lattice point falls inside).
  bool segmentFor(const VoxelRay& ray, const glm::vec3& toLight, const ClipBox& clip, RenderCounters& counters,
                  long occludedFrom, RaySegment& segment) const;
  //! segmentFor after a clip that passed: `firstIndex` = floor(tNear / step - phase) and
  //! `lastIndex` = ceil(tFar / step - phase), as floats. Shared with the eight-ray setup, which may
  //! pass the ownership of the search's first four candidates at each end (RayLanes8::nearOwned,
  //! farOwned; -1: not known, search from scratch). The run found is the same either way.
  bool segmentFromClip(const glm::vec3& o, const glm::vec3& d, const glm::vec3& inverse, float step, float phase,
                       float inverseStep, float firstIndex, float lastIndex, const glm::vec3& toLight,
                       RenderCounters& counters, long occludedFrom, RaySegment& segment, int nearOwned = -1,
                       int farOwned = -1) const;

  const Brick& brick_;
  const TransferTable& table_;
  const RenderSettings& settings_;
  float scale_, bias_;   //!< normalised scalar = value * scale + bias
  std::shared_ptr<const EmptySpaceMap> emptySpace_;  //!< invisible macro cells under this transfer function
  const OcclusionMap* occlusion_;
  FrontTransmittance* front_;
  std::shared_ptr<const std::vector<float>> specular_;  //!< pow(x, shininess) over [0, 1] (specular_table.h)
  MarchContext march_;           //!< the brick's constants for the sample loop
  MarchFunction marchFunction_;  //!< scalar or SIMD: equal results
};

}  // namespace kdswap
