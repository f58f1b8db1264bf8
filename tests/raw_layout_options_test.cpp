// The --raw-* options on every command that reads a volume: a headerless file whose name gives no
// layout is exported and benchmarked with the voxels the options describe, and the options are
// refused wherever no raw file is read (a data set, bench's own-data modes).
#include <doctest/doctest.h>

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/volume/reader.h"
#include "tests/test_files.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

std::vector<float> allVoxels(const VolumeSource& s) {
  std::vector<float> v(std::size_t(s.info().voxelCount()));
  s.read(VoxelBox{glm::ivec3(0), s.info().dims}, v.data());
  return v;
}

//! `value` as two bytes in the given order.
std::string twoBytes(std::uint16_t value, bool bigEndian) {
  const char low = char(value & 0xff), high = char(value >> 8);
  return bigEndian ? std::string{high, low} : std::string{low, high};
}

TEST_CASE("export writes a headerless uint16 file described by --raw-dims and --raw-type as a NRRD of the same voxels") {
  const test::TempDir dir;
  // Values above 32767: read as int16 they would turn negative; read with the wrong byte order,
  // 40000 + 97 i would come back scrambled.
  std::string bytes;
  std::vector<float> expected;
  for (int i = 0; i < 5 * 4 * 3; ++i) {
    const auto v = std::uint16_t(40000 + 97 * i);
    bytes += twoBytes(v, false);
    expected.push_back(float(v));
  }
  const std::string raw = dir.file("scan.raw"), nrrd = dir.file("scan.nrrd");
  test::writeFile(raw, bytes);
  const test::Run run = test::runKdswap("export --volume " + raw + " --raw-dims 5x4x3 --raw-type uint16 -o " + nrrd);
  CAPTURE(run.err);
  REQUIRE(run.code == 0);
  const auto back = openVolumeFile(nrrd);
  CHECK(back->info().dims == glm::ivec3(5, 4, 3));
  CHECK(allVoxels(*back) == expected);
}

TEST_CASE("export reads a big-endian file after a skipped header, with the spacing given by --raw-spacing") {
  const test::TempDir dir;
  std::string bytes = "sixteen byte hdr";
  std::vector<float> expected;
  for (int i = 0; i < 3 * 4 * 2; ++i) {
    const auto v = std::int16_t(-300 + 29 * i);
    bytes += twoBytes(std::uint16_t(v), true);
    expected.push_back(float(v));
  }
  const std::string raw = dir.file("signed.raw"), nrrd = dir.file("signed.nrrd");
  test::writeFile(raw, bytes);
  const test::Run run = test::runKdswap("export --volume " + raw + " --raw-dims 3x4x2 --raw-type int16 --raw-endian big " +
                                        "--raw-skip 16 --raw-spacing 0.5,1,2 --out " + nrrd);
  CAPTURE(run.err);
  REQUIRE(run.code == 0);
  const auto back = openVolumeFile(nrrd);
  CHECK(back->info().dims == glm::ivec3(3, 4, 2));
  CHECK(back->info().spacing == glm::vec3(0.5f, 1.0f, 2.0f));
  CHECK(allVoxels(*back) == expected);
}

TEST_CASE("bench runs on a raw file described by --raw-*, and its recorded command line reproduces the run") {
  const test::TempDir dir;
  std::string bytes = "head";  // --raw-skip 4
  for (int i = 0; i < 16 * 12 * 10; ++i) bytes += twoBytes(std::uint16_t(i * 37 % 4096), true);
  const std::string raw = dir.file("scan.raw"), out = dir.file("bench");
  test::writeFile(raw, bytes);
  const std::string layout = "--raw-dims 16x12x10 --raw-type uint16 --raw-endian big --raw-spacing 1,1,2 --raw-skip 4";
  const test::Run run =
      test::runKdswap("bench --volume " + raw + " " + layout + " --sizes 16 --nodes 1,2 --frames 1 --out-dir " + out);
  CAPTURE(run.err);
  REQUIRE(run.code == 0);
  const auto report = [&] { return nlohmann::json::parse(test::readFile(out + "/bench.json")); };
  const nlohmann::json j = report();
  CHECK(j["volume"]["dims"] == nlohmann::json({16, 12, 10}));
  CHECK(j["volume"]["type"] == "uint16");
  CHECK(j["cells"].size() == 2);
  const std::string command = j["command"];
  CAPTURE(command);
  CHECK(command.find("--volume " + raw + " " + layout + " ") != std::string::npos);

  // Without its layout the file cannot be read at all, so a second run proves the line carries it.
  REQUIRE(command.rfind("kdswap ", 0) == 0);
  fs::remove_all(out);
  const test::Run again = test::runKdswap(command.substr(7));
  CAPTURE(again.err);
  CHECK(again.code == 0);
  CHECK(report()["volume"]["dims"] == nlohmann::json({16, 12, 10}));
}

