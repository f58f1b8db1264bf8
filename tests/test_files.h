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

#include <doctest/doctest.h>
#include <zlib.h>

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

//! The whole file's bytes ("" when it cannot be opened).
inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream bytes;
  bytes << in.rdbuf();
  return bytes.str();
}

inline void writeFile(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

//! `raw` compressed with zlib: gzip framing when `gzip`, else a plain zlib stream.
inline std::string deflateBytes(const std::string& raw, bool gzip) {
  z_stream zs{};
  REQUIRE(deflateInit2(&zs, 6, Z_DEFLATED, gzip ? 15 + 16 : 15, 8, Z_DEFAULT_STRATEGY) == Z_OK);
  std::string out(deflateBound(&zs, uLong(raw.size())), '\0');
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(raw.data()));
  zs.avail_in = uInt(raw.size());
  zs.next_out = reinterpret_cast<Bytef*>(out.data());
  zs.avail_out = uInt(out.size());
  REQUIRE(deflate(&zs, Z_FINISH) == Z_STREAM_END);
  out.resize(zs.total_out);
  deflateEnd(&zs);
  return out;
}

struct Run {
  int code;         //!< exit code, -1 if the process did not exit normally
  std::string err;  //!< what it printed on stderr
};

//! Runs `build/app/kdswap ARGS` (stdout discarded) and returns its exit code and stderr. `env`:
//! NAME=VALUE assignments for the process, e.g. "KDSWAP_IMAGE_MODULE=/x".
inline Run runKdswap(const std::string& args, const std::string& env = "") {
  const TempDir scratch;
  const std::string err = scratch.file("stderr.txt");
  const std::string command =
      (env.empty() ? "" : "env " + env + " ") + std::string(KDSWAP_BINARY_DIR) + "/app/kdswap " + args + " > /dev/null 2> " + err;
  const int status = std::system(command.c_str());
  std::ifstream in(err);
  std::stringstream text;
  text << in.rdbuf();
  return Run{WIFEXITED(status) ? WEXITSTATUS(status) : -1, text.str()};
}

}  // namespace kdswap::test
