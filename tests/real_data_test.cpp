// The real test volumes in ../shared/data (SOURCES.md) open with the right shape, type, spacing
// and range, and their voxels equal the bytes read here directly, by a different code path.
#include <doctest/doctest.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include <glm/common.hpp>
#include <zlib.h>

#include "core/volume/reader.h"
#include "core/volume/volume_summary.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

const std::string kData = KDSWAP_SOURCE_DIR "/../shared/data";

bool haveData(const std::string& name) { return fs::exists(kData + "/" + name); }

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

//! The whole volume as floats through VolumeSource::read.
std::vector<float> readAll(const VolumeSource& source) {
  const glm::ivec3 d = source.info().dims;
  std::vector<float> out(std::size_t(d.x) * d.y * d.z);
  source.read(VoxelBox{{0, 0, 0}, d}, out.data());
  return out;
}

//! Compares `source` with uint8 voxels `bytes` (x fastest): every voxel, a brick, and the range.
void checkAgainstBytes(const VolumeSource& source, const unsigned char* bytes) {
  const glm::ivec3 d = source.info().dims;
  const std::vector<float> all = readAll(source);
  std::size_t mismatches = 0;
  unsigned char lo = 255, hi = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    mismatches += all[i] != float(bytes[i]);
    lo = std::min(lo, bytes[i]);
    hi = std::max(hi, bytes[i]);
  }
  CHECK(mismatches == 0);
  CHECK(source.info().minValue == float(lo));
  CHECK(source.info().maxValue == float(hi));
  const VoxelBox box{d / 4, d / 4 + d / 3};
  std::vector<float> brick(box.count());
  source.read(box, brick.data());
  std::size_t i = 0;
  mismatches = 0;
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x, ++i) mismatches += brick[i] != float(bytes[(std::size_t(z) * d.y + y) * d.x + x]);
  CHECK(mismatches == 0);
}

}  // namespace

TEST_CASE("the CT head opens from its detached NRRD header as 256x256x113 uint16, spacing 1 1 2, range 0..3272") {
  if (!haveData("cthead.nhdr")) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  const auto source = openVolumeFile(kData + "/cthead.nhdr");
  const VolumeInfo& info = source->info();
  CHECK(info.dims == glm::ivec3(256, 256, 113));
  CHECK(info.type == "uint16");
  CHECK(info.spacing == glm::vec3(1.0f, 1.0f, 2.0f));
  CHECK(info.minValue == 0.0f);
  CHECK(info.maxValue == 3272.0f);
  CHECK(info.nonFinite == 0);

  // Little-endian uint16 assembled by hand from the data file.
  const std::string raw = slurp(kData + "/cthead_256x256x113_uint16.raw");
  REQUIRE(raw.size() == 256u * 256 * 113 * 2);
  auto voxel = [&](int x, int y, int z) {
    const std::size_t i = 2 * ((std::size_t(z) * 256 + y) * 256 + x);
    return float(unsigned(static_cast<unsigned char>(raw[i])) | (unsigned(static_cast<unsigned char>(raw[i + 1])) << 8));
  };
  const VoxelBox box{{100, 60, 40}, {164, 131, 57}};
  std::vector<float> brick(box.count());
  source->read(box, brick.data());
  std::size_t i = 0, mismatches = 0, nonZero = 0;
  for (int z = box.lo.z; z < box.hi.z; ++z)
    for (int y = box.lo.y; y < box.hi.y; ++y)
      for (int x = box.lo.x; x < box.hi.x; ++x, ++i) {
        mismatches += brick[i] != voxel(x, y, z);
        nonZero += brick[i] != 0.0f;
      }
  CHECK(mismatches == 0);
  CHECK(nonZero > box.count() / 2);  // the brick is inside the head, not empty air
  for (const glm::ivec3 p : {glm::ivec3(0, 0, 0), glm::ivec3(255, 255, 112), glm::ivec3(128, 128, 56), glm::ivec3(17, 200, 99)}) {
    float v = -1.0f;
    source->read(VoxelBox{p, p + 1}, &v);
    CHECK(v == voxel(p.x, p.y, p.z));
  }
}

TEST_CASE("every NRRD header in the data folder matches its raw file opened by name, and the range it records") {
  if (!fs::exists(kData)) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  int headers = 0;
  for (const auto& entry : fs::directory_iterator(kData)) {
    if (entry.path().extension() != ".nhdr") continue;
    ++headers;
    const std::string header = slurp(entry.path().string());
    CAPTURE(entry.path().string());
    std::smatch file, range;
    REQUIRE(std::regex_search(header, file, std::regex("data file: (\\S+)")));
    const auto fromHeader = openVolumeFile(entry.path().string());
    const auto fromName = openVolumeFile(kData + "/" + file[1].str());
    CHECK(fromHeader->info().dims == fromName->info().dims);
    CHECK(fromHeader->info().type == fromName->info().type);
    CHECK(fromHeader->info().minValue == fromName->info().minValue);
    CHECK(fromHeader->info().maxValue == fromName->info().maxValue);
    if (std::regex_search(header, range, std::regex("value range: ([0-9.]+) \\.\\. ([0-9.]+)"))) {
      CHECK(fromHeader->info().minValue == doctest::Approx(std::stod(range[1].str())));
      CHECK(fromHeader->info().maxValue == doctest::Approx(std::stod(range[2].str())));
    }
    const glm::ivec3 d = fromHeader->info().dims;
    const VoxelBox box{d / 3, d / 3 + glm::min(d / 2, glm::ivec3(40))};
    std::vector<float> a(box.count()), b(box.count());
    fromHeader->read(box, a.data());
    fromName->read(box, b.data());
    CHECK(a == b);
  }
  CHECK(headers >= 10);
}

