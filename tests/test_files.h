// Test helpers for files and the command line: a temporary folder per test, writing bytes, and
// running the kdswap binary with its exit code and stderr.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <atomic>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace kdswap::test {

//! A fresh folder under the system temp dir (unique per process and call), removed at the end.
struct TempDir {
  std::filesystem::path path;
  TempDir() {
    static std::atomic<int> counter{0};
    path = std::filesystem::temp_directory_path() /
           ("kdswap_test_" + std::to_string(::getpid()) + "_" + std::to_string(counter++));
    std::filesystem::create_directories(path);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path, ec);  // best effort: a leftover temp folder must not fail the test
  }
  std::string file(const std::string& name) const { return (path / name).string(); }
};

inline void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

struct Run {
  int code;         //!< exit code, -1 if the process did not exit normally
  std::string err;  //!< what it printed on stderr
};

//! Runs `build/app/kdswap ARGS` (stdout discarded) and returns its exit code and stderr.
inline Run runKdswap(const std::string& args) {
  const TempDir scratch;
  const std::string err = scratch.file("stderr.txt");
  const std::string command = std::string(KDSWAP_BINARY_DIR) + "/app/kdswap " + args + " > /dev/null 2> " + err;
  const int status = std::system(command.c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return Run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace kdswap::test
