// Empty-space skipping: the cell distance map is the true chessboard distance, and rays that jump
// over invisible regions give the image of rays that sample every lattice point (to rounding).
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <random>

#include "core/render/empty_space_map.h"
#include "core/render/ray_caster.h"
#include "core/render/ray_march.h"
#include "core/render/reference_render.h"
#include "core/transfer/presets.h"
#include "core/volume/datasets/dataset.h"
#include "test_support.h"

using namespace kdswap;

namespace {

std::vector<std::uint8_t> bruteForce(const std::vector<std::uint8_t>& marks, const glm::ivec3& n) {
  std::vector<std::uint8_t> d(marks.size(), 255);
  for (int z = 0; z < n.z; ++z)
    for (int y = 0; y < n.y; ++y)
      for (int x = 0; x < n.x; ++x) {
        int best = 255;
        for (int qz = 0; qz < n.z; ++qz)
          for (int qy = 0; qy < n.y; ++qy)
            for (int qx = 0; qx < n.x; ++qx)
              if (marks[(std::size_t(qz) * n.y + qy) * n.x + qx] == 0)
                best = std::min(best, std::max({std::abs(qx - x), std::abs(qy - y), std::abs(qz - z)}));
        d[(std::size_t(z) * n.y + y) * n.x + x] = std::uint8_t(best);
      }
  return d;
}

}  // namespace

TEST_CASE("the cell distance map is the chessboard distance to the nearest visible cell") {
  std::mt19937 rng(11);
  const glm::ivec3 shapes[] = {{1, 1, 1}, {5, 1, 1}, {1, 7, 3}, {6, 5, 4}, {9, 8, 7}, {12, 3, 10}};
  for (const glm::ivec3& n : shapes)
    for (const double density : {0.0, 0.02, 0.1, 0.5, 1.0}) {
      std::bernoulli_distribution visible(density);
      std::vector<std::uint8_t> marks(std::size_t(n.x) * n.y * n.z);
      for (std::uint8_t& m : marks) m = visible(rng) ? 0 : 1;
      CAPTURE(n.x);
      CAPTURE(n.y);
      CAPTURE(n.z);
      CAPTURE(density);
      CHECK(EmptySpaceMap::chessboardDistance(marks, n) == bruteForce(marks, n));
    }
}

TEST_CASE("skipping empty space changes no pixel beyond rounding, only the number of samples taken") {
  struct Case {
    std::string data, transfer;
  };
  // Turbulence is dense under its own preset: a threshold at 70% leaves it gaps to skip.
  const Case cases[] = {{"phantom:40", "grayscale"}, {"phantom:40", "phantom"}, {"vessels:40", "vessels"},
                        {"turbulence:32", "threshold"}};
  const TransferFunction threshold({{0.0f, {0.2f, 0.3f, 0.9f}}, {1.0f, {1.0f, 0.9f, 0.6f}}},
                                   {{0.0f, 0.0f}, {0.7f, 0.0f}, {1.0f, 0.6f}}, "threshold");
  for (const Case& c : cases) {
    auto volume = openDataset(c.data);
    const glm::ivec3 dims = volume->info().dims;
    const TransferFunction tf = c.transfer == "threshold" ? threshold : loadTransferFunction(c.transfer);
    const glm::vec2 range = resolveValueRange(RenderSettings{}, volume->info());
    // The whole volume and a brick cut out of it (skipping works on the brick's own cells).
    // All three sizes of empty-space cells (one voxel, 2^3, 4^3: Brick::cellShiftFor) and both
    // voxel formats (compact cells hold the stored values' ranges).
    const VoxelBox cut{glm::ivec3(3, 9, 0), glm::ivec3(dims.x - 1, 30, 21)};
    const VoxelChoice compact = VoxelChoice::Compact;
    const Brick bricks[] = {wholeVolumeBrick(*volume, 0),          test::brickOf(*volume, cut, 0),
                            wholeVolumeBrick(*volume, 1),          test::brickOf(*volume, cut, 1),
                            wholeVolumeBrick(*volume, 2),          test::brickOf(*volume, cut, 2),
                            wholeVolumeBrick(*volume, 2, compact), test::brickOf(*volume, cut, 1, compact),
                            test::brickOf(*volume, cut, 0, compact)};
    for (const Brick& brick : bricks)
      for (const float azimuth : {0.0f, 37.0f, 90.0f, 211.0f}) {
        View view;
        view.azimuthDeg = azimuth;
        view.elevationDeg = azimuth > 100.0f ? -40.0f : 20.0f;
        view.projection = azimuth == 90.0f ? Projection::Orthographic : Projection::Perspective;
        RenderSettings skipping, sampling;
        skipping.stepVoxels = sampling.stepVoxels = azimuth == 37.0f ? 1.0f : 0.5f;
        sampling.skipEmptySpace = false;
        const ReferenceResult a = renderReference(brick, view, 72, 64, tf, skipping, range);
        const ReferenceResult b = renderReference(brick, view, 72, 64, tf, sampling, range);
        CAPTURE(c.data);
        CAPTURE(c.transfer);
        CAPTURE(azimuth);
        CAPTURE(brick.owned().lo.x);
        CAPTURE(brick.cellShift());
        CAPTURE(brick.storage().compactFormat());
        // Samples are composited in groups of eight taken samples (FrontToBack::addEight), so
        // leaving out invisible ones regroups the rest: equal to rounding (seen: <= 3e-7), while a
        // visible sample left out would show far above that.
        CHECK(maxAbsDifference(a.image, b.image, b.image.rect()) <= 1e-6f);
        CHECK(a.counters.samples < b.counters.samples);
      }
  }
}

