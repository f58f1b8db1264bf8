// The SIMD ray march against the scalar reference: for every pixel of many views, bricks and
// settings, the same colour bits and the same number of samples, ray by ray (castRay) and in the
// batches render() marches. (The image-level invariants are
// checked with whichever march the machine selects; this pins the two marches to each other.)
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "core/render/ray_caster.h"
#include "core/render/ray_march.h"
#include "core/render/reference_render.h"
#include "core/transfer/presets.h"
#include "core/volume/datasets/dataset.h"
#include "test_support.h"

using namespace kdswap;

namespace {

bool sameBits(const Rgba& a, const Rgba& b) { return std::memcmp(&a, &b, sizeof a) == 0; }

struct MarchComparison {
  long pixels = 0, differingPixels = 0, differingCounts = 0;
  long batchDiffering = 0;  //!< pixels where render()'s batched march differs from castRay
  bool renderedSamplesDiffer = false;
  std::uint64_t samples = 0;
};

//! Casts every pixel of a w x h frame through `brick` with both marches.
MarchComparison compareMarches(const Brick& brick, const View& view, const TransferFunction& tf,
                               const RenderSettings& settings, glm::vec2 range, MarchFunction simd) {
  const Camera camera(view, glm::vec3(0.0f), glm::vec3(brick.volumeDims() - 1) * brick.spacing(), 48, 40);
  const TransferTable table(tf, settings.stepVoxels);
  RayCaster scalar(brick, table, settings, range), vector(brick, table, settings, range);
  scalar.useMarch(&marchScalar);
  vector.useMarch(simd);
  MarchComparison result;
  // Whole frames go through render(), which marches a tile's rays in batches.
  RenderCounters renderedA, renderedB;
  const Image imageA = scalar.render(camera, renderedA), imageB = vector.render(camera, renderedB);
  result.renderedSamplesDiffer = renderedA.samples != renderedB.samples;
  std::uint64_t castSamples = 0;
  for (int y = 0; y < 40; ++y)
    for (int x = 0; x < 48; ++x) {
      RenderCounters a, b;
      const Ray ray = camera.ray(x, y);
      const Rgba ca = scalar.castRay(ray, a), cb = vector.castRay(ray, b);
      ++result.pixels;
      result.samples += a.samples;
      castSamples += a.samples;
      if (!sameBits(ca, cb)) ++result.differingPixels;
      if (a.samples != b.samples) ++result.differingCounts;
      const Rgba fromA = imageA.sample(x, y);
      const Rgba fromB = imageB.sample(x, y);
      if (!sameBits(fromA, ca) || !sameBits(fromB, ca)) ++result.batchDiffering;
    }
  if (castSamples != renderedA.samples) result.renderedSamplesDiffer = true;
  return result;
}

//! Colours and sample counts of `simd` against the scalar march over data sets, bricks, views and settings.
void checkAgainstScalar(MarchFunction simd) {
  struct Case {
    std::string data, transfer;
  };
  const Case cases[] = {{"phantom:40", "phantom"}, {"vessels:40", "vessels"}, {"turbulence:32", "turbulence"}};
  std::uint64_t totalSamples = 0;
  int bricksWithUniformCells = 0;
  for (const Case& c : cases) {
    auto volume = openDataset(c.data);
    const glm::ivec3 dims = volume->info().dims;
    const TransferFunction tf = loadTransferFunction(c.transfer);
    const glm::vec2 range = resolveValueRange(RenderSettings{}, volume->info());
    // The whole volume and a brick cut out of it (offset voxel origin, cells and ghost layers).
    // All three sizes of empty-space cells (one voxel, 2^3, 4^3: Brick::cellShiftFor), and both
    // voxel formats (large volumes store compact voxels: VoxelStorage::forVolume).
    const VoxelBox cut{glm::ivec3(3, 9, 0), glm::ivec3(dims.x - 1, 30, 21)};
    const VoxelChoice compact = VoxelChoice::Compact;
    const Brick bricks[] = {wholeVolumeBrick(*volume, 0),          test::brickOf(*volume, cut, 0),
                            wholeVolumeBrick(*volume, 1),          test::brickOf(*volume, cut, 1),
                            wholeVolumeBrick(*volume, 2),          test::brickOf(*volume, cut, 2),
                            wholeVolumeBrick(*volume, 1, compact), test::brickOf(*volume, cut, 2, compact),
                            wholeVolumeBrick(*volume, 0, compact)};
    for (const Brick& brick : bricks)
      for (const float azimuth : {0.0f, 37.0f, 90.0f, 211.0f})
        for (int variant = 0; variant < 4; ++variant) {
          View view;
          view.azimuthDeg = azimuth;
          view.elevationDeg = azimuth > 100.0f ? -40.0f : 20.0f;
          view.projection = azimuth == 90.0f ? Projection::Orthographic : Projection::Perspective;
          RenderSettings settings;
          settings.stepVoxels = azimuth == 37.0f ? 1.0f : 0.5f;
          settings.shading = variant != 1;
          settings.earlyTermination = variant == 2 ? 1.0f : 0.95f;  // 1: every ray runs to its end
          settings.skipEmptySpace = variant != 3;
          settings.jitter = variant != 0;
          const MarchComparison r = compareMarches(brick, view, tf, settings, range, simd);
          const TransferTable table(tf, settings.stepVoxels);
          const glm::vec2 map = normalisingScaleBias(range);
          bricksWithUniformCells += EmptySpaceMap(brick, table, map.x, map.y).anyUniform() ? 1 : 0;
          CAPTURE(c.data);
          CAPTURE(azimuth);
          CAPTURE(variant);
          CAPTURE(brick.owned().lo.x);
          CAPTURE(brick.cellShift());
          CAPTURE(brick.storage().compactFormat());
          CHECK(r.differingPixels == 0);
          CHECK(r.differingCounts == 0);
          CHECK(r.batchDiffering == 0);
          CHECK_FALSE(r.renderedSamplesDiffer);
          totalSamples += r.samples;
        }
  }
  CHECK(totalSamples > 1000000);  // the comparison saw real work, not empty frames
  CHECK(bricksWithUniformCells > 0);  // and samples that take a uniform cell's record (the phantom's)
}

}  // namespace

