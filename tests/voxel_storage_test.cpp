// Compact voxel storage (16-bit value and gradient): its quantisation, bricks built with it (exact
// for integer data, gradients pointing where the float ones do, shipped bricks rebuilt bit for
// bit), the choice by volume size, the central invariant under it for many node counts, views
// and sizes, and images within a grey level of the float format's.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>

#include "core/bench/quantised_source.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/voxel_storage.h"
#include "test_support.h"

using namespace kdswap;

namespace {

//! Angle in radians between two non-zero vectors.
double angleBetween(const glm::vec3& a, const glm::vec3& b) {
  const double c = double(glm::dot(a, b)) / (double(glm::length(a)) * double(glm::length(b)));
  return std::acos(std::clamp(c, -1.0, 1.0));
}

}  // namespace

TEST_CASE("compact storage keeps integer data exactly and float data to half a level") {
  SUBCASE("8-bit data: every value on its own level, back to within float rounding") {
    const VoxelStorage s = VoxelStorage::compact(0.0f, 255.0f, glm::vec3(1.0f));
    for (int v = 0; v <= 255; ++v) {
      CHECK(int(s.quantiseValue(float(v))) == v * 257 - 32768);  // 255 divides 65535: no rounding
      CHECK(s.value(s.quantiseValue(float(v))) == doctest::Approx(float(v)).epsilon(1e-6));
    }
  }
  SUBCASE("16-bit data spanning the type: every value on its own level") {
    const VoxelStorage s = VoxelStorage::compact(0.0f, 65535.0f, glm::vec3(1.0f));
    for (int v = 0; v <= 65535; v += 7) CHECK(int(s.quantiseValue(float(v))) == v - 32768);
  }
  SUBCASE("data typed uint8 but scaled to [0, 1] (quantised for a benchmark) keep their 256 levels") {
    // The type name says nothing of the values: kdswap bench --quantise 8 keeps the float range.
    VolumeInfo info;
    info.dims = {8, 8, 8};
    info.type = "uint8";
    info.minValue = 0.0f, info.maxValue = 1.0f;
    const VoxelStorage s = VoxelStorage::forVolume(info, VoxelChoice::Compact);
    for (int k = 0; k <= 255; ++k) {
      const float v = float(k) / 255.0f;
      CHECK(std::fabs(s.value(s.quantiseValue(v)) - v) <= 0.5f * s.valueStep * 1.01f);
    }
  }
  SUBCASE("float data: 65536 levels over the range, within half a level") {
    const VoxelStorage s = VoxelStorage::compact(-2.5f, 7.25f, glm::vec3(1.0f));
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(-2.5f, 7.25f);
    float worst = 0.0f;
    for (int i = 0; i < 100000; ++i) {
      const float v = u(rng);
      worst = std::max(worst, std::fabs(s.value(s.quantiseValue(v)) - v));
    }
    CHECK(worst <= 0.5f * s.valueStep * 1.01f);
    CHECK(s.value(s.quantiseValue(-2.5f)) == doctest::Approx(-2.5f).epsilon(1e-6));
    CHECK(s.value(s.quantiseValue(7.25f)) == doctest::Approx(7.25f).epsilon(1e-6));
  }
  SUBCASE("out of range and NaN are clamped, never wrapped") {
    const VoxelStorage s = VoxelStorage::compact(0.0f, 1.0f, glm::vec3(1.0f));
    CHECK(s.quantiseValue(5.0f) == 32767);
    CHECK(s.quantiseValue(-5.0f) == -32768);
    CHECK(s.quantiseValue(std::nanf("")) == -32768);
    CHECK(s.quantiseGradient(1e30f) == 32767);
    CHECK(s.quantiseGradient(-1e30f) == -32767);
    CHECK(s.quantiseGradient(std::nanf("")) == 0);
  }
  SUBCASE("the steepest gradient the range allows fits 16 bits, at the smallest spacing") {
    const glm::vec3 spacing(0.5f, 2.0f, 3.2f);
    const VoxelStorage s = VoxelStorage::compact(-10.0f, 30.0f, spacing);
    const float steepest = 40.0f / 0.5f;  // one-sided difference across the whole range
    CHECK(steepest * s.gradientScale <= 32767.0f);  // stored without clamping
    CHECK(std::abs(int(s.quantiseGradient(-steepest))) > 32000);  // and using the levels
  }
  SUBCASE("one value everywhere") {
    const VoxelStorage s = VoxelStorage::compact(3.0f, 3.0f, glm::vec3(1.0f));
    CHECK(s.value(s.quantiseValue(3.0f)) == 3.0f);
  }
}

