// Output files: a write that fails (a full disk, the file-size limit) is reported with the file's
// name and a non-zero exit, never a truncated file and success; a resumed animation renders again
// a frame whose file is empty.
#include <doctest/doctest.h>

#include <sys/resource.h>
#include <sys/wait.h>

#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/image/image_io.h"
#include "core/util/error.h"
#include "core/util/file_writer.h"

#include "test_files.h"

using namespace kdswap;
namespace fs = std::filesystem;

namespace {

//! Lowers this process's file-size limit for one scope (writes past it fail with EFBIG).
struct FileSizeLimit {
  rlimit saved{};
  explicit FileSizeLimit(rlim_t bytes) {
    reportFileSizeLimitAsError();  // else the first write past the limit kills the test with SIGXFSZ
    REQUIRE(getrlimit(RLIMIT_FSIZE, &saved) == 0);
    rlimit lower = saved;
    lower.rlim_cur = bytes;
    REQUIRE(setrlimit(RLIMIT_FSIZE, &lower) == 0);
  }
  ~FileSizeLimit() { setrlimit(RLIMIT_FSIZE, &saved); }
};

bool onlyFile(const fs::path& dir, const std::string& name) {
  int count = 0;
  for (const auto& entry : fs::directory_iterator(dir)) count += entry.path().filename() == name ? 1 : 100;
  return count == 1;
}

//! Runs kdswap under `ulimit -f BLOCKS` (512-byte blocks); stdout discarded.
test::Run runLimited(int blocks, const std::string& args, const test::TempDir& scratch) {
  const std::string err = scratch.file("stderr.txt");
  const std::string command = "bash -c 'ulimit -f " + std::to_string(blocks) + "; exec " +
                              std::string(KDSWAP_BINARY_DIR) + "/app/kdswap " + args + "' > /dev/null 2> " + err;
  const int status = std::system(command.c_str());
  return test::Run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, test::readFile(err)};
}

}  // namespace

TEST_CASE("a file written past the disk's room fails with its name and the cause, and keeps the old contents") {
  const test::TempDir dir;
  const std::string path = dir.file("table.csv");
  writeFileAtomically(path, "old\n");
  {
    const FileSizeLimit limit(1000);
    const std::string tooLarge = path + ": write failed: File too large", failed = path + ": write failed";
    CHECK_THROWS_WITH_AS(writeFileAtomically(path, std::string(5000, 'x')), doctest::Contains(tooLarge.c_str()), Error);
    CHECK_THROWS_WITH_AS(appendToFile(path, std::string(5000, 'x')), doctest::Contains(failed.c_str()), Error);
  }
  CHECK(test::readFile(path).substr(0, 4) == "old\n");
  CHECK(onlyFile(dir.path, "table.csv"));  // no temporary file left behind
  writeFileAtomically(path, "new\n");
  CHECK(test::readFile(path) == "new\n");
  appendToFile(path, "more\n");
  CHECK(test::readFile(path) == "new\nmore\n");
  CHECK_THROWS_WITH_AS(writeFileAtomically(dir.path.string(), "x"), doctest::Contains("is a directory"), Error);
}

TEST_CASE("kdswap render on a full disk exits 2 naming the image, and leaves no truncated picture") {
  const test::TempDir dir;
  for (const char* name : {"frame.png", "frame.exr", "frame.tif", "frame.jpg"}) {
    CAPTURE(name);
    const std::string out = dir.file(name);
    const test::Run run = runLimited(8, "render --dataset phantom:64 --size 256x256 --out " + out, dir);
    CHECK(run.code == 2);
    CHECK(run.err.find(out + ": ") != std::string::npos);
    CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
    CHECK_FALSE(fs::exists(out));
  }
  CHECK(onlyFile(dir.path, "stderr.txt"));
  // With room, the same command writes a picture that reads back.
  const std::string out = dir.file("frame.png");
  CHECK(runLimited(100000, "render --dataset phantom:64 --size 256x256 --out " + out, dir).code == 0);
  CHECK(readImage(out).width() == 256);
}

TEST_CASE("kdswap render --stats into a directory is one line naming it") {
  const test::TempDir dir;
  const test::Run run = test::runKdswap("render --dataset phantom:32 --size 32x32 --stats " + dir.path.string() +
                                        " --out " + dir.file("a.png"));
  CHECK(run.code == 2);
  CHECK(run.err.find("is a directory") != std::string::npos);
  CHECK(std::count(run.err.begin(), run.err.end(), '\n') == 1);
}

TEST_CASE("kdswap animate --resume renders again a frame whose file is empty") {
  const test::TempDir dir;
  const std::string args = "animate --dataset phantom:32 --size 48x40 --frames 3 --no-video --out-dir " + dir.path.string();
  REQUIRE(test::runKdswap(args).code == 0);
  const std::string frame = dir.file("frame_0001.png");
  const std::string before = test::readFile(frame);
  REQUIRE(!before.empty());
  std::ofstream(frame, std::ios::trunc).close();  // as a full disk or a killed writer leaves it
  REQUIRE(test::runKdswap(args + " --resume").code == 0);
  CHECK(test::readFile(frame) == before);
  CHECK(readImage(frame).width() == 48);
}

TEST_CASE("kdswap export past the disk's room exits 2 naming the file, and can replace its own input") {
  const test::TempDir dir;
  const std::string out = dir.file("phantom.nrrd");
  const test::Run full = runLimited(8, "export --dataset phantom:32 --out " + out, dir);
  CHECK(full.code == 2);
  CHECK(full.err.find(out + ": write failed") != std::string::npos);
  CHECK_FALSE(fs::exists(out));
  // The volume read may be the file written: the new one is renamed into place at the end.
  REQUIRE(test::runKdswap("export --dataset phantom:32 --out " + out).code == 0);
  const std::string before = test::readFile(out);
  REQUIRE(test::runKdswap("export --volume " + out + " --out " + out).code == 0);
  const std::string after = test::readFile(out);
  CHECK(after.substr(after.size() - 32 * 32 * 32 * 4) == before.substr(before.size() - 32 * 32 * 32 * 4));
  int files = 0;
  for (const auto& entry : fs::directory_iterator(dir.path)) files += entry.path().filename() != "stderr.txt";
  CHECK(files == 1);  // no temporary file left behind
}