TEST_CASE("the AVX2 ray march gives the scalar march's colours bit for bit, with the same samples") {
  // Every build of it: for AVX2 alone, for CPUs with AVX-512 VL, and that with 512-bit registers
  // (where this CPU has them).
  std::vector<MarchFunction> simds;
  for (const MarchFunction m : {avx2MarchFunction(), avx512vlMarchFunction(), avx512MarchFunction()})
    if (m) simds.push_back(m);
  if (simds.empty()) {
    MESSAGE("this CPU or build has no AVX2: only the scalar march exists, nothing to compare");
    return;
  }
  for (const MarchFunction simd : simds) {
    CAPTURE(marchName(simd));
    checkAgainstScalar(simd);
  }
}

namespace {
// Stand-ins for the builds: chooseMarch only compares and returns the pointers. Different bodies,
// so no linker folds them into one address.
void fakeAvx2(const MarchContext&, const RaySegment*, std::size_t, Rgba*, std::uint64_t& s) { s += 2; }
void fakeAvx512vl(const MarchContext&, const RaySegment*, std::size_t, Rgba*, std::uint64_t& s) { s += 3; }
void fakeAvx512(const MarchContext&, const RaySegment*, std::size_t, Rgba*, std::uint64_t& s) { s += 5; }
}  // namespace