TEST_CASE("the voxel format follows the volume's size unless the user chooses") {
  VolumeInfo info;
  info.dims = {256, 256, 128};  // 2^23 voxels: float
  CHECK_FALSE(VoxelStorage::forVolume(info).compactFormat());
  info.dims = {256, 256, 129};
  CHECK(VoxelStorage::forVolume(info).compactFormat());
  CHECK_FALSE(VoxelStorage::forVolume(info, VoxelChoice::Float).compactFormat());
  info.dims = {8, 8, 8};
  CHECK(VoxelStorage::forVolume(info, VoxelChoice::Compact).compactFormat());
  CHECK(parseVoxelChoice("compact") == VoxelChoice::Compact);
  CHECK(parseVoxelChoice("float") == VoxelChoice::Float);
  CHECK(parseVoxelChoice("auto") == VoxelChoice::Auto);
  CHECK_THROWS_WITH_AS(parseVoxelChoice("half"), "--voxels \"half\": expected auto, float or compact", Error);
}

TEST_CASE("a compact brick: half the memory, the float brick's values and gradient directions") {
  auto volume = test::makeBlobs({30, 27, 33}, glm::vec3(1.0f, 1.3f, 0.7f));
  const Brick whole = wholeVolumeBrick(*volume, Brick::kCellShiftByVolume, VoxelChoice::Float);
  const Brick compact = wholeVolumeBrick(*volume, Brick::kCellShiftByVolume, VoxelChoice::Compact);
  REQUIRE(compact.storage().compactFormat());
  CHECK(compact.compactData() != nullptr);
  CHECK(compact.voxelData() == nullptr);
  const std::uint64_t voxels = std::uint64_t(whole.stored().count());
  const auto cells = [](const Brick& b) { return b.cellRanges().bytes() + b.uniformCells().size(); };
  CHECK(whole.bytes() - cells(whole) == voxels * 16);
  CHECK(compact.bytes() - cells(compact) == voxels * 8);
  const VoxelStorage& s = compact.storage();
  long compared = 0;
  double worstAngle = 0.0;
  for (int z = 0; z < 33; ++z)
    for (int y = 0; y < 27; ++y)
      for (int x = 0; x < 30; ++x) {
        CHECK(std::fabs(compact.valueAt(x, y, z) - whole.valueAt(x, y, z)) <= 0.5f * s.valueStep * 1.01f);
        const glm::vec3 g = whole.voxel(x, y, z).gradient;
        const CompactVoxel& c = compact.compactVoxel(x, y, z);
        const glm::vec3 q(c.gradient[0], c.gradient[1], c.gradient[2]);
        // Directions agree wherever the gradient is more than a few levels long.
        if (glm::length(g) * s.gradientScale > 200.0f) {
          worstAngle = std::max(worstAngle, angleBetween(g, q));
          ++compared;
        }
      }
  CHECK(compared > 10000);
  CHECK(worstAngle < 0.02);  // radians: ~1 degree at worst, where the float gradient itself is short
}

TEST_CASE("a compact brick rebuilt from its shipped values, or cut from the volume, stores the same bits") {
  auto volume = test::makeBlobs({26, 31, 24});
  const VolumeInfo& info = volume->info();
  const VoxelStorage storage = VoxelStorage::forVolume(info, VoxelChoice::Compact);
  const Brick whole = wholeVolumeBrick(*volume, Brick::kCellShiftByVolume, VoxelChoice::Compact);
  const VoxelBox owned{glm::ivec3(5, 0, 9), glm::ivec3(19, 17, 23)};
  const VoxelBox stored = Brick::storedBoxFor(owned, info.dims);
  std::vector<float> raw(std::size_t(stored.count()));
  volume->read(stored, raw.data());
  const Brick brick(owned, info.dims, info.spacing, raw, Brick::Shipping::Yes, Brick::kCellShiftByVolume, storage);
  const Brick rebuilt(owned, info.dims, info.spacing, brick.storedValues(), Brick::Shipping::Yes,
                      Brick::kCellShiftByVolume, storage);
  CHECK(std::memcmp(brick.compactData(), rebuilt.compactData(),
                    std::size_t(brick.stored().count()) * sizeof(CompactVoxel)) == 0);
  long differing = 0;
  for (int z = brick.stored().lo.z; z < brick.stored().hi.z; ++z)
    for (int y = brick.stored().lo.y; y < brick.stored().hi.y; ++y)
      for (int x = brick.stored().lo.x; x < brick.stored().hi.x; ++x)
        differing += std::memcmp(&brick.compactVoxel(x, y, z), &whole.compactVoxel(x, y, z), sizeof(CompactVoxel)) != 0;
  CHECK(differing == 0);  // values and gradients equal the whole volume's, next to every cut too
}

