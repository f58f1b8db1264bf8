// The built-in procedural data sets (vessels, turbulence, phantom) are deterministic, identical
// whether read whole or brick by brick, report their exact value range, and look like what they
// stand for; volume summaries count every voxel.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"
#include "core/volume/memory_volume.h"
#include "core/volume/volume_summary.h"

namespace kdswap {
namespace {

std::vector<float> readAll(const VolumeSource& source) {
  const glm::ivec3 d = source.info().dims;
  std::vector<float> out(std::size_t(d.x) * d.y * d.z);
  source.read(VoxelBox{{0, 0, 0}, d}, out.data());
  return out;
}

std::string sizeText(const glm::ivec3& d) {
  return std::to_string(d.x) + "x" + std::to_string(d.y) + "x" + std::to_string(d.z);
}

const char* const kProcedural[] = {"vessels", "turbulence", "phantom"};

}  // namespace

TEST_CASE("vessels and turbulence are registered, name themselves and suggest their preset") {
  const std::vector<std::string> names = datasetNames();
  for (const char* name : kProcedural) CHECK(std::find(names.begin(), names.end(), name) != names.end());
  for (const std::string name : {"vessels", "turbulence"}) {
    const auto source = openDataset(name + ":24x20x16");
    CHECK(source->info().dims == glm::ivec3(24, 20, 16));
    CHECK(source->info().name == name);
    CHECK(source->info().preset == name);
    CHECK(source->info().type == "float32");
    CHECK(openDataset(name)->info().dims == glm::ivec3(128));
  }
}

TEST_CASE("a data set's size is N or WxHxD, each a whole number from 2 to 8192") {
  CHECK(openDataset("phantom:40")->info().dims == glm::ivec3(40));
  CHECK(openDataset("vessels:32x48x64")->info().dims == glm::ivec3(32, 48, 64));
  CHECK(openDataset("turbulence:+16x2x8192")->info().dims == glm::ivec3(16, 2, 8192));
  CHECK(openDataset("phantom: 32 x 48 x 64")->info().dims == glm::ivec3(32, 48, 64));  // spaces are fine
  // A stray separator is refused, not dropped: "64x" must not quietly mean 64^3.
  for (const char* spec : {"phantom:64x", "phantom:64x64x64x", "phantom:64xx64", "phantom:x64", "phantom:",
                           "phantom:64x64", "phantom:0x40", "phantom:6.5", "phantom:6 4", "phantom:+-64"}) {
    CAPTURE(spec);
    CHECK_THROWS_WITH_AS(openDataset(spec), doctest::Contains("is not N or WxHxD"), Error);
  }
  for (const char* spec : {"phantom:1", "phantom:8193", "phantom:-64", "phantom:64x64x1"}) {
    CAPTURE(spec);
    CHECK_THROWS_WITH_AS(openDataset(spec), doctest::Contains("each size must be between 2 and 8192 voxels"), Error);
  }
}

TEST_CASE("a data set gives the same voxels read whole, brick by brick, or opened twice") {
  for (const char* name : kProcedural)
    for (const glm::ivec3 d : {glm::ivec3(17), glm::ivec3(33, 20, 9), glm::ivec3(40, 41, 42)}) {
      const std::string spec = std::string(name) + ":" + sizeText(d);
      CAPTURE(spec);
      const auto source = openDataset(spec);
      const std::vector<float> whole = readAll(*source);
      CHECK(readAll(*openDataset(spec)) == whole);
      const VoxelBox boxes[] = {{{0, 0, 0}, {d.x, d.y, 1}},        {{d.x / 2, 0, d.z / 3}, {d.x, d.y / 2 + 1, d.z}},
                                {{1, 2, 3}, {d.x - 1, d.y - 2, d.z - 3}}, {{d.x - 1, d.y - 1, d.z - 1}, d},
                                {{3, 0, 0}, {4, d.y, d.z}}};
      for (const VoxelBox& box : boxes) {
        std::vector<float> part(box.count());
        source->read(box, part.data());
        std::size_t i = 0, mismatches = 0;
        for (int z = box.lo.z; z < box.hi.z; ++z)
          for (int y = box.lo.y; y < box.hi.y; ++y)
            for (int x = box.lo.x; x < box.hi.x; ++x, ++i)
              mismatches += part[i] != whole[(std::size_t(z) * d.y + y) * d.x + x];
        CHECK(mismatches == 0);
      }
    }
}

TEST_CASE("the range vessels and turbulence report is exactly the range of their voxels") {
  for (const char* name : {"vessels", "turbulence"})
    for (const glm::ivec3 d : {glm::ivec3(5), glm::ivec3(8), glm::ivec3(37, 29, 23), glm::ivec3(64), glm::ivec3(96, 96, 48),
                               glm::ivec3(130, 20, 12)}) {
      const std::string spec = std::string(name) + ":" + sizeText(d);
      CAPTURE(spec);
      const auto source = openDataset(spec);
      const std::vector<float> v = readAll(*source);
      const auto [lo, hi] = std::minmax_element(v.begin(), v.end());
      CHECK(source->info().minValue == *lo);
      CHECK(source->info().maxValue == *hi);
      CHECK(std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); }));
    }
}

