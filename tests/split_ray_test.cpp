// A ray cut into segments by brick boundaries, composited with "over", equals the whole ray:
// samples sit on one global lattice and each belongs to exactly one brick (paper, Figure 3).
#include <doctest/doctest.h>

#include <algorithm>
#include <glm/geometric.hpp>
#include <random>

#include "core/render/ray_caster.h"
#include "core/render/reference_render.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("a ray split into 2 to 8 segments at arbitrary cuts equals the whole ray") {
  auto volume = test::makeBlobs({40, 36, 44}, glm::vec3(1.0f, 1.3f, 0.9f));
  const glm::ivec3 dims = volume->info().dims;
  const Brick whole = wholeVolumeBrick(*volume);
  const TransferTable table(test::testTransfer(), 0.5f);
  RenderSettings settings;
  settings.earlyTermination = 1.0f;
  const glm::vec2 range(volume->info().minValue, volume->info().maxValue);
  const RayCaster wholeCaster(whole, table, settings, range);
  const glm::vec3 worldMax = volume->info().worldMax();

  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  float worst = 0.0f;
  int raysChecked = 0;
  for (int segments = 2; segments <= 8; ++segments) {
    for (int trial = 0; trial < 6; ++trial) {
      const int axis = trial % 3;
      // Random distinct cut planes strictly inside the domain along `axis`.
      std::vector<int> cuts;
      while (int(cuts.size()) < segments - 1) {
        const int c = 1 + int(u(rng) * float(dims[axis] - 2));
        if (std::find(cuts.begin(), cuts.end(), c) == cuts.end()) cuts.push_back(c);
      }
      std::sort(cuts.begin(), cuts.end());
      std::vector<Brick> bricks;
      int lo = 0;
      for (int i = 0; i <= int(cuts.size()); ++i) {
        const int hi = i < int(cuts.size()) ? cuts[std::size_t(i)] : dims[axis] - 1;
        VoxelBox owned{glm::ivec3(0), dims - 1};
        owned.lo[axis] = lo;
        owned.hi[axis] = hi;
        bricks.push_back(test::brickOf(*volume, owned));
        lo = hi;
      }
      for (int r = 0; r < 20; ++r) {
        // A ray from outside through a random interior point, often nearly parallel to the cuts.
        const glm::vec3 target = glm::vec3(u(rng), u(rng), u(rng)) * worldMax;
        glm::vec3 dir = glm::normalize(glm::vec3(u(rng) - 0.5f, u(rng) - 0.5f, u(rng) - 0.5f));
        if (r % 4 == 0) dir[axis] = 0.0f, dir = glm::normalize(dir);  // parallel to the cut planes
        const Ray ray{target - dir * 200.0f, dir, u(rng)};  // random lattice phase, as jitter gives
        RenderCounters counters;
        const Rgba expected = wholeCaster.castRay(ray, counters);
        // Composite segments front to back: along the ray, lower `axis` first when dir[axis] >= 0.
        Rgba sum{};
        for (int i = 0; i < int(bricks.size()); ++i) {
          const int index = dir[axis] >= 0.0f ? i : int(bricks.size()) - 1 - i;
          const RayCaster part(bricks[std::size_t(index)], table, settings, range);
          sum = over(sum, part.castRay(ray, counters));
        }
        worst = std::max({worst, std::fabs(sum.r - expected.r), std::fabs(sum.g - expected.g),
                          std::fabs(sum.b - expected.b), std::fabs(sum.a - expected.a)});
        ++raysChecked;
      }
    }
  }
  CHECK(raysChecked == 7 * 6 * 20);
  CHECK(worst <= 1e-5f);
}

TEST_CASE("the segments of a split ray take exactly the samples of the whole ray") {
  auto volume = test::makeBlobs({30, 30, 30});
  const Brick whole = wholeVolumeBrick(*volume);
  const TransferTable table(test::testTransfer(), 0.37f);
  RenderSettings settings;
  settings.stepVoxels = 0.37f;
  settings.earlyTermination = 1.0f;
  const glm::vec2 range(0.0f, 1.0f);
  VoxelBox left{glm::ivec3(0), glm::ivec3(13, 29, 29)}, right{glm::ivec3(13, 0, 0), glm::ivec3(29)};
  const Brick a = test::brickOf(*volume, left), b = test::brickOf(*volume, right);
  const Ray ray{glm::vec3(-50.0f, 14.2f, 15.1f), glm::normalize(glm::vec3(1.0f, 0.01f, -0.02f))};
  RenderCounters wholeCount, partCount;
  RayCaster(whole, table, settings, range).castRay(ray, wholeCount);
  RayCaster(a, table, settings, range).castRay(ray, partCount);
  RayCaster(b, table, settings, range).castRay(ray, partCount);
  CHECK(wholeCount.samples > 50);
  CHECK(partCount.samples == wholeCount.samples);
}
