// The eight-ray setup (AVX2) against Camera::ray and VoxelRay, lane by lane and bit for bit, over
// perspective and orthographic views, odd frame sizes, spacings, jitter on and off and lattice phase
// shifts (kdswap render --passes). (That the clip and lattice indices match too is checked through
// render() = castRay in ray_march_test.cpp.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cstring>
#include <utility>

#include "core/camera/camera.h"
#include "core/render/ray_setup.h"
#include "core/render/render_settings.h"
#include "core/render/voxel_ray.h"

using namespace kdswap;

namespace {

bool sameBits(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

}  // namespace

TEST_CASE("eight rays set up at once equal Camera::ray and VoxelRay pixel by pixel, bit for bit") {
  if (!raySetup8Available()) {
    MESSAGE("no AVX2 here (or KDSWAP_SIMD=scalar): rays are set up one by one, nothing to compare");
    return;
  }
  long lanes = 0, differing = 0, crossing = 0, windows = 0, wrongEnds = 0, ownedEnds = 0;
  for (const Projection projection : {Projection::Perspective, Projection::Orthographic})
    for (const float azimuth : {0.0f, 33.0f, 90.0f, 250.0f})
      for (const auto& [jitter, shift] : {std::pair{false, 0.0f}, std::pair{true, 0.0f}, std::pair{false, 0.37f},
                                          std::pair{true, latticePassShift(3)}}) {
        View view;
        view.distance = 2.5f;  // close: the volume fills most of the small frame
        view.azimuthDeg = azimuth;
        view.elevationDeg = azimuth - 60.0f;
        view.projection = projection;
        const glm::vec3 spacing = azimuth == 33.0f ? glm::vec3(3.2f, 3.2f, 1.5f) : glm::vec3(1.0f);
        const glm::vec3 worldHi = glm::vec3(63.0f, 63.0f, 92.0f) * spacing;
        const int width = 61, height = 37;  // rows not a multiple of eight
        const Camera camera(view, glm::vec3(0.0f), worldHi, width, height);
        RenderSettings settings;
        settings.jitter = jitter;
        settings.phaseShift = shift;  // a pass of kdswap render --passes
        settings.stepVoxels = 0.5f;
        const VoxelRay::Scale scale(spacing, settings);
        const RaySetupConstants c{camera.basis(), scale.inverseSpacing, scale.inverseStep, scale.jitter,
                                  scale.phaseShift,   glm::vec3(8.0f, 4.0f, 10.0f), glm::vec3(40.0f, 50.0f, 60.0f), 61.0f,
                                  glm::vec3(8.0f, 4.0f, 10.0f), glm::vec3(40.0f, 50.0f, 60.0f), scale.step};
        // RayCaster's exact ownership rule for lattice index k of a lane's ray.
        const auto owned = [&](const RayLanes8& r, int j, long k) {
          const float t = (float(k) + r.phase[j]) * scale.step;
          const glm::vec3 p = glm::vec3(r.ox[j], r.oy[j], r.oz[j]) + glm::vec3(r.dx[j], r.dy[j], r.dz[j]) * t;
          return p.x >= c.ownedLo.x && p.x < c.ownedHi.x && p.y >= c.ownedLo.y && p.y < c.ownedHi.y &&
                 p.z >= c.ownedLo.z && p.z < c.ownedHi.z;
        };
        RayLanes8 out;
        for (int y = 0; y < height; ++y)
          for (int x0 = 0; x0 < width; x0 += 8) {
            setupRays8(c, x0, y, out);
            for (int j = 0; j < 8 && x0 + j < width; ++j) {
              const Ray ray = camera.ray(x0 + j, y);
              const VoxelRay v(ray, scale);
              const glm::vec3 inverse = 1.0f / v.direction;
              ++lanes;
              crossing += (out.crosses >> j) & 1;
              differing += !(sameBits(out.ox[j], v.origin.x) && sameBits(out.oy[j], v.origin.y) &&
                             sameBits(out.oz[j], v.origin.z) && sameBits(out.dx[j], v.direction.x) &&
                             sameBits(out.dy[j], v.direction.y) && sameBits(out.dz[j], v.direction.z) &&
                             sameBits(out.ix[j], inverse.x) && sameBits(out.iy[j], inverse.y) &&
                             sameBits(out.iz[j], inverse.z) && sameBits(out.wx[j], ray.direction.x) &&
                             sameBits(out.wy[j], ray.direction.y) && sameBits(out.wz[j], ray.direction.z) &&
                             sameBits(out.phase[j], v.phase));
              // The owned-run ends' first four candidates, where given, follow the same rule.
              if ((out.windows >> j) & 1) {
                ++windows;
                const long kBegin = std::max(0L, long(out.firstIndex[j]) - 1), kEnd = long(out.lastIndex[j]) + 1;
                for (int i = 0; i < 4; ++i) {
                  wrongEnds += ((out.nearOwned[j] >> i) & 1) != int(owned(out, j, kBegin + i));
                  wrongEnds += ((out.farOwned[j] >> i) & 1) != int(owned(out, j, kEnd - 3 + i));
                  ownedEnds += ((out.nearOwned[j] >> i) & 1) + ((out.farOwned[j] >> i) & 1);
                }
              }
            }
          }
      }
  CHECK(lanes == 32L * 61 * 37);  // 2 projections x 4 views x 4 phase settings, every pixel
  CHECK(differing == 0);
  CHECK(crossing > lanes / 10);  // the clip box is in view: many rays cross it, not all
  CHECK(crossing < lanes);
  CHECK(windows >= crossing);  // every crossing ray's ends are tested ahead
  CHECK(wrongEnds == 0);
  CHECK(ownedEnds > windows);  // and most runs start and end within them
}
