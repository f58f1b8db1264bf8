// CullingRest: when a cluster skips occlusion culling for a while. Culling saves work but never
// changes an image; its map (one march per pixel) pays where opaque matter hides much of the
// bricks behind it (turbulence: 64% of ray-brick pairs culled, 17.8 M -> 6.2 M samples) and costs
// ~8% of a frame where little is hidden (CT head, default scene: ~1% culled). After a frame that
// culled under kMinCulledShare of its ray-brick pairs, the next kRestFrames frames go without it;
// then it is tried again (the view or the transfer function may have changed). The virtual
// cluster and the MPI ranks follow the same rule, so their frames take the same samples.
#pragma once

#include <cstdint>

namespace kdswap {

class CullingRest {
 public:
  static constexpr double kMinCulledShare = 0.05;
  static constexpr int kRestFrames = 15;

  //! Called once per frame that could cull: false while resting (and counts the rest down).
  bool mapThisFrame() {
    if (restFrames_ == 0) return true;
    --restFrames_;
    return false;
  }

  //! After a frame that used the map: its ray-brick pairs and how many the map culled.
  void afterFrame(std::uint64_t rays, std::uint64_t occluded) {
    if (double(occluded) < kMinCulledShare * double(rays)) restFrames_ = kRestFrames;
  }

 private:
  int restFrames_ = 0;
};

}  // namespace kdswap
