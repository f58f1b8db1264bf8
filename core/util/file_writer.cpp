#include "core/util/file_writer.h"

#include <cerrno>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <filesystem>
#include <sys/stat.h>
#include <unistd.h>

#include "core/util/error.h"

namespace kdswap {
namespace {

std::string why() { return std::strerror(errno); }

//! Writes all of `bytes` to `fd`, retrying short writes and interrupted calls.
bool writeAll(int fd, std::string_view bytes) {
  const char* p = bytes.data();
  std::size_t left = bytes.size();
  while (left > 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      if (n == 0) errno = EIO;
      return false;
    }
    p += n, left -= std::size_t(n);
  }
  return true;
}

void refuseDirectory(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw Error(path + ": is a directory, not a file to write");
}

}  // namespace

void reportFileSizeLimitAsError() {
  static const bool ignored = std::signal(SIGXFSZ, SIG_IGN) != SIG_ERR;
  (void)ignored;
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  reportFileSizeLimitAsError();
  if (path.empty()) throw Error("an output file name is empty");
  refuseDirectory(path);
  const std::filesystem::path target(path);
  std::filesystem::path folder = target.parent_path();
  if (folder.empty()) folder = ".";
  std::string temp = (folder / (".kdswap-tmp-" + std::to_string(::getpid()) + "-XXXXXX")).string();
  const int fd = ::mkstemp(temp.data());
  if (fd < 0) throw Error(path + ": cannot create a file in " + folder.string() + ": " + why());
  // mkstemp makes the file private (0600); an output file gets the usual permissions.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd, 0666 & ~mask);
  std::string failure;
  if (!writeAll(fd, bytes))
    failure = "write failed: " + why();
  else if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS)  // EINVAL: a file that cannot sync (a pipe)
    failure = "write failed when flushing to disk: " + why();
  if (::close(fd) != 0 && failure.empty()) failure = "write failed when closing: " + why();
  if (failure.empty() && ::rename(temp.c_str(), path.c_str()) != 0) failure = "cannot move the finished file into place: " + why();
  if (!failure.empty()) {
    ::unlink(temp.c_str());
    throw Error(path + ": " + failure);
  }
}

void appendToFile(const std::string& path, std::string_view bytes) {
  reportFileSizeLimitAsError();
  refuseDirectory(path);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0666);
  if (fd < 0) throw Error(path + ": cannot open for appending: " + why());
  std::string failure;
  if (!writeAll(fd, bytes)) failure = "write failed: " + why();
  if (::close(fd) != 0 && failure.empty()) failure = "write failed when closing: " + why();
  if (!failure.empty()) throw Error(path + ": " + failure);
}

}  // namespace kdswap
