// Command-line validation: every bad value is refused up front with one line naming the option or
// file and the problem, exit 2 — never a raw library message, a long run first, or a wrong image
// with exit 0. Each case runs the kdswap binary as a user would.
#include <doctest/doctest.h>

#include <sys/wait.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "test_files.h"

namespace kdswap {
namespace {

namespace fs = std::filesystem;

using test::TempDir;
using test::writeFile;

struct Output {
  int code;
  std::string out, err;
};

std::string readText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

//! Runs `build/app/kdswap ARGS`, keeping stdout too (test::runKdswap drops it; --help prints there).
Output run(const std::string& args) {
  const TempDir scratch;
  const std::string out = scratch.file("stdout.txt"), err = scratch.file("stderr.txt");
  const std::string command = std::string(KDSWAP_BINARY_DIR) + "/app/kdswap " + args + " > " + out + " 2> " + err;
  const int status = std::system(command.c_str());
  return Output{WIFEXITED(status) ? WEXITSTATUS(status) : -1, readText(out), readText(err)};
}

//! Checks that `args` exits 2 with one line on stderr, starting "kdswap: ", that contains every
//! one of `expected` and no "unexpected error" (a library exception that slipped through).
void expectRefused(const std::string& args, const std::vector<std::string>& expected) {
  const Output r = run(args);
  CAPTURE(args);
  CAPTURE(r.err);
  CHECK(r.code == 2);
  CHECK(std::count(r.err.begin(), r.err.end(), '\n') == 1);
  CHECK(r.err.rfind("kdswap: ", 0) == 0);
  CHECK(r.err.find("unexpected error") == std::string::npos);
  for (const std::string& e : expected) CHECK_MESSAGE(r.err.find(e) != std::string::npos, "missing: " << e);
}

const std::string kRender = "render --dataset phantom:16 --size 8x8 -q ";
const std::string kBench = "bench --dataset phantom:16 --frames 1 --sizes 16 --nodes 1 ";
const std::string kAnimate = "animate --dataset phantom:16 --size 8x8 --frames 2 --no-video ";

}  // namespace

TEST_CASE("render --background refuses NaN like inf and negative values") {
  const TempDir dir;
  for (const char* bad : {"nan,0,0", "0,nan,0", "inf,0,0", "-0.5,0,0", "0,0,0,", "0,0"})
    expectRefused(kRender + "--out " + dir.file("b.png") + " --background " + bad, {"--background", bad});
  CHECK(run(kRender + "--out " + dir.file("ok.png") + " --background 0.2,0.3,1").code == 0);
}

TEST_CASE("render --range refuses MIN,MAX that are not finite floats or equal at float precision") {
  const TempDir dir;
  for (const char* bad : {"0,1e-50", "0.5,0.50000001", "-1e39,1", "1e39,1e40", "-3e38,3e38", "0,1e-45"})
    expectRefused(kRender + "--out " + dir.file("r.png") + " --range " + bad, {"--range", bad, "float"});
  CHECK(run(kRender + "--out " + dir.file("ok.png") + " --range 0,1e-3").code == 0);
}

TEST_CASE("bench validates the view, distance, turn and threads like render, before any cell runs") {
  const TempDir dir;
  const std::string out = " --out-dir " + dir.file("bench");
  expectRefused(kBench + "--view nan,nan" + out, {"--view", "nan"});
  expectRefused(kBench + "--view 0,1000" + out, {"--view", "(-90, 90)"});
  expectRefused(kBench + "--view 30,15," + out, {"--view", "empty item"});
  expectRefused(kBench + "--degrees nan" + out, {"--degrees"});
  expectRefused(kBench + "--degrees 1000" + out, {"--degrees", "-360 to 360"});
  expectRefused(kBench + "--threads -3" + out, {"--threads", "0 to 1024"});
  expectRefused(kBench + "--step nan" + out, {"--step"});
  expectRefused(kBench + "--distance 0" + out, {"--distance", "between 0 and 1000"});
  expectRefused(kBench + "--distance nan" + out, {"--distance"});
  CHECK_FALSE(fs::exists(dir.file("bench")));  // nothing measured, nothing written
}

TEST_CASE("bench --interleave shapes a grid: the fixed-cell modes refuse it rather than ignore it") {
  expectRefused("bench --targets --interleave", {"--interleave", "--targets"});
  expectRefused("bench --micro --interleave", {"--interleave", "--micro"});
}

TEST_CASE("a folder or an out-of-range number as key file is named with the problem") {
  const TempDir dir;
  const std::string out = " --out-dir " + dir.file("anim");
  expectRefused(kAnimate + "--keys " + dir.path.string() + out, {dir.path.string(), "is a folder"});
  const std::string huge = dir.file("huge.json"), floatHuge = dir.file("float_huge.json");
  writeFile(huge, R"([{"azimuth": 1e400}])");
  writeFile(floatHuge, R"([{"azimuth": 0}, {"azimuth": 1e300}])");
  expectRefused(kAnimate + "--keys " + huge + out, {"huge.json", "out of range"});
  expectRefused(kAnimate + "--keys " + floatHuge + out, {"float_huge.json", "key 1", "azimuth", "finite"});
}

TEST_CASE("an output folder that is an existing file is refused before any work") {
  const TempDir dir;
  const std::string file = dir.file("plain_file");
  writeFile(file, "not a folder\n");
  expectRefused(kBench + "--out-dir " + file, {"--out-dir", "plain_file", "not a folder"});
  expectRefused(kAnimate + "--out-dir " + file, {"--out-dir", "plain_file", "not a folder"});
  expectRefused(kRender + "--out " + dir.file("x.png") + " --phases-dir " + file, {"--phases-dir", "not a folder"});
}

TEST_CASE("an unknown subcommand is named and the subcommands listed") {
  expectRefused("bogus_subcommand", {"unknown subcommand", "bogus_subcommand", "render", "animate", "bench", "info",
                                     "export"});
  expectRefused("\"\"", {"unknown subcommand"});
}

TEST_CASE("no subcommand, or an option before one, is answered with the subcommands") {
  expectRefused("", {"give a subcommand, one of", "render", "animate", "bench", "info", "export", "kdswap --help"});
  expectRefused("--out x.png", {"give a subcommand before \"--out\"", "render", "export"});
}

TEST_CASE("--tf naming a folder says it is a folder") {
  const TempDir dir;
  expectRefused(kRender + "--out " + dir.file("t.png") + " --tf " + dir.path.string(), {"--tf", "is a folder"});
  expectRefused(kBench + "--out-dir " + dir.file("b") + " --tf " + dir.path.string(), {"--tf", "is a folder"});
}

TEST_CASE("empty option values are refused, naming the option, instead of meaning the default") {
  const TempDir dir;
  const std::string png = " --out " + dir.file("e.png");
  for (const char* option : {"--volume", "--dataset", "--tf", "--speeds", "--range", "--spacing", "--radices"})
    expectRefused(kRender + png + " " + option + " \"\"", {std::string(option) + ": empty"});
  expectRefused(kRender + "--out \"\"", {"--out: empty"});
  expectRefused(kRender + png + " --stats \"\"", {"--stats: empty"});
  expectRefused(kBench + "--out-dir \"\"", {"--out-dir: empty"});
  expectRefused(kBench + "--out-dir " + dir.file("b") + " --dataset \"\"", {"--dataset: empty"});
  expectRefused(kAnimate + "--out-dir \"\"", {"--out-dir: empty"});
  expectRefused(kAnimate + "--out-dir " + dir.file("a") + " --keys \"\"", {"--keys: empty"});
  expectRefused("export --out \"\" --dataset phantom:8", {"--out: empty"});
  expectRefused("info --dataset \"\"", {"--dataset: empty"});
  // Every command that reads a --volume has the --raw-* options; an empty one is not "not given".
  const std::vector<std::string> readers = {kRender + png, kAnimate + "--out-dir " + dir.file("a"),
                                            kBench + "--out-dir " + dir.file("b"),
                                            "export --dataset phantom:8 --out " + dir.file("e.nrrd"), "info --dataset phantom:8"};
  for (const std::string& command : readers)
    for (const char* option : {"--raw-dims", "--raw-type", "--raw-endian", "--raw-spacing", "--raw-skip"})
      expectRefused(command + " " + option + " \"\"", {std::string(option) + ": "});
}

TEST_CASE("a trailing separator is an empty item, not dropped") {
  const TempDir dir;
  const std::string png = " --out " + dir.file("s.png");
  expectRefused("render --dataset phantom:16 -q --size 64x" + png, {"--size", "64x"});
  expectRefused(kRender + png + " --view 30,15,", {"--view", "empty item"});
  expectRefused(kRender + png + " --range 0,1,", {"--range", "empty item"});
  expectRefused(kRender + png + " --speeds 1,0.5,", {"--speeds", "empty item"});
  const std::string out = " --out-dir " + dir.file("bench");
  expectRefused("bench --dataset phantom:16 --frames 1 --nodes 1 --sizes 16," + out, {"--sizes"});
  expectRefused("bench --dataset phantom:16 --frames 1 --sizes 16 --nodes 1," + out, {"--nodes"});
  expectRefused(kBench + "--composite binary-swap," + out, {"--composite", "empty item"});
  expectRefused(kBench + "--balance space," + out, {"--balance", "empty item"});
}

TEST_CASE("--view elevation outside (-90, 90) is refused, not clamped; the range is in --help") {
  const TempDir dir;
  const std::string png = " --out " + dir.file("v.png");
  for (const char* bad : {"0,1000", "0,90", "0,-90", "0,-91"})
    expectRefused(kRender + png + " --view " + bad, {"--view", "elevation", "(-90, 90)"});
  expectRefused(kRender + png + " --view 1e39,0", {"--view", "azimuth"});
  expectRefused(kRender + png + " --view 1e9,0", {"--view", "azimuth", "-36000 to 36000"});
  expectRefused(kBench + "--view -36001,15 --out-dir " + dir.file("b"), {"--view", "azimuth", "-36000 to 36000"});
  expectRefused(kAnimate + "--out-dir " + dir.file("a") + " --view 0,95", {"--view", "(-90, 90)"});
  CHECK(run(kRender + png + " --view 400,89.5").code == 0);
  CHECK(run("render --help").out.find("(-90, 90)") != std::string::npos);
}

TEST_CASE("--radices with a strategy other than radix-k is refused instead of ignored") {
  const TempDir dir;
  expectRefused(kRender + "--out " + dir.file("r.png") + " --nodes 8 --radices 4,2", {"--radices", "radix-k"});
  CHECK(run(kRender + "--out " + dir.file("ok.png") + " --nodes 8 --composite radix-k --radices 4,2").code == 0);
}

TEST_CASE("export --type uint8 with --quantise 16 is refused, not one of them ignored") {
  const TempDir dir;
  expectRefused("export --dataset phantom:8 --quantise 16 --type uint8 --out " + dir.file("q.nrrd"),
                {"--type uint8", "--quantise 16"});
  CHECK_FALSE(fs::exists(dir.file("q.nrrd")));
  CHECK(run("export --dataset phantom:8 --quantise 8 --type uint16 --out " + dir.file("ok.nrrd")).code == 0);
}

TEST_CASE("bench --targets with a missing --head fails at once, before any target runs") {
  const auto start = std::chrono::steady_clock::now();
  expectRefused("bench --targets --frames 1 --head /nonexistent/head.nhdr", {"--head", "/nonexistent/head.nhdr"});
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  CHECK(seconds < 5.0);  // the other targets take tens of seconds
}

TEST_CASE("export can replace its own input, however the path is spelled") {
  // The new file is written beside the old one and renamed into place after the last read.
  const TempDir dir;
  const std::string volume = dir.file("in.nrrd");
  REQUIRE(run("export --dataset phantom:8 --out " + volume).code == 0);
  const std::string before = run("info " + volume).out;
  for (const std::string& out : {volume, (dir.path / "." / "in.nrrd").string()}) {
    const Output replaced = run("export --volume " + volume + " --out " + out);
    CHECK_MESSAGE(replaced.code == 0, replaced.err);
    CHECK(run("info " + volume).out.substr(before.find('\n')) == before.substr(before.find('\n')));
  }
}

TEST_CASE("info takes the volume as --volume FILE too, like every other subcommand") {
  const TempDir dir;
  const std::string volume = dir.file("v.nrrd");
  REQUIRE(run("export --dataset phantom:8 --out " + volume).code == 0);
  const Output positional = run("info " + volume), option = run("info --volume " + volume);
  CHECK(positional.code == 0);
  CHECK_MESSAGE(option.code == 0, option.err);
  CHECK(option.out == positional.out);
}

TEST_CASE("help texts list the accepted image extensions and the enforced ranges") {
  const std::string renderHelp = run("render --help").out;
  const std::string extensions = ".png, .exr, .tif, .tiff or .jpg";
  CHECK(renderHelp.find(extensions) != std::string::npos);
  const TempDir dir;
  expectRefused(kRender + "--out " + dir.file("x.bmp"), {"--out", extensions});
  const std::string benchHelp = run("bench --help").out;
  for (const char* text : {"NAME[:N|:WxHxD]", "1..1000", "each 1..16384", "each 1..4096", "0..1024", "(-90, 90)"})
    CHECK_MESSAGE(benchHelp.find(text) != std::string::npos, text);
  CHECK(run("animate --help").out.find("(0, 240]") != std::string::npos);
}

}  // namespace kdswap