TEST_CASE("compact interpolation reproduces a linear field, and agrees with the float interpolation") {
  // f = 3x - 2y + 5z + 40: trilinear interpolation is exact for it.
  auto volume = test::makeVolume({12, 10, 9}, [](int x, int y, int z) { return float(3 * x - 2 * y + 5 * z + 40); });
  const Brick whole = wholeVolumeBrick(*volume, Brick::kCellShiftByVolume, VoxelChoice::Float);
  const VolumeInfo& info = volume->info();
  const VoxelStorage storage = VoxelStorage::compact(info.minValue, info.maxValue, info.spacing);
  const VoxelBox owned{glm::ivec3(0), info.dims - 1};
  std::vector<float> raw(std::size_t(info.voxelCount()));
  volume->read(VoxelBox{glm::ivec3(0), info.dims}, raw.data());
  const Brick compact(owned, info.dims, info.spacing, raw, Brick::Shipping::No, Brick::kCellShiftByVolume, storage);
  const VoxelAddressing at(compact);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> ux(0.0f, 10.999f), uy(0.0f, 8.999f), uz(0.0f, 7.999f);
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 p(ux(rng), uy(rng), uz(rng));
    const glm::ivec3 floor(int(p.x), int(p.y), int(p.z));
    const TrilinearCell::Lanes c = interpolateCompact(at, p, floor);
    const float value = c[0] * storage.valueStep + storage.valueOrigin;
    // Corners within half a level each, so the blend too; a level is 1/65535 of the range.
    CHECK(std::fabs(value - (3.0f * p.x - 2.0f * p.y + 5.0f * p.z + 40.0f)) <= storage.valueStep);
    CHECK(std::fabs(value - TrilinearCell(whole, p).value()) <= storage.valueStep);
    // Inside (away from the one-sided faces) the gradient is (3, -2, 5) everywhere.
    if (p.x >= 1.0f && p.x < 10.0f && p.y >= 1.0f && p.y < 8.0f && p.z >= 1.0f && p.z < 7.0f)
      CHECK(angleBetween(glm::vec3(c[1], c[2], c[3]), glm::vec3(3.0f, -2.0f, 5.0f)) < 1e-3);
  }
}

TEST_CASE("under compact storage the distributed image equals the single-node image") {
  auto volume = test::makeBlobs({35, 30, 33}, glm::vec3(1.0f, 1.1f, 0.9f));
  const TransferFunction tf = test::testTransfer();
  const Brick whole = wholeVolumeBrick(*volume, Brick::kCellShiftByVolume, VoxelChoice::Compact);
  const glm::vec2 range(volume->info().minValue, volume->info().maxValue);
  std::mt19937 rng(23);
  std::uniform_real_distribution<float> az(-180.0f, 180.0f), el(-70.0f, 70.0f);
  const std::pair<int, int> sizes[] = {{64, 48}, {37, 53}, {1, 1}};
  for (const int nodes : {2, 3, 8, 16, 64}) {
    ClusterOptions options;
    options.nodes = nodes;
    options.voxels = VoxelChoice::Compact;
    options.bricksPerNode = nodes == 8 ? 4 : 1;  // shipped sub-bricks keep the storage too
    VirtualCluster cluster(*volume, options);
    for (int v = 0; v < 3; ++v) {
      View view;
      view.azimuthDeg = az(rng), view.elevationDeg = el(rng);
      view.projection = v == 2 ? Projection::Orthographic : Projection::Perspective;
      for (auto [w, h] : sizes) {
        FrameRequest request;
        request.view = view, request.width = w, request.height = h, request.transfer = tf;
        request.settings.earlyTermination = 1.0f;
        const FrameResult frame = cluster.renderFrame(request);
        const ReferenceResult ref = renderReference(whole, view, w, h, tf, request.settings, range);
        CAPTURE(nodes);
        CAPTURE(view.azimuthDeg);
        CAPTURE(w);
        CHECK(maxAbsDifference(frame.image, ref.image, ref.image.rect()) <= 1e-5f);
      }
    }
  }
}