TEST_CASE("a brick is marked all visible exactly when no cell of its map is empty, and renders the same") {
  auto volume = openDataset("turbulence:32");
  const glm::vec2 range = resolveValueRange(RenderSettings{}, volume->info());
  const Brick whole = wholeVolumeBrick(*volume, 1);
  // A transfer function that shows every value, one with a threshold that hides the low ones.
  const TransferFunction everything({{0.0f, {1.0f, 1.0f, 1.0f}}, {1.0f, {1.0f, 0.5f, 0.2f}}},
                                    {{0.0f, 0.05f}, {1.0f, 0.5f}}, "everything");
  const TransferFunction threshold({{0.0f, {0.2f, 0.3f, 0.9f}}, {1.0f, {1.0f, 0.9f, 0.6f}}},
                                   {{0.0f, 0.0f}, {0.7f, 0.0f}, {1.0f, 0.6f}}, "threshold");
  const auto mapOf = [&](const TransferFunction& tf, bool enabled) {  // as RayCaster builds it
    const TransferTable table(tf, RenderSettings{}.stepVoxels);
    const glm::vec2 scaleBias = normalisingScaleBias(range);
    return EmptySpaceMap(whole, table, scaleBias.x, scaleBias.y, enabled);
  };
  const auto emptyCells = [&](const EmptySpaceMap& map) {
    const glm::ivec3 n = map.cellCount();
    long empty = 0;
    for (std::size_t i = 0; i < std::size_t(n.x) * n.y * n.z; ++i) empty += map.reach(i) != 0;
    return empty;
  };
  const EmptySpaceMap dense = mapOf(everything, true), gappy = mapOf(threshold, true),
                      unskipped = mapOf(threshold, false);
  CHECK(emptyCells(dense) == 0);
  CHECK(dense.allVisible());
  CHECK(emptyCells(gappy) > 0);
  CHECK_FALSE(gappy.allVisible());
  CHECK(gappy.anyVisible());
  CHECK(unskipped.allVisible());  // skipping off: nothing is empty
  // The SIMD march skips the map of a dense brick; the scalar march reads it at every sample.
  // Same samples, same bits, with skipping on (the map is built and all visible).
  const MarchFunction simd = selectedMarchFunction();
  if (simd == &marchScalar) {
    MESSAGE("only the scalar march runs here: nothing to compare");
    return;
  }
  for (const float azimuth : {37.0f, 200.0f}) {
    View view;
    view.azimuthDeg = azimuth;
    view.elevationDeg = azimuth > 100.0f ? -30.0f : 20.0f;
    const Camera camera(view, glm::vec3(0.0f), glm::vec3(whole.volumeDims() - 1) * whole.spacing(), 64, 56);
    RenderSettings settings;
    const TransferTable table(everything, settings.stepVoxels);
    RayCaster scalar(whole, table, settings, range), vector(whole, table, settings, range);
    scalar.useMarch(&marchScalar);
    vector.useMarch(simd);
    RenderCounters a, b;
    const Image imageA = scalar.render(camera, a), imageB = vector.render(camera, b);
    CAPTURE(azimuth);
    CHECK(a.samples == b.samples);
    CHECK(a.samples > 10000);
    CHECK(imageA.rect() == imageB.rect());
    CHECK(std::memcmp(imageA.data(), imageB.data(), std::size_t(imageA.rect().area()) * sizeof(Rgba)) == 0);
  }
}

