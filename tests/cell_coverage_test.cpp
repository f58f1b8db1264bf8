// CellCoverage: the pixels a brick's rays can reach its visible cells through. A pixel it leaves
// out must be one whose ray takes no sample in the brick (checked ray by ray with castRay, which
// uses no coverage), for bricks cut anywhere, both cell sizes, grouped cells, both projections
// and near views; and it must leave some pixels out, or it would be checking nothing.
#include <doctest/doctest.h>

#include <random>

#include "core/render/cell_coverage.h"
#include "core/render/ray_caster.h"
#include "test_support.h"

using namespace kdswap;

namespace {

struct Scene {
  std::unique_ptr<MemoryVolume> volume = test::makeBlobs({40, 36, 44}, glm::vec3(1.0f, 1.1f, 0.9f));
  TransferFunction tf = test::testTransfer();
  glm::vec2 range() const { return glm::vec2(volume->info().minValue, volume->info().maxValue); }
  Camera camera(const View& view, int w, int h) const {
    return Camera(view, glm::vec3(0.0f), glm::vec3(volume->info().dims - 1) * volume->info().spacing, w, h);
  }
};

const Scene& scene() {
  static const Scene s;
  return s;
}

//! Pixels of the caster's rectangle the coverage leaves out; fails for any whose ray takes a sample.
std::int64_t checkLeftOut(const RayCaster& caster, const Camera& camera) {
  const CellCoverage coverage = caster.coverage(camera);
  const Rect rect = caster.screenRect(camera);
  std::int64_t leftOut = 0;
  for (int y = rect.y; y < rect.bottom(); ++y)
    for (int x = rect.x; x < rect.right(); ++x) {
      if (coverage.eight(x, y) & 1) continue;
      ++leftOut;
      RenderCounters counters;
      const Rgba c = caster.castRay(camera.ray(x, y), counters);
      CHECK_MESSAGE(counters.samples == 0, "pixel " << x << "," << y << " left out, but its ray takes samples");
      CHECK(c.a == 0.0f);
    }
  return leftOut;
}

}  // namespace

TEST_CASE("cell coverage: a pixel it leaves out has a ray that takes no sample in the brick") {
  const Scene& s = scene();
  const glm::ivec3 dims = s.volume->info().dims;
  std::mt19937 rng(71);
  const VoxelBox boxes[] = {VoxelBox{{0, 0, 0}, dims - 1}, VoxelBox{{0, 0, 0}, {20, 17, 22}},
                            VoxelBox{{20, 9, 5}, {39, 35, 30}}, VoxelBox{{7, 18, 22}, {31, 35, 43}}};
  RenderSettings settings;
  settings.earlyTermination = 0.95f;
  const TransferTable table(s.tf, settings.stepVoxels);
  std::int64_t leftOut = 0, pixels = 0;
  for (const VoxelBox& owned : boxes)
    for (int cellShift : {1, 2}) {
      const Brick brick = test::brickOf(*s.volume, owned, cellShift);
      const RayCaster caster(brick, table, settings, s.range());
      for (const View& view : test::randomViews(rng, 3)) {
        const Camera camera = s.camera(view, 61, 53);
        CAPTURE(cellShift);
        CAPTURE(view.azimuthDeg);
        CAPTURE(view.elevationDeg);
        leftOut += checkLeftOut(caster, camera);
        pixels += caster.screenRect(camera).area();
      }
    }
  // The blobs fill a sphere inside the box: the rectangles' corners see only empty cells.
  CHECK(leftOut > pixels / 20);
}

TEST_CASE("cell coverage: bricks with more cells a side than it keeps groups are covered by groups, as safely") {
  const Scene& s = scene();
  // Two-voxel cells over the whole volume: 18-22 cells a side, grouped by two.
  const Brick brick = wholeVolumeBrick(*s.volume, 1);
  REQUIRE(brick.cellCount().x > CellGroups::kMaxPerAxis);
  RenderSettings settings;
  const TransferTable table(s.tf, settings.stepVoxels);
  const RayCaster caster(brick, table, settings, s.range());
  std::mt19937 rng(72);
  std::int64_t leftOut = 0;
  for (const View& view : test::randomViews(rng, 4)) leftOut += checkLeftOut(caster, s.camera(view, 57, 49));
  CHECK(leftOut > 0);
}

TEST_CASE("cell coverage: an eye inside the volume, or a brick all visible, covers every pixel") {
  const Scene& s = scene();
  RenderSettings settings;
  const TransferTable table(s.tf, settings.stepVoxels);
  const Brick whole = wholeVolumeBrick(*s.volume);
  const RayCaster caster(whole, table, settings, s.range());
  View inside;
  inside.distance = 0.2f;  // bounding-sphere radii from the centre: inside the box
  for (Projection p : {Projection::Perspective, Projection::Orthographic}) {
    inside.projection = p;
    const Camera camera = s.camera(inside, 33, 31);
    if (p == Projection::Perspective) CHECK(caster.coverage(camera).coversAll());
    checkLeftOut(caster, camera);
  }
  // No visible cell: nothing is covered, whatever rectangle it is asked for.
  const auto clear = test::makeVolume({12, 10, 9}, [](int, int, int) { return 0.0f; });
  const Brick empty = wholeVolumeBrick(*clear);
  const EmptySpaceMap none(empty, table, 1.0f, 0.0f);
  REQUIRE(!none.anyVisible());
  const CellCoverage nothing(empty, none, s.camera(View{}, 20, 20), Rect{0, 0, 20, 20});
  CHECK(nothing.coveredPixels() == 0);
  for (int y = -1; y <= 20; ++y) CHECK(nothing.eight(-3, y) == 0);
  // Every cell visible: nothing to leave out, so nothing is built.
  const auto flat = test::makeVolume({20, 18, 16}, [](int x, int, int) { return 0.5f + 0.01f * float(x); });
  const Brick solid = wholeVolumeBrick(*flat);
  const RayCaster solidCaster(solid, table, settings, glm::vec2(0.0f, 1.0f));
  View view;
  CHECK(solidCaster.coverage(Camera(view, glm::vec3(0.0f), glm::vec3(19.0f, 17.0f, 15.0f), 40, 40)).coversAll());
}

TEST_CASE("cell coverage: eight pixels at once read the same bits as one at a time, at every offset") {
  const Scene& s = scene();
  RenderSettings settings;
  const TransferTable table(s.tf, settings.stepVoxels);
  const Brick brick = test::brickOf(*s.volume, VoxelBox{{0, 0, 0}, {20, 17, 22}}, 1);
  const RayCaster caster(brick, table, settings, s.range());
  View view;
  view.azimuthDeg = 30.0f, view.elevationDeg = 20.0f;
  // Wide enough that rows span several 64-bit words.
  const Camera camera = s.camera(view, 640, 420);
  const CellCoverage coverage = caster.coverage(camera);
  const Rect rect = caster.screenRect(camera);
  REQUIRE(rect.w > 130);
  REQUIRE(!coverage.coversAll());
  std::int64_t covered = 0;
  for (int y = rect.y - 1; y <= rect.bottom(); ++y)
    for (int x = rect.x - 9; x <= rect.right() + 1; ++x) {
      const int eight = coverage.eight(x, y);
      for (int j = 1; j < 8; ++j) CHECK(((eight >> j) & 1) == (coverage.eight(x + j, y) & 1));
      if (!rect.contains(x, y)) CHECK((eight & 1) == 0);
      covered += rect.contains(x, y) && (eight & 1);
    }
  CHECK(covered == coverage.coveredPixels());
  CHECK(covered > 0);
  CHECK(covered < rect.area());
}