namespace {

struct StorageComparison {
  long covered = 0;  //!< pixels with alpha > 0.01 in the float storage's image
  long far = 0;      //!< pixels whose channels differ by more than a grey level
  float largest = 0.0f;
  std::uint64_t floatSamples = 0, compactSamples = 0;
};

//! The volume rendered from float and from compact bricks, same view, settings and transfer.
StorageComparison compareStorage(const VolumeSource& volume, bool shading) {
  const glm::vec2 range(volume.info().minValue, volume.info().maxValue);
  const Brick f = wholeVolumeBrick(volume, Brick::kCellShiftByVolume, VoxelChoice::Float);
  const Brick c = wholeVolumeBrick(volume, Brick::kCellShiftByVolume, VoxelChoice::Compact);
  View view;
  view.azimuthDeg = 30.0f, view.elevationDeg = 20.0f;
  view.distance = 2.5f;  // close: the volume fills most of the 96 x 96 frame
  RenderSettings settings;
  settings.shading = shading;
  const TransferFunction tf = test::testTransfer();
  const ReferenceResult fromFloat = renderReference(f, view, 96, 96, tf, settings, range);
  const ReferenceResult fromCompact = renderReference(c, view, 96, 96, tf, settings, range);
  const Image &a = fromFloat.image, &b = fromCompact.image;
  StorageComparison out;
  for (int y = 0; y < 96; ++y)
    for (int x = 0; x < 96; ++x) {
      const Rgba p = a.at(x, y), q = b.at(x, y);
      out.covered += p.a > 0.01f;
      out.far += std::max({std::fabs(p.r - q.r), std::fabs(p.g - q.g), std::fabs(p.b - q.b), std::fabs(p.a - q.a)}) >
                 1.0f / 255.0f;
    }
  out.largest = maxAbsDifference(a, b, a.rect());
  out.floatSamples = fromFloat.counters.samples, out.compactSamples = fromCompact.counters.samples;
  return out;
}

std::unique_ptr<VolumeSource> storageTestVolume(const std::string& data) {
  // The quantised phantom is what bench --targets renders: typed uint8, its values still in [0, 1].
  if (data == "phantom:48 quantised to 8 bits") return std::make_unique<QuantisedSource>(openDataset("phantom:48"), 8);
  return openDataset(data);
}

}  // namespace

TEST_CASE("compact and float storage give images within a grey level of each other") {
  for (const char* data : {"turbulence:48", "vessels:48", "phantom:48", "phantom:48 quantised to 8 bits"}) {
    const std::unique_ptr<VolumeSource> volume = storageTestVolume(data);
    CAPTURE(std::string(data));
    // Values and opacity: 65536 levels keep every pixel within a grey level, or nearly every one.
    const StorageComparison unshaded = compareStorage(*volume, false);
    CHECK(unshaded.covered > 1000);              // the images show something
    CHECK(unshaded.far * 200 <= unshaded.covered);  // at most 0.5% of the pixels differ by more than a grey level
    // The same work: a sample count far off would mean the values changed.
    CHECK(double(unshaded.compactSamples) == doctest::Approx(double(unshaded.floatSamples)).epsilon(0.01));

    // Shaded: the 16-bit gradients move a direction by at most ~1/32767 of the largest gradient the
    // range allows, which shows only where the gradient itself nearly vanishes: on the crest of a
    // thin smooth shell, as the phantom's skull is at 48^3 (under a voxel thick, smoothed over three).
    // There shading may differ by a few grey levels (measured: 8.7% of the pixels by more than one,
    // none by more than seven with white-noise ray phases; 8.04 with blue-noise phases, whose
    // samples land on the crest elsewhere); elsewhere, as for the other volumes, within one.
    const StorageComparison shaded = compareStorage(*volume, true);
    CHECK(shaded.covered > 1000);
    CHECK(double(shaded.compactSamples) == doctest::Approx(double(shaded.floatSamples)).epsilon(0.01));
    if (std::string(data) == "phantom:48") {
      MESSAGE("largest difference " << shaded.largest * 255.0f << " grey levels, " << shaded.far << " of "
                                    << shaded.covered << " pixels by more than one");
      CHECK(shaded.largest < 9.0f / 255.0f);
      CHECK(shaded.far * 10 <= shaded.covered);  // at most 10% differ by more than a grey level
    } else {
      CHECK(shaded.far * 200 <= shaded.covered);
      CHECK(shaded.largest < 0.05f);
    }
  }
}
