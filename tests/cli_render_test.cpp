// The command line as a user runs it: the default scene renders to a non-blank picture, the
// scripting interface (stats JSON, --verify) holds, and bad options give one line and exit 2.
#include <doctest/doctest.h>

#include <unistd.h>

#include <sys/wait.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "core/image/image_io.h"
#include "core/volume/reader.h"

#include "test_files.h"

using namespace kdswap;
namespace fs = std::filesystem;

namespace {

fs::path workDir() {
  const fs::path dir = fs::temp_directory_path() / ("kdswap-cli-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

using test::Run;
using test::runKdswap;

int lineCount(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("kdswap render writes the default scene as a picture that is not blank") {
  const fs::path png = workDir() / "default.png", exr = workDir() / "default.exr";
  fs::remove(png);
  fs::remove(exr);
  REQUIRE(runKdswap("render --size 96x80 --out " + png.string()).code == 0);
  REQUIRE(runKdswap("render --size 96x80 --nodes 4 --out " + exr.string()).code == 0);
  const Image picture = readImage(exr.string());
  CHECK(picture.width() == 96);
  CHECK(picture.height() == 80);
  int covered = 0, empty = 0;
  for (int y = 0; y < 80; ++y)
    for (int x = 0; x < 96; ++x) (picture.at(x, y).a > 0.0f ? covered : empty)++;
  CHECK(covered > 96 * 80 / 10);  // the head fills a good part of the frame
  CHECK(empty > 0);               // and there is background around it
  const Image opaque = readImage(png.string());
  CHECK(opaque.at(0, 0).r == 0.0f);                    // black background
  CHECK(opaque.at(48, 40).r + opaque.at(48, 40).g > 0.05f);  // something drawn in the middle
}

TEST_CASE("kdswap render --verify --stats writes the documented JSON keys and passes") {
  const fs::path json = workDir() / "stats.json";
  const Run run = runKdswap("render --dataset phantom:48 --size 64x48 --nodes 6 --ert 1 --verify --stats " + json.string() +
                         " --out " + (workDir() / "v.png").string());
  CHECK(run.code == 0);
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const char* key : {"nodes", "image", "strategy", "partition", "wall_s", "render_s_max", "composite_s_max",
                          "modelled_parallel_s", "samples", "rays", "rays_occluded", "bytes_sent", "peak_rss_bytes",
                          "per_node",
                          "distribute_s", "gather_s", "occlusion_map_s"})
    CHECK_MESSAGE(j.contains(key), key);
  CHECK(j["nodes"] == 6);
  CHECK(j["occlusion_map_s"].get<double>() == 0.0);  // --ert 1: no early termination, so no map to compute
  CHECK(j["per_node"].size() == 6);
  CHECK(j["per_node"][0].contains("private_bytes"));
  // The culled pairs are counted among the rays, node by node and in all.
  std::uint64_t occluded = 0;
  for (const auto& node : j["per_node"]) {
    CHECK(node["rays_occluded"].get<std::uint64_t>() <= node["rays"].get<std::uint64_t>());
    occluded += node["rays_occluded"].get<std::uint64_t>();
  }
  CHECK(j["rays_occluded"].get<std::uint64_t>() == occluded);
  CHECK(j["verify"]["max_abs_diff"].get<double>() <= 1e-5);
}

TEST_CASE("kdswap render --passes averages shifted lattices, records them and verifies against the same passes") {
  const fs::path json = workDir() / "passes.json", one = workDir() / "one.exr", four = workDir() / "four.exr";
  const Run run = runKdswap("render --dataset phantom:48 --size 64x48 --nodes 5 --ert 1 --passes 4 --verify --stats " +
                            json.string() + " --out " + four.string());
  CHECK(run.code == 0);
  std::ifstream in(json);
  const nlohmann::json j = nlohmann::json::parse(in);
  CHECK(j["passes"]["count"] == 4);
  CHECK(j["passes"]["wall_s"].get<double>() >= j["wall_s"].get<double>());  // four frames, the table's the first
  CHECK(j["verify"]["max_abs_diff"].get<double>() <= 1e-5);
  // The mean differs from the first pass alone (its lattice is one of four), but only a little.
  REQUIRE(runKdswap("render --dataset phantom:48 --size 64x48 --nodes 5 --ert 1 --out " + one.string()).code == 0);
  const Image a = readImage(one.string()), b = readImage(four.string());
  const float diff = maxAbsDifference(a, b, a.rect());
  CHECK(diff > 1e-3f);
  CHECK(diff < 0.25f);
}

TEST_CASE("kdswap render --phases writes the Figure 6 grid") {
  const fs::path grid = workDir() / "grid.png";
  fs::remove(grid);
  CHECK(runKdswap("render --dataset phantom:32 --size 40x40 --nodes 8 --phases " + grid.string() + " --out " +
               (workDir() / "g.png").string()).code == 0);
  const Image img = readImage(grid.string());
  CHECK(img.width() > 8 * 40 / 2);
  CHECK(img.height() > 4 * 20);
}

TEST_CASE("bad options give one line on stderr and exit code 2") {
  const std::string out = " --out " + (workDir() / "bad.png").string();
  for (const std::string& args :
       {std::string("render --size 0x10"), std::string("render --size 20000x10"), std::string("render --size banana"),
        std::string("render --nodes 0"), std::string("render --nodes 5000"), std::string("render --no-such-option"),
        std::string("render --composite magic"), std::string("render --volume /no/such/file.nrrd"),
        std::string("render --tf no-such-preset"), std::string("render --step 0"), std::string("render --view 10"),
        std::string("render --spacing 1,0,1"), std::string("render --spacing 1,2")}) {
    const Run run = runKdswap(args + out);
    CHECK_MESSAGE(run.code == 2, args);
    CHECK_MESSAGE(lineCount(run.err) == 1, args << " printed: " << run.err);
  }
  const Run unwritable = runKdswap("render --size 8x8 --out /no/such/folder/a.png");
  CHECK(unwritable.code == 2);
  CHECK(unwritable.err.find("/no/such/folder") != std::string::npos);
}

TEST_CASE("kdswap render --spacing overrides the data's voxel spacing") {
  // A 24-voxel phantom stretched 3 times along z is taller on screen (z is up): more rows are lit.
  const auto litRows = [](const std::string& extra) {
    const std::string path = (workDir() / "spacing.exr").string();
    const Run run = runKdswap("render --dataset phantom:24 --size 32x32 --view 90,0 --tf grayscale --out " + path + extra);
    REQUIRE_MESSAGE(run.code == 0, run.err);
    const Image image = readImage(path);
    int rows = 0;
    for (int y = 0; y < image.height(); ++y) {
      bool lit = false;
      for (int x = 0; x < image.width(); ++x) lit = lit || image.at(x, y).a > 0.05f;
      rows += lit ? 1 : 0;
    }
    return rows;
  };
  const int plain = litRows(""), stretched = litRows(" --spacing 1,1,3");
  CHECK(plain > 0);
  CHECK(stretched > plain);
}

TEST_CASE("kdswap export writes a data set that kdswap and other tools read back") {
  const fs::path nrrd = workDir() / "phantom16.nrrd";
  fs::remove(nrrd);
  REQUIRE(runKdswap("export --dataset phantom:16 --quantise 8 --out " + nrrd.string()).code == 0);
  const auto back = openVolumeFile(nrrd.string());
  CHECK(back->info().type == "uint8");
  CHECK(back->info().dims == glm::ivec3(16));
  CHECK(back->info().maxValue > 0.0f);  // levels of the phantom's nominal range [0, 1]
  CHECK(back->info().maxValue <= 255.0f);
  // It renders like any file.
  CHECK(runKdswap("render --volume " + nrrd.string() + " --size 32x32 --nodes 4 --verify --out " +
                  (workDir() / "e.png").string()).code == 0);
  const Run bad = runKdswap("export --dataset phantom:16 --out " + (workDir() / "x.png").string());
  CHECK(bad.code == 2);
  CHECK(lineCount(bad.err) == 1);
}

TEST_CASE("kdswap bench --distance frames the scene as render does: the same view takes the same samples") {
  const fs::path dir = workDir() / "bench-distance";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const std::string scene = " --dataset phantom:32 --tf grayscale --step 1 --view 40,20";
  const Run render = runKdswap("render" + scene + " --size 64x64 --nodes 1 -q --out " + (dir / "r.png").string() +
                               " --stats " + (dir / "r.json").string());
  REQUIRE(render.code == 0);
  const std::uint64_t renderSamples = nlohmann::json::parse(test::readFile((dir / "r.json").string()))["samples"];
  REQUIRE(renderSamples > 0);
  auto benchSamples = [&](const std::string& distance) {
    const fs::path out = dir / ("bench" + distance);
    const Run bench = runKdswap("bench" + scene + " --sizes 64 --nodes 1 --frames 1 --degrees 0 --out-dir " +
                                out.string() + (distance.empty() ? "" : " --distance " + distance));
    CAPTURE(bench.err);
    REQUIRE(bench.code == 0);
    const nlohmann::json j = nlohmann::json::parse(test::readFile((out / "bench.json").string()));
    CHECK(j["settings"]["view_distance"].get<double>() == doctest::Approx(distance.empty() ? 2.5 : std::stod(distance)));
    CHECK(j["command"].get<std::string>().find(" --distance ") != std::string::npos);
    return j["cells"][0]["samples"].get<double>();
  };
  CHECK(benchSamples("3.4") == double(renderSamples));  // render's default distance
  CHECK(benchSamples("") > double(renderSamples));      // the bench's closer default: more of the frame
}

TEST_CASE("kdswap bench --interleave says so in bench.json and the recorded command") {
  const fs::path dir = workDir() / "bench-interleave";
  fs::remove_all(dir);
  const Run bench = runKdswap("bench --dataset phantom:16 --sizes 16,24 --nodes 1,2 --frames 1 --interleave --out-dir " +
                              dir.string());
  CAPTURE(bench.err);
  REQUIRE(bench.code == 0);
  const nlohmann::json j = nlohmann::json::parse(test::readFile((dir / "bench.json").string()));
  CHECK(j["settings"]["interleaved"] == true);
  CHECK(j["command"].get<std::string>().find(" --interleave") != std::string::npos);
  CHECK(j["cells"].size() == 4);
  // Where it ran: this machine's CPU count, and a kernel name.
  CHECK(j["machine"]["logical_cpus"].get<int>() == int(std::thread::hardware_concurrency()));
  CHECK_FALSE(j["machine"]["cpu"].get<std::string>().empty());
  const std::string march = j["machine"]["ray_march"];
  // AMD CPUs with AVX-512 run the 512-bit build ("avx512"), Intel ones the 256-bit builds.
  CHECK((march == "scalar" || march == "avx2" || march == "avx2+avx512vl" || march == "avx512"));
}