TEST_CASE("vessels are thin bright tubes in a dark, mostly empty background") {
  const auto source = openDataset("vessels:96");
  const std::vector<float> v = readAll(*source);
  const double n = double(v.size());
  const double empty = double(std::count(v.begin(), v.end(), 0.0f)) / n;
  const double bright = double(std::count_if(v.begin(), v.end(), [](float x) { return x > 0.5f; })) / n;
  CHECK(empty > 0.8);
  CHECK(bright > 0.001);
  CHECK(bright < 0.05);
  // Smooth profile: no jump from background to full intensity between neighbours.
  float step = 0.0f;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (i % 96 != 0) step = std::max(step, std::abs(v[i] - v[i - 1]));
  CHECK(step < 0.8f);
}

TEST_CASE("turbulence is dense and smooth, with structure at several scales") {
  const auto source = openDataset("turbulence:64");
  const std::vector<float> v = readAll(*source);
  double mean = 0.0;
  for (float x : v) mean += x;
  mean /= double(v.size());
  CHECK(mean > 0.15);
  CHECK(mean < 0.6);
  const double low = double(std::count_if(v.begin(), v.end(), [](float x) { return x < 0.02f; })) / double(v.size());
  CHECK(low < 0.02);
  float step = 0.0;
  for (std::size_t i = 1; i < v.size(); ++i)
    if (i % 64 != 0) step = std::max(step, std::abs(v[i] - v[i - 1]));
  CHECK(step < 0.35f);
  CHECK(step > 0.02f);
}

TEST_CASE("a summary histogram puts equal counts in equal bins and the maximum in the last bin") {
  // 16 values 0..15, each on 4x4 voxels of a slice: one value per bin of 16 over [0, 15].
  std::vector<float> values;
  for (int z = 0; z < 16; ++z)
    for (int i = 0; i < 16; ++i) values.push_back(float(z));
  VolumeInfo info;
  info.dims = glm::ivec3(4, 4, 16);
  info.name = "steps";
  info.type = "uint8";
  const MemoryVolume volume(info, values);
  const VolumeSummary s = summarizeVolume(volume, 16);
  CHECK(s.histogram == std::vector<std::uint64_t>(16, 16));
  CHECK(s.zeros == 16);
  CHECK(s.atMinimum == 16);
  CHECK(s.mean == doctest::Approx(7.5));
  CHECK(s.storedBytes == 256);
  CHECK(s.brickBytes == 256 * 16);
  const VolumeSummary four = summarizeVolume(volume, 4);
  CHECK(four.histogram == std::vector<std::uint64_t>(4, 64));
}

TEST_CASE("the summary of a data set streams every voxel and reports dims, type, spacing and range") {
  const auto source = openDataset("phantom:33x31x29");
  const std::vector<float> v = readAll(*source);
  const VolumeSummary s = summarizeVolume(*source, 16);
  std::uint64_t total = 0;
  for (std::uint64_t c : s.histogram) total += c;
  CHECK(total == v.size());
  CHECK(s.zeros == std::uint64_t(std::count(v.begin(), v.end(), 0.0f)));
  const nlohmann::json j = summaryToJson(s);
  CHECK(j["dims"] == nlohmann::json({33, 31, 29}));
  CHECK(j["type"] == "float32");
  CHECK(j["spacing"] == nlohmann::json({1.0, 1.0, 1.0}));
  CHECK(j["range"] == nlohmann::json({0.0, 1.0}));
  CHECK(j["histogram"]["counts"].size() == 16);
  const std::string text = formatSummary(s);
  CHECK(text.find("dimensions  33 x 31 x 29") != std::string::npos);
  CHECK(text.find("in bricks with gradients") != std::string::npos);
  CHECK(std::count(text.begin(), text.end(), '\n') >= 16 + 7);
}

}  // namespace kdswap
