// A command's outputs are checked before it works: an output that names its input, another
// output or a folder is refused with one line and nothing is written; a transparent background is
// not silently dropped into a JPEG; an animation folder holds only this run's frames; an error
// naming a file with a newline in its name stays on one line; an export whose voxels do not fill
// the data set's range says which --range renders it alike.
#include <doctest/doctest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/util/printable_text.h"

#include "test_files.h"

using namespace kdswap;
namespace fs = std::filesystem;

namespace {

using test::Run;
using test::runKdswap;
using test::TempDir;

int lineCount(const std::string& s) { return int(std::count(s.begin(), s.end(), '\n')); }

//! Runs kdswap ARGS; the run must fail with exit 2, one line on stderr holding `expected`.
void expectRefused(const std::string& args, const std::string& expected) {
  const Run run = runKdswap(args);
  CHECK_MESSAGE(run.code == 2, args);
  CHECK_MESSAGE(lineCount(run.err) == 1, args << " printed: " << run.err);
  CHECK_MESSAGE(run.err.find(expected) != std::string::npos, args << " printed: " << run.err);
}

}  // namespace

TEST_CASE("render refuses outputs that would overwrite its input or each other, before rendering") {
  const TempDir dir;
  const std::string volume = dir.file("in.nrrd");
  REQUIRE(runKdswap("export --dataset phantom:16 --out " + volume).code == 0);
  const std::string before = test::readFile(volume);
  const std::string scene = "render --size 16x16 --volume " + volume;

  expectRefused(scene + " --out " + dir.file("a.png") + " --stats " + volume, "is an input of this command");
  fs::create_symlink(volume, dir.path / "link.nrrd");
  expectRefused(scene + " --out " + dir.file("a.png") + " --stats " + dir.file("link.nrrd"),
                "is an input of this command");
  expectRefused(scene + " --out " + dir.file("a.png") + " --stats " + dir.file("a.png"), "the same file as --out");
  expectRefused(scene + " --nodes 2 --out " + dir.file("a.png") + " --phases " + (dir.path / "." / "a.png").string(),
                "the same file as --out");
  expectRefused(scene + " --out " + dir.file("a.png") + " --stats " + dir.path.string(), "is a directory");
  expectRefused(scene + " --background none --out " + dir.file("a.jpg"), "no alpha channel");

  CHECK(test::readFile(volume) == before);
  CHECK_FALSE(fs::exists(dir.file("a.png")));  // refused before the render, so nothing written
  CHECK_FALSE(fs::exists(dir.file("a.jpg")));
  // Different files are fine, and a transparent background goes into a PNG.
  CHECK(runKdswap(scene + " --background none --out " + dir.file("a.png") + " --stats " + dir.file("a.json")).code == 0);
}

TEST_CASE("export may replace its input in place, and names the --range that renders it like the data set") {
  const TempDir dir;
  const std::string volume = dir.file("p.nrrd");
  const std::string note = dir.file("note.txt");
  // phantom:16's voxels do not reach the top of the range 0 .. 1 it is rendered over.
  const std::string command = std::string(KDSWAP_BINARY_DIR) + "/app/kdswap export --dataset phantom:16 --out " +
                              volume + " > " + note;
  REQUIRE(std::system(command.c_str()) == 0);
  CHECK(test::readFile(note).find("render this file with --range 0,1") != std::string::npos);
  CHECK(runKdswap("export --volume " + volume + " --quantise 8 --out " + volume).code == 0);
  CHECK(test::readFile(volume).find("type: uint8") != std::string::npos);
}

TEST_CASE("animate removes the frames of an earlier, longer run from its folder") {
  const TempDir dir;
  const std::string out = dir.file("frames");
  const std::string scene = "animate --dataset phantom:16 --size 16x16 --no-video --out-dir " + out;
  REQUIRE(runKdswap(scene + " --frames 4").code == 0);
  REQUIRE(fs::exists(out + "/frame_0003.png"));
  test::writeFile(out + "/notes.txt", "mine");
  REQUIRE(runKdswap(scene + " --frames 2").code == 0);
  CHECK(fs::exists(out + "/frame_0001.png"));
  CHECK_FALSE(fs::exists(out + "/frame_0002.png"));
  CHECK_FALSE(fs::exists(out + "/frame_0003.png"));
  CHECK(fs::exists(out + "/notes.txt"));  // only the pictures it names itself
}

TEST_CASE("an error naming a file with a newline in its name is one line") {
  const TempDir dir;
  const Run run = runKdswap("render --size 8x8 --out " + dir.file("a.png") + " --volume '" + dir.file("no\nsuch.nrrd") + "'");
  CHECK(run.code == 2);
  CHECK(lineCount(run.err) == 1);
  CHECK(run.err.find("no\\x0Asuch.nrrd") != std::string::npos);
  CHECK(oneLine("a\tb\nc") == "a\\x09b\\x0Ac");
  CHECK(printableText("a\tb\nc") == "a\tb\nc");  // a window keeps its line breaks
}

TEST_CASE("a long frame shows a progress line on a terminal, and none when stderr is a file") {
  const TempDir dir;
  // A message held back 2 s makes the frame long on any machine; `script` gives it a terminal.
  const std::string render = std::string(KDSWAP_BINARY_DIR) +
                             "/app/kdswap render --dataset phantom:16 --size 16x16 --nodes 4 "
                             "--inject-fault delay:1:0:2 --out " + dir.file("a.png");
  const std::string shown = dir.file("terminal.txt");
  REQUIRE(std::system(("script -qec '" + render + "' /dev/null > " + shown + " 2>&1").c_str()) == 0);
  CHECK(test::readFile(shown).find("of 4 nodes rendered") != std::string::npos);
  const Run plain = runKdswap("render --dataset phantom:16 --size 16x16 --nodes 4 --inject-fault delay:1:0:2 --out " +
                              dir.file("b.png"));
  CHECK(plain.code == 0);
  CHECK(plain.err.find("nodes rendered") == std::string::npos);
}
