// Against the analytic answer: a cube of constant scalar with opacity a per voxel, seen face-on
// orthographically, has alpha 1 - (1 - a)^(L / 1 voxel) for path length L.
#include <doctest/doctest.h>

#include <cmath>

#include "core/render/reference_render.h"
#include "test_support.h"

using namespace kdswap;

TEST_CASE("a constant cube seen face-on has alpha 1 - (1 - a)^L for several opacities and steps") {
  const int n = 64;
  auto cube = test::makeVolume({n, n, n}, [](int, int, int) { return 0.5f; });
  const Brick whole = wholeVolumeBrick(*cube);
  const float length = float(n - 1);  // the data domain runs between the first and last voxel centres
  const float radius = 0.5f * std::sqrt(3.0f) * length;
  for (float a : {0.005f, 0.02f, 0.05f, 0.2f}) {
    for (float step : {0.25f, 0.5f, 0.75f, 1.0f}) {
      const TransferFunction tf({{0.0f, glm::vec3(1.0f)}, {1.0f, glm::vec3(1.0f)}}, {{0.0f, a}, {1.0f, a}});
      RenderSettings settings;
      settings.stepVoxels = step;
      settings.shading = false;
      settings.jitter = false;  // the entry distance below is chosen for the unjittered lattice
      settings.earlyTermination = 1.0f;
      View view;
      view.projection = Projection::Orthographic;
      view.azimuthDeg = 0.0f;  // looking along +y, straight at the y = 0 face
      view.elevationDeg = 0.0f;
      // Entry at t = 150.37: no lattice point lies near a face, so exactly L / step samples fall inside.
      view.distance = (150.37f + 0.5f * length) / radius;
      const ReferenceResult r = renderReference(whole, view, 9, 9, tf, settings, glm::vec2(0.0f, 1.0f));
      const float expected = 1.0f - std::pow(1.0f - a, length);
      INFO("a = " << a << ", step = " << step);
      CHECK(std::fabs(r.image.at(4, 4).a - expected) <= 1e-3f);
      CHECK(r.image.at(4, 4).r == doctest::Approx(r.image.at(4, 4).a));  // white, premultiplied
    }
  }
}

TEST_CASE("early ray termination stops a ray once its opacity reaches the threshold") {
  auto cube = test::makeVolume({32, 32, 32}, [](int, int, int) { return 1.0f; });
  const Brick whole = wholeVolumeBrick(*cube);
  const TransferFunction tf({{0.0f, glm::vec3(1.0f)}, {1.0f, glm::vec3(1.0f)}}, {{0.0f, 0.3f}, {1.0f, 0.3f}});
  RenderSettings settings;
  settings.shading = false;
  View view;
  view.projection = Projection::Orthographic;
  view.azimuthDeg = 0.0f;
  view.elevationDeg = 0.0f;
  settings.earlyTermination = 0.9f;
  const ReferenceResult stopped = renderReference(whole, view, 5, 5, tf, settings, glm::vec2(0.0f, 1.0f));
  settings.earlyTermination = 1.0f;
  const ReferenceResult full = renderReference(whole, view, 5, 5, tf, settings, glm::vec2(0.0f, 1.0f));
  CHECK(stopped.image.at(2, 2).a >= 0.9f);
  CHECK(stopped.image.at(2, 2).a < 0.95f);
  CHECK(full.image.at(2, 2).a > 0.999f);
  CHECK(stopped.counters.samples * 4 < full.counters.samples);
}