TEST_CASE("the MetaImage MR head opens as 48x62x42 uint8 with spacing 4 and equals its raw bytes") {
  if (!haveData("HeadMRVolume.mhd")) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  const auto source = openVolumeFile(kData + "/HeadMRVolume.mhd");
  CHECK(source->info().dims == glm::ivec3(48, 62, 42));
  CHECK(source->info().type == "uint8");
  CHECK(source->info().spacing == glm::vec3(4.0f));
  const std::string raw = slurp(kData + "/HeadMRVolume_48x62x42_uint8.raw");
  REQUIRE(raw.size() == 48u * 62 * 42);
  checkAgainstBytes(*source, reinterpret_cast<const unsigned char*>(raw.data()));
}

TEST_CASE("the legacy VTK 1.0 iron protein opens as 68^3 uint8 and equals the bytes after its LOOKUP_TABLE line") {
  if (!haveData("ironProt.vtk")) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  const auto source = openVolumeFile(kData + "/ironProt.vtk");
  CHECK(source->info().dims == glm::ivec3(68));
  CHECK(source->info().type == "uint8");
  CHECK(source->info().spacing == glm::vec3(1.0f));
  const std::string file = slurp(kData + "/ironProt.vtk");
  const std::string marker = "LOOKUP_TABLE default\n";
  const std::size_t start = file.find(marker);
  REQUIRE(start != std::string::npos);
  REQUIRE(file.size() >= start + marker.size() + 68u * 68 * 68);
  checkAgainstBytes(*source, reinterpret_cast<const unsigned char*>(file.data() + start + marker.size()));
  CHECK(source->info().maxValue > 0.0f);
}

TEST_CASE("the MNI NIfTI template with a big-endian header opens as 91x109x91 uint8, spacing 2") {
  if (!haveData("avg152T1_RL_nifti.nii.gz")) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  // Decompress independently with gzread.
  gzFile gz = gzopen((kData + "/avg152T1_RL_nifti.nii.gz").c_str(), "rb");
  REQUIRE(gz != nullptr);
  std::string bytes(1 << 21, '\0');
  const int got = gzread(gz, bytes.data(), unsigned(bytes.size()));
  gzclose(gz);
  REQUIRE(got == 352 + 91 * 109 * 91);
  const unsigned char* h = reinterpret_cast<const unsigned char*>(bytes.data());
  REQUIRE((h[0] == 0 && h[1] == 0 && h[2] == 1 && h[3] == 0x5c));  // 348, big-endian: the case this guards

  const auto source = openVolumeFile(kData + "/avg152T1_RL_nifti.nii.gz");
  CHECK(source->info().dims == glm::ivec3(91, 109, 91));
  CHECK(source->info().type == "uint8");
  CHECK(source->info().spacing == glm::vec3(2.0f));
  checkAgainstBytes(*source, h + 352);
  CHECK(source->info().maxValue == 255.0f);
}

TEST_CASE("the float32 hydrogen orbital equals its raw floats and has range 0..1") {
  if (!haveData("hydrogen_orbital.nhdr")) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  const auto source = openVolumeFile(kData + "/hydrogen_orbital.nhdr");
  CHECK(source->info().type == "float32");
  CHECK(source->info().minValue == 0.0f);
  CHECK(source->info().maxValue == doctest::Approx(1.0));
  const std::string raw = slurp(kData + "/hydrogen_orbital_64x64x64_float32.raw");
  REQUIRE(raw.size() == 64u * 64 * 64 * 4);
  const std::vector<float> all = readAll(*source);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < all.size(); ++i) {
    float v;
    std::memcpy(&v, raw.data() + 4 * i, 4);  // little-endian file on a little-endian test machine
    mismatches += all[i] != v;
  }
  CHECK(mismatches == 0);
}

TEST_CASE("the summary of the CT head counts every voxel, its zeros, and reports it in JSON") {
  if (!haveData("cthead.nhdr")) {
    MESSAGE("skipped: no real data at " << kData);
    return;
  }
  const auto source = openVolumeFile(kData + "/cthead.nhdr");
  const VolumeSummary s = summarizeVolume(*source, 16);
  const std::string raw = slurp(kData + "/cthead_256x256x113_uint16.raw");
  std::uint64_t zeros = 0, top = 0;
  for (std::size_t i = 0; i < raw.size(); i += 2) {
    const unsigned v = unsigned(static_cast<unsigned char>(raw[i])) | (unsigned(static_cast<unsigned char>(raw[i + 1])) << 8);
    zeros += v == 0;
    top += v >= 3272u - 3272u / 16;  // the last bin: [15/16 of the range, max]
  }
  std::uint64_t total = 0;
  for (std::uint64_t c : s.histogram) total += c;
  CHECK(total == 256u * 256 * 113);
  CHECK(s.zeros == zeros);
  CHECK(s.atMinimum == zeros);
  CHECK(s.histogram.back() == top);
  CHECK(s.storedBytes == 256u * 256 * 113 * 2);
  CHECK(s.brickBytes == 256u * 256 * 113 * 16);
  const nlohmann::json j = summaryToJson(s);
  CHECK(j["dims"] == nlohmann::json({256, 256, 113}));
  CHECK(j["type"] == "uint16");
  CHECK(j["spacing"] == nlohmann::json({1.0, 1.0, 2.0}));
  CHECK(j["range"] == nlohmann::json({0.0, 3272.0}));
}

}  // namespace kdswap
