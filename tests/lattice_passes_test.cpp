// Passes of one view on shifted sampling lattices (RenderSettings::phaseShift, latticePassShift,
// ImageAverage; kdswap render --passes): the shifts spread evenly, every pass keeps the central
// invariant, and their mean converges on the image of a far finer lattice, rings and grain gone.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "core/image/image_average.h"
#include "core/render/voxel_ray.h"
#include "test_support.h"

using namespace kdswap;

namespace {

//! A sphere's distance field seen through a thin opacity shell: a fixed lattice draws the shell as
//! rings, jitter as grain. The field is linear in each voxel, so a fine lattice sees a smooth shell.
struct ShellScene {
  std::unique_ptr<MemoryVolume> volume = test::makeVolume({40, 40, 40}, [](int x, int y, int z) {
    return std::sqrt(float((x - 20) * (x - 20) + (y - 20) * (y - 20) + (z - 20) * (z - 20))) / 20.0f;
  });
  Brick whole = wholeVolumeBrick(*volume);
  TransferFunction tf{{{0.0f, {1.0f, 0.9f, 0.8f}}, {1.0f, {1.0f, 0.9f, 0.8f}}},
                      {{0.0f, 0.0f}, {0.29f, 0.0f}, {0.3f, 0.6f}, {0.31f, 0.0f}, {1.0f, 0.0f}}};
  View view;
  ShellScene() { view.distance = 2.2f; }
  glm::vec2 range() const { return glm::vec2(volume->info().minValue, volume->info().maxValue); }

  //! The mean of `passes` passes at `step` (passes 0 .. passes - 1).
  Image render(float step, int passes) const {
    ImageAverage average(Rect{0, 0, 64, 64});
    for (int pass = 0; pass < passes; ++pass) {
      RenderSettings settings;
      settings.stepVoxels = step;
      settings.earlyTermination = 1.0f;
      settings.phaseShift = latticePassShift(pass);
      average.add(renderReference(whole, view, 64, 64, tf, settings, range()).image);
    }
    return average.mean();
  }
};

//! Root mean square of the channel differences over the frame.
double rmsDifference(const Image& a, const Image& b) {
  double sum = 0.0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x) {
      const Rgba p = a.sample(x, y), q = b.sample(x, y);
      sum += (p.r - q.r) * (p.r - q.r) + (p.g - q.g) * (p.g - q.g) + (p.b - q.b) * (p.b - q.b) + (p.a - q.a) * (p.a - q.a);
    }
  return std::sqrt(sum / (64.0 * 64.0 * 4.0));
}

}  // namespace

TEST_CASE("lattice pass shifts start at 0 and spread evenly over one step for any number of passes") {
  CHECK(latticePassShift(0) == 0.0f);
  for (int n = 1; n <= 256; ++n) {
    std::vector<float> shifts;
    for (int pass = 0; pass < n; ++pass) {
      const float s = latticePassShift(pass);
      REQUIRE((s >= 0.0f && s < 1.0f));
      shifts.push_back(s);
    }
    std::sort(shifts.begin(), shifts.end());
    float gap = 1.0f - shifts.back() + shifts.front();  // around the circle
    for (int i = 1; i < n; ++i) gap = std::max(gap, shifts[std::size_t(i)] - shifts[std::size_t(i - 1)]);
    CHECK_MESSAGE(gap * float(n) < 2.0f, n << " passes leave a gap of " << gap);  // evenly: 1 / n
  }
  // A shifted phase stays in [0, 1) however close the pixel's offset is to 1.
  for (float offset : {0.0f, 0.5f, 0.99999994f})
    for (int pass = 0; pass < 64; ++pass) {
      const float phase = latticePhase(offset, latticePassShift(pass));
      CHECK((phase >= 0.0f && phase < 1.0f));
    }
}

TEST_CASE("an average of images is their pixels' mean, transparent where an image does not reach") {
  Image a(Rect{0, 0, 4, 3}), b(Rect{2, 1, 4, 4});
  for (int y = 0; y < 3; ++y)
    for (int x = 0; x < 4; ++x) a.at(x, y) = Rgba{0.2f, 0.4f, 0.6f, 0.8f};
  for (int y = 1; y < 5; ++y)
    for (int x = 2; x < 6; ++x) b.at(x, y) = Rgba{0.6f, 0.0f, 0.2f, 0.4f};
  ImageAverage average(Rect{0, 0, 5, 4});
  CHECK(average.mean().at(1, 1).a == 0.0f);
  average.add(a);
  average.add(b);
  CHECK(average.count() == 2);
  const Image mean = average.mean();
  CHECK(mean.rect().w == 5);
  CHECK(mean.rect().h == 4);
  CHECK(mean.at(0, 0).r == doctest::Approx(0.1));   // only a
  CHECK(mean.at(3, 2).r == doctest::Approx(0.4));   // both
  CHECK(mean.at(3, 2).a == doctest::Approx(0.6));
  CHECK(mean.at(4, 3).b == doctest::Approx(0.1));   // only b (clipped to the frame)
  CHECK(mean.at(0, 3).a == 0.0f);                   // neither
}

TEST_CASE("every shifted pass is the single-node image on 3, 8 and 13 nodes") {
  const std::unique_ptr<MemoryVolume> volume = test::makeBlobs({33, 29, 31});
  for (int nodes : {3, 8, 13}) {
    ClusterOptions options;
    options.nodes = nodes;
    VirtualCluster cluster(*volume, options);
    for (int pass : {1, 2, 5}) {
      FrameRequest request;
      request.width = 70, request.height = 53;
      request.view.azimuthDeg = 20.0f + 40.0f * float(pass);
      request.transfer = test::testTransfer();
      request.settings.earlyTermination = 1.0f;  // the exact comparison
      request.settings.phaseShift = latticePassShift(pass);
      const FrameResult frame = cluster.renderFrame(request);
      const float diff = test::diffAgainstReference(*volume, request, frame.image);
      CHECK_MESSAGE(diff <= 1e-5f, nodes << " nodes, pass " << pass << ": max abs diff " << diff);
    }
  }
}

TEST_CASE("the mean of shifted passes converges on a fine lattice's image: rings and grain average out") {
  const ShellScene scene;
  const Image fine = scene.render(1.0f / 16.0f, 1);  // 16 samples a voxel: the shell is smooth
  const Image one = scene.render(1.0f, 1), eight = scene.render(1.0f, 8), thirtyTwo = scene.render(1.0f, 32);
  const double oneToFine = rmsDifference(one, fine), eightToFine = rmsDifference(eight, fine);
  const double oneToMany = rmsDifference(one, thirtyTwo), eightToMany = rmsDifference(eight, thirtyTwo);
  MESSAGE("rms difference from step 1/16: 1 pass " << oneToFine << ", 8 passes " << eightToFine
                                                   << "; from 32 passes: 1 pass " << oneToMany << ", 8 passes "
                                                   << eightToMany);
  CHECK(oneToFine > 0.01);  // the scene does show the coarse lattice's artefacts
  CHECK(eightToFine < 0.35 * oneToFine);
  // What is left is not noise but a bias (compositing a 0.6-opaque shell one voxel apart is not
  // compositing it in sixteenths): the passes converge, and more of them change little.
  CHECK(eightToMany < 0.1 * oneToMany);
}
