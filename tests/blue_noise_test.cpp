// The blue-noise tile behind each ray's sampling phase (core/camera/blue_noise.h): every rank once,
// the same tile on every call and every machine, and the defining property: far less
// low-frequency energy than white noise, so jitter's grain is fine rather than blotchy.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdint>
#include <vector>

#include "core/camera/blue_noise.h"
#include "core/camera/camera.h"

namespace kdswap {
namespace {

constexpr int kSide = BlueNoiseTile::kSide;

//! Mean periodogram |DFT|^2 of the (mean-free) tile over frequencies 0 < |(u, v)| <= radius.
double lowFrequencyPower(const BlueNoiseTile& tile, int radius) {
  double mean = 0.0;
  for (int i = 0; i < BlueNoiseTile::kCells; ++i) mean += tile.data()[i];
  mean /= BlueNoiseTile::kCells;
  double power = 0.0;
  int count = 0;
  for (int v = -radius; v <= radius; ++v)
    for (int u = -radius; u <= radius; ++u) {
      if (u * u + v * v == 0 || u * u + v * v > radius * radius) continue;
      std::complex<double> sum = 0.0;
      for (int y = 0; y < kSide; ++y)
        for (int x = 0; x < kSide; ++x)
          sum += (double(tile.at(x, y)) - mean) * std::polar(1.0, -2.0 * M_PI * double(u * x + v * y) / kSide);
      power += std::norm(sum);
      ++count;
    }
  return power / count;
}

TEST_CASE("the blue-noise tile holds every rank's value (r + 1/2) / 4096 exactly once") {
  const BlueNoiseTile& tile = BlueNoiseTile::instance();
  std::vector<float> values(tile.data(), tile.data() + BlueNoiseTile::kCells);
  std::sort(values.begin(), values.end());
  for (int r = 0; r < BlueNoiseTile::kCells; ++r)
    REQUIRE(values[std::size_t(r)] == (float(r) + 0.5f) / float(BlueNoiseTile::kCells));
  CHECK(&BlueNoiseTile::instance() == &tile);
}

TEST_CASE("the blue-noise tile is the same on every machine: its ranks hash to one pinned value") {
  // Every rank of an MPI job builds its own tile, and its rays' lattices come from it: hosts that
  // built different tiles would render different images. The tile uses IEEE basic operations
  // only (no libm), so this value holds on any CPU and compiler setting (checked at -O0, -O2 and
  // -O2 -march=native when pinned).
  const BlueNoiseTile& tile = BlueNoiseTile::instance();
  std::uint64_t hash = 1469598103934665603ull;  // FNV-1a over the ranks
  for (int i = 0; i < BlueNoiseTile::kCells; ++i) {
    hash ^= std::uint64_t(tile.data()[i] * float(BlueNoiseTile::kCells));
    hash *= 1099511628211ull;
  }
  CHECK(hash == 10022113111318286093ull);
}

TEST_CASE("the blue-noise tile has almost no low-frequency energy, unlike white noise") {
  // White noise of variance 1/12 (uniform values) has an expected periodogram of 4096 / 12 at
  // every frequency; void-and-cluster ordering pushes the energy to high frequencies.
  const double white = BlueNoiseTile::kCells / 12.0;
  const double lowest = lowFrequencyPower(BlueNoiseTile::instance(), 4);
  MESSAGE("mean power at |f| <= 4 cycles per tile: " << lowest << " (white noise: " << white << ")");
  CHECK(lowest < 0.05 * white);
  // Neighbours differ by much more than independent values would (mean |a - b| = 1/3 for those).
  const BlueNoiseTile& tile = BlueNoiseTile::instance();
  double difference = 0.0;
  for (int y = 0; y < kSide; ++y)
    for (int x = 0; x < kSide; ++x)
      difference += std::fabs(tile.at(x, y) - tile.at(x + 1, y)) + std::fabs(tile.at(x, y) - tile.at(x, y + 1));
  difference /= 2.0 * BlueNoiseTile::kCells;
  MESSAGE("mean difference of 4-neighbours: " << difference);
  CHECK(difference > 0.37);
}

TEST_CASE("a ray's phase is its pixel's cell of the tile, repeating every 64 pixels") {
  const BlueNoiseTile& tile = BlueNoiseTile::instance();
  for (int py : {0, 5, 63, 64, 700})
    for (int px : {0, 1, 31, 64, 65, 1023}) {
      CHECK(Camera::pixelOffset(px, py) == tile.at(px % kSide, py % kSide));
      CHECK(Camera::pixelOffset(px + kSide, py) == Camera::pixelOffset(px, py));
      CHECK(Camera::pixelOffset(px, py + kSide) == Camera::pixelOffset(px, py));
    }
  // Every phase lies strictly inside (0, 1): a sample never sits on the ray's clip point itself.
  for (int i = 0; i < BlueNoiseTile::kCells; ++i) CHECK((tile.data()[i] > 0.0f && tile.data()[i] < 1.0f));
}

}  // namespace
}  // namespace kdswap
