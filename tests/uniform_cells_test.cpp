// Uniform macro cells: where every voxel record a sample can touch is the same, the sample takes
// that record instead of interpolating eight equal corners. Which cells qualify, and that images
// with them equal images without them to rounding, with the same samples. (The SIMD marches'
// equality with the scalar one, uniform cells included, is ray_march_test's.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <memory>

#include "core/render/empty_space_map.h"
#include "core/render/ray_caster.h"
#include "core/render/reference_render.h"
#include "core/transfer/presets.h"
#include "core/volume/datasets/dataset.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("a macro cell is uniform exactly where every voxel record its samples touch is the same") {
  const glm::ivec3 dims(20, 18, 22), odd(10, 9, 11);
  auto volume = test::makeVolume(dims, [&](int x, int y, int z) { return glm::ivec3(x, y, z) == odd ? 0.9f : 0.5f; });
  // The odd voxel's record differs in its value; its six face neighbours' in their gradients.
  auto differs = [&](const glm::ivec3& v) {
    const glm::ivec3 d = glm::abs(v - odd);
    return d.x + d.y + d.z <= 1;
  };
  for (const VoxelChoice voxels : {VoxelChoice::Float, VoxelChoice::Compact})
    for (const int shift : {1, 2}) {
      const Brick brick = wholeVolumeBrick(*volume, shift, voxels);
      const glm::ivec3 n = brick.cellCount();
      REQUIRE(brick.uniformCells().size() == std::size_t(n.x) * n.y * n.z);
      int uniform = 0, mixed = 0;
      for (int cz = 0; cz < n.z; ++cz)
        for (int cy = 0; cy < n.y; ++cy)
          for (int cx = 0; cx < n.x; ++cx) {
            // Samples with floor in the cell touch floor .. floor + 1 (within the owned box).
            const glm::ivec3 c = glm::ivec3(cx, cy, cz) + brick.cellLo();
            const glm::ivec3 lo = glm::max(c << shift, brick.owned().lo);
            const glm::ivec3 hi = glm::min((c + 1) << shift, brick.owned().hi);
            bool expected = true;
            for (int z = lo.z; z <= hi.z; ++z)
              for (int y = lo.y; y <= hi.y; ++y)
                for (int x = lo.x; x <= hi.x; ++x) expected = expected && !differs(glm::ivec3(x, y, z));
            const bool marked = brick.uniformCells()[(std::size_t(cz) * n.y + cy) * n.x + cx] != 0;
            CAPTURE(cx);
            CAPTURE(cy);
            CAPTURE(cz);
            CAPTURE(shift);
            CHECK(marked == expected);
            (marked ? uniform : mixed) += 1;
          }
      CHECK(uniform > 0);
      CHECK(mixed > 0);
      // The march codes carry the brick's marks on visible cells (all are, under this table).
      const TransferTable table(test::testTransfer(), 0.5f);
      const EmptySpaceMap map(brick, table, 1.0f, 0.0f);
      REQUIRE(map.anyUniform());
      for (std::size_t i = 0; i < brick.uniformCells().size(); ++i)
        CHECK(map.marchCodes()[i] == (brick.uniformCells()[i] != 0 ? EmptySpaceMap::kUniformBit : 0));
    }

  // A ramp has no uniform cell (the blobs' zeros around the ball are uniform); a constant field is
  // all uniform, and under a transfer function that shows it every code carries the bit.
  const Brick ramp =
      wholeVolumeBrick(*test::makeVolume({24, 20, 26}, [](int x, int y, int z) { return 0.01f * float(x + 2 * y + 3 * z); }), 1);
  CHECK(std::count(ramp.uniformCells().begin(), ramp.uniformCells().end(), 1) == 0);
  const Brick blobs = wholeVolumeBrick(*test::makeBlobs({24, 20, 26}), 1);
  CHECK(std::count(blobs.uniformCells().begin(), blobs.uniformCells().end(), 1) > 0);
  const Brick flat = wholeVolumeBrick(*test::makeVolume({16, 16, 16}, [](int, int, int) { return 0.5f; }), 1);
  CHECK(std::count(flat.uniformCells().begin(), flat.uniformCells().end(), 0) == 0);
  const TransferTable table(test::testTransfer(), 0.5f);
  const EmptySpaceMap shown(flat, table, 1.0f, 0.0f);
  CHECK(shown.anyUniform());
  CHECK(shown.marchCodes()[0] == EmptySpaceMap::kUniformBit);
  CHECK_FALSE(EmptySpaceMap(flat, table, 1.0f, 0.0f, true, false).anyUniform());
  CHECK_FALSE(EmptySpaceMap(flat, table, 1.0f, -0.5f).anyUniform());  // invisible there: skipped, not shaded
}

TEST_CASE("samples in uniform cells take the cell's record: the image interpolation gives, to rounding, same samples") {
  auto phantom = openDataset("phantom:48");
  const TransferFunction tf = loadTransferFunction("phantom");
  const glm::vec2 range = resolveValueRange(RenderSettings{}, phantom->info());
  const glm::vec2 map = normalisingScaleBias(range);
  const VoxelBox cut{glm::ivec3(5, 11, 2), glm::ivec3(40, 37, 30)};  // a brick with cut faces and offsets
  const Brick bricks[] = {wholeVolumeBrick(*phantom, 1), wholeVolumeBrick(*phantom, 2, VoxelChoice::Compact),
                          test::brickOf(*phantom, cut, 1), test::brickOf(*phantom, cut, 2, VoxelChoice::Compact)};
  std::uint64_t samples = 0;
  for (const Brick& brick : bricks)
    for (const float azimuth : {0.0f, 63.0f, 200.0f}) {
      View view;
      view.azimuthDeg = azimuth;
      view.elevationDeg = azimuth > 100.0f ? -35.0f : 15.0f;
      RenderSettings settings;
      settings.earlyTermination = 1.0f;  // every ray to its end: the sample counts must agree exactly
      settings.stepVoxels = azimuth == 63.0f ? 1.0f : 0.5f;
      const TransferTable table(tf, settings.stepVoxels);
      auto with = std::make_shared<const EmptySpaceMap>(brick, table, map.x, map.y);
      auto without = std::make_shared<const EmptySpaceMap>(brick, table, map.x, map.y, true, false);
      REQUIRE(with->anyUniform());
      const Camera camera(view, glm::vec3(0.0f), glm::vec3(brick.volumeDims() - 1) * brick.spacing(), 64, 56);
      RenderCounters a, b;
      const Image taken = RayCaster(brick, table, settings, range, nullptr, with).render(camera, a);
      const Image interpolated = RayCaster(brick, table, settings, range, nullptr, without).render(camera, b);
      CAPTURE(azimuth);
      CAPTURE(brick.storage().compactFormat());
      CHECK(a.samples == b.samples);
      REQUIRE(taken.rect() == interpolated.rect());
      float worst = 0.0f, opacity = 0.0f;
      for (int y = taken.rect().y; y < taken.rect().bottom(); ++y)
        for (int x = taken.rect().x; x < taken.rect().right(); ++x) {
          const Rgba p = taken.sample(x, y), q = interpolated.sample(x, y);
          worst = std::max({worst, std::fabs(p.r - q.r), std::fabs(p.g - q.g), std::fabs(p.b - q.b), std::fabs(p.a - q.a)});
          opacity += p.a;
        }
      CHECK(worst <= 2e-6f);
      CHECK(opacity > 50.0f);  // the view shows the phantom
      samples += a.samples;
    }
  CHECK(samples > 200000);
}