TEST_CASE("the march is chosen by the CPU's vector units, and KDSWAP_SIMD narrows or widens it") {
  const MarchBuilds amd{&fakeAvx2, &fakeAvx512vl, &fakeAvx512, true};     // 512-bit at full speed
  const MarchBuilds intel{&fakeAvx2, &fakeAvx512vl, &fakeAvx512, false};  // AVX-512, narrower is faster
  const MarchBuilds avx2Only{&fakeAvx2, nullptr, nullptr, false};
  const MarchBuilds none{};
  struct Case {
    const char* cpu;
    const MarchBuilds& builds;
    const char* request;
    MarchFunction expected;
  };
  const Case cases[] = {
      // No request: the fastest build for the CPU.
      {"AMD", amd, "", &fakeAvx512},
      {"Intel", intel, "", &fakeAvx512vl},
      {"AVX2 only", avx2Only, "", &fakeAvx2},
      {"no AVX2", none, "", &marchScalar},
      // A request: that build where the CPU has it ...
      {"AMD", amd, "avx512vl", &fakeAvx512vl},
      {"AMD", amd, "avx2", &fakeAvx2},
      {"Intel", intel, "avx512", &fakeAvx512},
      {"Intel", intel, "scalar", &marchScalar},
      // ... the next narrower one where it does not; unknown text is no request.
      {"AVX2 only", avx2Only, "avx512", &fakeAvx2},
      {"AVX2 only", avx2Only, "avx512vl", &fakeAvx2},
      {"no AVX2", none, "avx2", &marchScalar},
      {"AMD", amd, "avx-512", &fakeAvx512},
      {"Intel", intel, "AVX2", &fakeAvx512vl},
  };
  for (const Case& c : cases) {
    CAPTURE(c.cpu);
    CAPTURE(c.request);
    CHECK((chooseMarch(c.builds, c.request) == c.expected));
  }
  // The real builds carry their names into reports.
  CHECK(std::string(marchName(&marchScalar)) == "scalar");
  if (avx512MarchFunction()) {
    CHECK(std::string(marchName(avx512MarchFunction())) == "avx512");
    CHECK(std::string(marchName(avx512vlMarchFunction())) == "avx2+avx512vl");
  }
  if (avx2MarchFunction()) CHECK(std::string(marchName(avx2MarchFunction())) == "avx2");
}

TEST_CASE("compositing eight at a time equals sample-by-sample front-to-back over, and stops at the same sample") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int stoppedGroups = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 1 + trial % FrontToBack::kGroup;
    ShadedSample s[FrontToBack::kGroup] = {};
    for (int j = 0; j < n; ++j) {
      // A third of the samples invisible (opacity 0), the rest up to 0.35.
      const float a = unit(rng) < 0.33f ? 0.0f : 0.35f * unit(rng);
      s[j] = ShadedSample{unit(rng), unit(rng), unit(rng), a};
    }
    const float start = 0.2f + 0.8f * unit(rng), stop = trial % 3 == 0 ? 0.0f : 0.25f;
    // Reference: "over" one sample at a time, in double precision.
    double r = 0, g = 0, b = 0, t = start;
    int expectedTaken = n;
    bool expectedDone = false;
    for (int j = 0; j < n; ++j) {
      if (s[j].a <= 0.0f) continue;
      r += t * s[j].a * s[j].r, g += t * s[j].a * s[j].g, b += t * s[j].a * s[j].b;
      t *= 1.0 - s[j].a;
      if (t <= stop) {
        expectedTaken = j + 1, expectedDone = true;
        break;
      }
    }
    if (std::fabs(t - stop) < 1e-4) continue;  // too close to the threshold for float and double to agree
    FrontToBack eight;
    eight.transmittance = start;
    int taken = -1;
    const bool done = eight.addEight(s, n, stop, taken);
    CAPTURE(trial);
    CHECK(done == expectedDone);
    CHECK(taken == expectedTaken);
    const Rgba colour = eight.rgba();
    CHECK(std::fabs(colour.r - r) < 1e-6);
    CHECK(std::fabs(colour.g - g) < 1e-6);
    CHECK(std::fabs(colour.b - b) < 1e-6);
    CHECK(std::fabs(eight.transmittance - t) < 1e-6);
    stoppedGroups += done;
  }
  CHECK(stoppedGroups > 100);  // the threshold was reached often enough to test the stop
}