TEST_CASE("a brick with few empty cells in its visible box marches every sample, to the same image") {
  auto volume = openDataset("turbulence:32");
  const glm::vec2 range = resolveValueRange(RenderSettings{}, volume->info());
  const Brick whole = wholeVolumeBrick(*volume, 1);
  const glm::vec2 scaleBias = normalisingScaleBias(range);
  const MarchFunction simd = selectedMarchFunction();
  bool sawFew = false, sawMany = false;
  // Thresholds from none hidden to most hidden: opacity 0 below t.
  for (const float t : {0.0f, 0.1f, 0.2f, 0.25f, 0.3f, 0.35f, 0.4f, 0.5f, 0.6f, 0.7f}) {
    const TransferFunction tf({{0.0f, {0.2f, 0.3f, 0.9f}}, {1.0f, {1.0f, 0.9f, 0.6f}}},
                              {{0.0f, 0.0f}, {t, 0.0f}, {1.0f, 0.6f}}, "threshold");
    const TransferTable table(tf, RenderSettings{}.stepVoxels);
    const EmptySpaceMap map(whole, table, scaleBias.x, scaleBias.y);
    if (!map.anyVisible()) continue;
    // The rule, recomputed from the exact reach: empty cells inside the visible cells' box.
    const glm::ivec3 n = map.cellCount();
    glm::ivec3 lo(n), hi(-1);
    for (int z = 0; z < n.z; ++z)
      for (int y = 0; y < n.y; ++y)
        for (int x = 0; x < n.x; ++x)
          if (map.reach(map.cellIndex(glm::ivec3(x, y, z))) == 0) {
            lo = glm::min(lo, glm::ivec3(x, y, z));
            hi = glm::max(hi, glm::ivec3(x, y, z));
          }
    std::size_t empty = 0, boxCells = 0;
    for (int z = lo.z; z <= hi.z; ++z)
      for (int y = lo.y; y <= hi.y; ++y)
        for (int x = lo.x; x <= hi.x; ++x) {
          empty += map.reach(map.cellIndex(glm::ivec3(x, y, z))) != 0;
          ++boxCells;
        }
    CAPTURE(t);
    CHECK(map.marchesEverySample() == (empty * EmptySpaceMap::kFewEmptyCells <= boxCells));
    if (map.allVisible()) CHECK(map.marchesEverySample());
    // The march's codes hold the reach only where the march skips; the exact reach stays.
    for (std::size_t i = 0; i < std::size_t(n.x) * n.y * n.z; ++i) {
      const int codeReach = map.marchCodes()[i] & EmptySpaceMap::kReachMask;
      CHECK(codeReach == (map.marchesEverySample() ? 0 : std::min<int>(map.reach(i), EmptySpaceMap::kReachMask)));
    }
    if (map.marchesEverySample() && empty > 0) sawFew = true;
    if (!map.marchesEverySample()) sawMany = true;
    if (!map.marchesEverySample() || empty == 0) continue;
    // Marching the empty cells' samples (opacity 0) adds nothing: the image of skipping off, to
    // rounding, with every owned sample taken; scalar and SIMD marches agree bit for bit.
    RenderSettings on, off;
    off.skipEmptySpace = false;
    for (const float azimuth : {37.0f, 200.0f}) {
      View view;
      view.azimuthDeg = azimuth;
      view.elevationDeg = azimuth > 100.0f ? -30.0f : 20.0f;
      const Camera camera(view, glm::vec3(0.0f), glm::vec3(whole.volumeDims() - 1) * whole.spacing(), 64, 56);
      const TransferTable shown(tf, on.stepVoxels);
      RayCaster skipping(whole, shown, on, range), every(whole, shown, off, range), scalar(whole, shown, on, range);
      skipping.useMarch(simd);
      scalar.useMarch(&marchScalar);
      RenderCounters a, b, c;
      const Image withMap = skipping.render(camera, a), without = every.render(camera, b),
                  reference = scalar.render(camera, c);
      CAPTURE(azimuth);
      CHECK(a.samples == b.samples);
      CHECK(a.samples == c.samples);
      CHECK(maxAbsDifference(withMap, without, withMap.rect().unite(without.rect())) <= 1e-5f);
      CHECK(withMap.rect() == reference.rect());
      CHECK(std::memcmp(withMap.data(), reference.data(), std::size_t(withMap.rect().area()) * sizeof(Rgba)) == 0);
    }
  }
  CHECK(sawFew);   // the sweep met a brick with some, but few, empty cells
  CHECK(sawMany);  // and one that skips
}

TEST_CASE("empty-space cells are one voxel up to 2^21 voxels, 2^3 up to 2^27 and 4^3 above, on every brick") {
  CHECK(Brick::cellShiftFor(glm::ivec3(64, 64, 93)) == 0);
  CHECK(Brick::cellShiftFor(glm::ivec3(128)) == 0);  // exactly 2^21
  CHECK(Brick::cellShiftFor(glm::ivec3(128, 128, 129)) == 1);
  CHECK(Brick::cellShiftFor(glm::ivec3(256)) == 1);
  CHECK(Brick::cellShiftFor(glm::ivec3(302)) == 1);
  CHECK(Brick::cellShiftFor(glm::ivec3(512)) == 1);  // exactly 2^27
  CHECK(Brick::cellShiftFor(glm::ivec3(512, 512, 513)) == 2);
  CHECK(Brick::cellShiftFor(glm::ivec3(1024)) == 2);
  // A brick follows its volume's size, not its own, so all of a volume's bricks agree.
  auto volume = openDataset("phantom:40");
  const Brick brick = test::brickOf(*volume, VoxelBox{glm::ivec3(0), glm::ivec3(8)});
  CHECK(brick.cellShift() == 0);
  CHECK(brick.cellCount() == glm::ivec3(8));  // owned [0, 8): samples' floors 0..7, a cell each
  CHECK(test::brickOf(*volume, VoxelBox{glm::ivec3(0), glm::ivec3(8)}, 1).cellCount() == glm::ivec3(4));
  CHECK(test::brickOf(*volume, VoxelBox{glm::ivec3(0), glm::ivec3(8)}, 2).cellCount() == glm::ivec3(2));
}