TEST_CASE("bench refuses a bad --raw-dims before measuring or writing anything") {
  const test::TempDir dir;
  const std::string raw = dir.file("plain.raw"), out = dir.file("bench");
  test::writeFile(raw, std::string(64, '\0'));
  const std::string bench = "bench --volume " + raw + " --raw-type uint8 --sizes 16 --nodes 1 --frames 1 --out-dir " + out;
  const std::pair<const char*, const char*> kBad[] = {
      {"4x4", "expected WxHxD"},
      {"4x4x", "empty item (a 'x' too many)"},
      {"4xfourx4", "\"four\" is not a number"},
      {"1x4x16", "each size must be a whole number from 2 to 1000000"},
      {"4x4x4.5", "each size must be a whole number from 2 to 1000000"}};
  for (const auto& [dims, problem] : kBad) {
    CAPTURE(dims);
    const test::Run run = test::runKdswap(bench + " --raw-dims " + dims);
    CHECK(run.code == 2);
    CHECK(run.err == "kdswap: --raw-dims \"" + std::string(dims) + "\": " + problem + "\n");
    CHECK_FALSE(fs::exists(out));
  }
  CHECK(test::runKdswap(bench + " --raw-dims 4x4x4").code == 0);  // the same command with good dimensions runs
}

TEST_CASE("every --raw-* option is refused, naming it, by every command that reads no raw file") {
  const test::TempDir dir;
  const std::string out = dir.file("out");
  struct Command {
    std::string args;   //!< writes to `out` if it runs
    std::string other;  //!< what the command reads instead of a raw file
  };
  const Command kCommands[] = {
      {"render --dataset phantom:16 --size 16x16 --out " + out + ".png", "--dataset phantom:16"},
      {"info --dataset phantom:16", "--dataset phantom:16"},
      {"export --dataset phantom:16 --out " + out + ".nrrd", "--dataset phantom:16"},
      {"bench --dataset phantom:16 --sizes 16 --nodes 1 --frames 1 --out-dir " + out, "--dataset phantom:16"},
      {"bench --sizes 16 --nodes 1 --frames 1 --out-dir " + out, "--dataset phantom:128 (the default)"},
      {"bench --targets", "--targets"},
      {"bench --micro", "--micro"},
      {"bench --paper --frames 1", "--paper"}};
  const std::pair<const char*, const char*> kOptions[] = {
      {"--raw-dims", "4x4x4"}, {"--raw-type", "uint8"}, {"--raw-endian", "big"}, {"--raw-spacing", "1,1,1"}, {"--raw-skip", "8"}};
  for (const Command& c : kCommands)
    for (const auto& [option, value] : kOptions) {
      const std::string args = c.args + " " + option + " " + value;
      CAPTURE(args);
      const test::Run run = test::runKdswap(args);
      CHECK(run.code == 2);
      CHECK(run.err == "kdswap: " + std::string(option) + " describes a raw --volume file; it does not apply to " + c.other + "\n");
      CHECK_FALSE(fs::exists(out + ".png"));
      CHECK_FALSE(fs::exists(out + ".nrrd"));
      CHECK_FALSE(fs::exists(out));
    }
}

}  // namespace
}  // namespace kdswap
