// NRRD export: what is written reads back as the same voxels (float32 exactly; 8/16-bit as the
// levels of the value range), and a file that cannot be written is a one-line error naming it.
#include <doctest/doctest.h>

#include <cmath>
#include <filesystem>

#include "core/bench/quantised_source.h"
#include "core/util/error.h"
#include "core/volume/reader.h"
#include "core/volume/writers/nrrd_writer.h"
#include "tests/test_files.h"
#include "tests/test_support.h"

namespace kdswap {
namespace {

std::vector<float> allVoxels(const VolumeSource& s) {
  std::vector<float> v(std::size_t(s.info().voxelCount()));
  s.read(VoxelBox{glm::ivec3(0), s.info().dims}, v.data());
  return v;
}

TEST_CASE("NRRD export: float32 reads back bit for bit, with dims and spacing") {
  const test::TempDir dir;
  // Odd sizes and anisotropic spacing: a transposed axis or a slice written twice would show.
  const auto volume = test::makeVolume(glm::ivec3(7, 5, 3), [](int x, int y, int z) { return float(x) - 0.25f * float(y * y) + 100.5f * float(z); },
                                       glm::vec3(0.5f, 1.25f, 3.0f));
  const std::string path = dir.file("v.nrrd");
  int slices = 0;
  writeNrrd(path, *volume, NrrdSample::Float32, [&](int done, int total) {
    CHECK(total == 3);
    slices = done;
  });
  CHECK(slices == 3);
  const auto back = openVolumeFile(path);
  CHECK(back->info().dims == glm::ivec3(7, 5, 3));
  CHECK(back->info().spacing == glm::vec3(0.5f, 1.25f, 3.0f));
  CHECK(allVoxels(*back) == allVoxels(*volume));
}

TEST_CASE("NRRD export: a quantised source written as uint8 / uint16 reads back as its levels") {
  const test::TempDir dir;
  for (int bits : {8, 16}) {
    CAPTURE(bits);
    const QuantisedSource quantised(test::makeBlobs(glm::ivec3(9, 8, 6)), bits);
    const std::string path = dir.file(bits == 8 ? "q8.nrrd" : "q16.nrrd");
    writeNrrd(path, quantised, bits == 8 ? NrrdSample::Uint8 : NrrdSample::Uint16);
    const auto back = openVolumeFile(path);
    CHECK(back->info().type == (bits == 8 ? "uint8" : "uint16"));
    const std::vector<float> levels = allVoxels(*back), values = allVoxels(quantised);
    const float lo = quantised.info().minValue, span = quantised.info().maxValue - lo, top = float((1 << bits) - 1);
    REQUIRE(levels.size() == values.size());
    float highest = 0.0f;
    for (std::size_t i = 0; i < levels.size(); ++i) {
      CHECK(levels[i] == std::round((values[i] - lo) / span * top));  // whole levels, in voxel order
      highest = std::max(highest, levels[i]);
    }
    CHECK(highest == top);  // the maximum maps to the top level
  }
}

TEST_CASE("NRRD export: unwritable paths and unknown types are one-line errors naming them") {
  const auto volume = test::makeVolume(glm::ivec3(2, 2, 2), [](int x, int, int) { return float(x); });
  const std::string path = "/nonexistent-kdswap-dir/v.nrrd";
  try {
    writeNrrd(path, *volume, NrrdSample::Float32);
    FAIL("expected an error");
  } catch (const Error& e) {
    CHECK(std::string(e.what()).find(path) != std::string::npos);
  }
  CHECK_FALSE(std::filesystem::exists(path));
  CHECK_THROWS_AS(parseNrrdSample("int7", "--type"), Error);
  CHECK(parseNrrdSample("uint16", "--type") == NrrdSample::Uint16);
}

}  // namespace
}  // namespace kdswap
