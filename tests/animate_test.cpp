// Batch animation (issue 10): camera paths interpolate as documented, every frame of a distributed
// orbit equals the single-node render of its view, and a resumed run equals an uninterrupted one.
#include <doctest/doctest.h>

#include <unistd.h>

#include <sys/wait.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include "core/animation/camera_path.h"
#include "core/animation/sequence_writer.h"
#include "core/image/image_average.h"
#include "core/image/image_io.h"
#include "core/render/reference_render.h"
#include "core/render/voxel_ray.h"
#include "core/transfer/presets.h"
#include "core/util/error.h"
#include "core/volume/datasets/dataset.h"

#include "test_files.h"

using namespace kdswap;
namespace fs = std::filesystem;

namespace {

fs::path workDir() {
  const fs::path dir = fs::temp_directory_path() / ("kdswap-animate-test-" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir;
}

using test::Run;
using test::runKdswap;

std::vector<nlohmann::json> statsLines(const fs::path& p) {
  std::vector<nlohmann::json> lines;
  std::ifstream in(p);
  for (std::string line; std::getline(in, line);)
    if (!line.empty()) lines.push_back(nlohmann::json::parse(line));
  return lines;
}

int lineCount(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

}  // namespace

TEST_CASE("an orbit steps the azimuth evenly and a full turn does not repeat its first frame") {
  View start;
  start.azimuthDeg = 10.0f;
  const CameraPath path = CameraPath::orbit(start, 360.0f, 8);
  REQUIRE(path.frameCount() == 8);
  for (int i = 0; i < 8; ++i) {
    CHECK(path.frame(i).view.azimuthDeg == doctest::Approx(10.0f + 45.0f * i));
    CHECK(path.frame(i).view.elevationDeg == start.elevationDeg);
    CHECK(path.frame(i).view.distance == start.distance);
  }
  CHECK(CameraPath::orbit(start, 90.0f, 1).frame(0).view.azimuthDeg == 10.0f);
}

TEST_CASE("an elevation sweep goes from its first angle at the first frame to its second at the last") {
  const CameraPath path = CameraPath::orbit(View{}, 180.0f, 5, glm::vec2(-20.0f, 40.0f));
  CHECK(path.frame(0).view.elevationDeg == doctest::Approx(-20.0f));
  CHECK(path.frame(2).view.elevationDeg == doctest::Approx(10.0f));
  CHECK(path.frame(4).view.elevationDeg == doctest::Approx(40.0f));
  CHECK_THROWS_AS(CameraPath::orbit(View{}, 180.0f, 5, glm::vec2(-20.0f, 90.0f)), Error);
}

TEST_CASE("keys sit at the first and last frames, views between them are linear, a tf switches at its key") {
  View base;
  base.distance = 3.0f;
  std::vector<CameraKey> keys(3);
  keys[0].azimuthDeg = 0.0f;
  keys[0].elevationDeg = 10.0f;
  keys[1].azimuthDeg = 180.0f;  // elevation and distance repeat the previous key's
  keys[1].tf = "ct-bone";
  keys[2].azimuthDeg = 360.0f;
  keys[2].elevationDeg = 50.0f;
  keys[2].distance = 2.0f;
  const CameraPath path = CameraPath::fromKeys(base, keys, 9);
  REQUIRE(path.frameCount() == 9);
  CHECK(path.frame(0).view.azimuthDeg == doctest::Approx(0.0f));
  CHECK(path.frame(2).view.azimuthDeg == doctest::Approx(90.0f));
  CHECK(path.frame(4).view.azimuthDeg == doctest::Approx(180.0f));
  CHECK(path.frame(4).view.elevationDeg == doctest::Approx(10.0f));
  CHECK(path.frame(4).view.distance == doctest::Approx(3.0f));
  CHECK(path.frame(6).view.elevationDeg == doctest::Approx(30.0f));
  CHECK(path.frame(6).view.distance == doctest::Approx(2.5f));
  CHECK(path.frame(8).view.azimuthDeg == doctest::Approx(360.0f));
  CHECK(path.frame(8).view.distance == doctest::Approx(2.0f));
  CHECK(path.frame(3).tf.empty());
  CHECK(path.frame(4).tf == "ct-bone");
  CHECK(path.frame(8).tf == "ct-bone");
  CHECK(path.transferFunctions() == std::vector<std::string>{"ct-bone"});
  // One key: a still camera; one frame: the first key.
  CHECK(CameraPath::fromKeys(base, {keys[0]}, 4).frame(3).view.azimuthDeg == 0.0f);
  CHECK(CameraPath::fromKeys(base, keys, 1).frame(0).view.elevationDeg == doctest::Approx(10.0f));
}

TEST_CASE("malformed keys are rejected with the index of the bad key") {
  const auto j = nlohmann::json::parse(R"({"keys": [{"azimuth": 0}, {"azimuth": 10, "elevation": 95}]})");
  CHECK_THROWS_WITH_AS(parseCameraKeys(j, "k.json"), doctest::Contains("k.json: key 1"), Error);
  CHECK_THROWS_WITH_AS(parseCameraKeys(nlohmann::json::parse(R"([{"azimuth": "x"}])"), "k.json"),
                       doctest::Contains("key 0"), Error);
  CHECK_THROWS_WITH_AS(parseCameraKeys(nlohmann::json::parse(R"([{"azimut": 3}])"), "k.json"),
                       doctest::Contains("unknown field"), Error);
  CHECK_THROWS_AS(parseCameraKeys(nlohmann::json::array(), "k.json"), Error);
  CHECK_THROWS_WITH_AS(parseCameraKeys(nlohmann::json::parse(R"([{"azimuth": 0}, {"azimuth": 1e9}])"), "k.json"),
                       "k.json: key 1: \"azimuth\" must be from -36000 to 36000 degrees (100 turns)", Error);
  CHECK(parseCameraKeys(nlohmann::json::parse(R"([{"azimuth": -36000}])"), "k.json")[0].azimuthDeg == -36000.0f);
  CHECK_THROWS_AS(CameraPath::orbit(View{}, 360.0f, 0), Error);
  CHECK(CameraPath::orbit(View{}, -kMaxOrbitDegrees, 4).frame(3).view.azimuthDeg == View{}.azimuthDeg - 27000.0f);
  CHECK_THROWS_WITH_AS(CameraPath::orbit(View{}, 1e9f, 36), "orbit: degrees must be from -36000 to 36000 (100 turns)", Error);
  CHECK_THROWS_AS(CameraPath::orbit(View{}, std::nanf(""), 36), Error);
  CHECK_THROWS_AS(CameraPath::orbit(View{}, 360.0f, kMaxAnimationFrames + 1), Error);
}

TEST_CASE("frame numbers widen past 9999 frames and the summary takes medians") {
  const fs::path dir = workDir() / "names";
  fs::remove_all(dir);
  SequenceWriter small({dir.string(), "png", "", 10, false, {}});
  CHECK(fs::path(small.framePath(7)).filename() == "frame_0007.png");
  CHECK(fs::path(small.phasesPath(7)).filename() == "phases_0007.png");
  SequenceWriter big({dir.string(), "exr", "", 20000, false, {}});
  CHECK(fs::path(big.framePath(7)).filename() == "frame_00007.exr");
  big.record({{"frame", 0}, {"wall_s", 1.0}, {"modelled_parallel_s", 0.5}, {"gather_s", 0.1}});
  big.record({{"frame", 1}, {"wall_s", 3.0}, {"modelled_parallel_s", 0.7}, {"gather_s", 0.3}});
  big.record({{"frame", 2}, {"wall_s", 2.0}, {"modelled_parallel_s", 0.6}, {"gather_s", 0.2}});
  const SequenceSummary s = summarizeSequence(big.records());
  CHECK(s.frames == 3);
  CHECK(s.medianWallSeconds == 2.0);
  CHECK(s.medianModelledSeconds == 0.6);
  CHECK(s.medianGatherSeconds == 0.2);
  CHECK(statsLines(big.statsPath()).size() == 3);
}

TEST_CASE("kdswap animate: every frame of an 8-frame orbit on 5 nodes equals the single-node render") {
  const fs::path dir = workDir() / "orbit";
  fs::remove_all(dir);
  const std::string args = "animate --dataset phantom:32 --size 64x64 --nodes 5 --ert 1 --orbit 360 --frames 8 "
                           "--format exr --no-video --out-dir " + dir.string();
  const Run run = runKdswap(args);
  REQUIRE_MESSAGE(run.code == 0, run.err);

  const auto source = openDataset("phantom:32");
  const TransferFunction tf = loadTransferFunction(source->info().preset);
  RenderSettings settings;
  settings.earlyTermination = 1.0f;
  const Brick whole = wholeVolumeBrick(*source);
  const CameraPath path = CameraPath::orbit(View{}, 360.0f, 8);
  const auto lines = statsLines(dir / "stats.jsonl");
  REQUIRE(lines.size() == 8);
  for (int i = 0; i < 8; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.exr", i);
    REQUIRE(fs::exists(dir / name));
    const Image frame = readImage((dir / name).string());
    const ReferenceResult ref = renderReference(whole, path.frame(i).view, 64, 64, tf, settings,
                                                resolveValueRange(settings, source->info()));
    const float diff = maxAbsDifference(frame, ref.image, frame.rect());
    CHECK_MESSAGE(diff <= 1e-5f, "frame " << i << ": max abs diff " << diff << "; reproduce: kdswap " << args);
    CHECK(lines[std::size_t(i)]["frame"] == i);
    CHECK(lines[std::size_t(i)]["view"]["azimuth"].get<double>() == doctest::Approx(30.0 + 45.0 * i));
    for (const char* key : {"wall_s", "modelled_parallel_s", "distribute_s", "gather_s", "per_node"})
      CHECK_MESSAGE(lines[std::size_t(i)].contains(key), key);
  }
}

TEST_CASE("kdswap animate --passes: every frame is the mean of the same passes rendered on one node") {
  const fs::path dir = workDir() / "orbit_passes";
  fs::remove_all(dir);
  const std::string args = "animate --dataset phantom:32 --size 48x40 --nodes 6 --ert 1 --orbit 90 --frames 3 "
                           "--passes 3 --format exr --no-video --out-dir " + dir.string();
  const Run run = runKdswap(args);
  REQUIRE_MESSAGE(run.code == 0, run.err);

  const auto source = openDataset("phantom:32");
  const TransferFunction tf = loadTransferFunction(source->info().preset);
  const Brick whole = wholeVolumeBrick(*source);
  const CameraPath path = CameraPath::orbit(View{}, 90.0f, 3);
  const auto lines = statsLines(dir / "stats.jsonl");
  REQUIRE(lines.size() == 3);
  for (int i = 0; i < 3; ++i) {
    char name[32];
    std::snprintf(name, sizeof name, "frame_%04d.exr", i);
    const Image frame = readImage((dir / name).string());
    ImageAverage reference(Rect{0, 0, 48, 40});
    for (int pass = 0; pass < 3; ++pass) {
      RenderSettings settings;
      settings.earlyTermination = 1.0f;
      settings.phaseShift = latticePassShift(pass);
      reference.add(renderReference(whole, path.frame(i).view, 48, 40, tf, settings,
                                    resolveValueRange(settings, source->info()))
                        .image);
    }
    const float diff = maxAbsDifference(frame, reference.mean(), frame.rect());
    CHECK_MESSAGE(diff <= 1e-5f, "frame " << i << ": max abs diff " << diff << "; reproduce: kdswap " << args);
    CHECK(lines[std::size_t(i)]["render"]["passes"] == 3);  // part of the frame's identity for --resume
  }
}

TEST_CASE("kdswap animate --resume after an interruption gives the same files as an uninterrupted run") {
  const fs::path whole = workDir() / "whole", resumed = workDir() / "resumed";
  fs::remove_all(whole);
  fs::remove_all(resumed);
  const std::string common = "animate --dataset phantom:32 --size 48x40 --nodes 3 --ert 1 --orbit 300 --frames 6 "
                             "--elevation-sweep -10,30 --phases --no-video --out-dir ";
  REQUIRE(runKdswap(common + whole.string()).code == 0);

  const Run stopped = runKdswap(common + resumed.string() + " --stop-after 2");
  CHECK(stopped.code == 130);
  CHECK(stopped.err.find("--resume") != std::string::npos);
  CHECK(fs::exists(resumed / "frame_0001.png"));
  CHECK_FALSE(fs::exists(resumed / "frame_0002.png"));
  const auto firstWrite = fs::last_write_time(resumed / "frame_0000.png");

  const Run resume = runKdswap(common + resumed.string() + " --resume");
  REQUIRE_MESSAGE(resume.code == 0, resume.err);
  CHECK(resume.err.find("2 of 6 frames already done") != std::string::npos);
  CHECK(fs::last_write_time(resumed / "frame_0000.png") == firstWrite);  // kept, not rendered again
  for (int i = 0; i < 6; ++i) {
    char frame[32], phases[32];
    std::snprintf(frame, sizeof frame, "frame_%04d.png", i);
    std::snprintf(phases, sizeof phases, "phases_%04d.png", i);
    CHECK_MESSAGE(test::readFile(whole / frame) == test::readFile(resumed / frame), frame);
    CHECK(fs::exists(resumed / phases));
  }
  const auto lines = statsLines(resumed / "stats.jsonl");
  REQUIRE(lines.size() == 6);
  for (int i = 0; i < 6; ++i) CHECK(lines[std::size_t(i)]["frame"] == i);

  // A frame whose stats line is missing counts as not done, even though its image exists.
  std::ofstream(resumed / "stats.jsonl") << lines[0].dump() << "\n";
  const Run again = runKdswap(common + resumed.string() + " --resume");
  CHECK(again.code == 0);
  CHECK(again.err.find("1 of 6 frames already done") != std::string::npos);
  CHECK(statsLines(resumed / "stats.jsonl").size() == 6);
}

TEST_CASE("kdswap animate rejects bad input with one line and exit 2") {
  const fs::path dir = workDir() / "bad";
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::ofstream(dir / "blocker") << "a file, not a folder\n";
  std::ofstream(dir / "broken.json") << R"([{"azimuth": 0}, {"azimuth": 90, "distance": -1}])";
  std::ofstream(dir / "notjson.json") << "[{\"azimuth\": 0,";
  const std::string base = "animate --dataset phantom:16 --size 16x16 --no-video ";
  const std::string out = " --out-dir " + (dir / "out").string();
  struct Case {
    std::string args, expect;
  };
  for (const Case& c : {Case{base + "--frames 0" + out, "--frames 0"},
                        Case{base + "--frames 100001" + out, "--frames 100001"},
                        Case{base + "--keys " + (dir / "missing.json").string() + out, "missing.json"},
                        Case{base + "--keys " + (dir / "broken.json").string() + out, "key 1"},
                        Case{base + "--keys " + (dir / "notjson.json").string() + out, "not valid JSON"},
                        Case{base + "--frames 2 --out-dir " + (dir / "blocker" / "sub").string(), "blocker"}}) {
    const Run run = runKdswap(c.args);
    CHECK_MESSAGE(run.code == 2, c.args);
    CHECK_MESSAGE(lineCount(run.err) == 1, run.err);
    CHECK_MESSAGE(run.err.find(c.expect) != std::string::npos, run.err);
  }
}
