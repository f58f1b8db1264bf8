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

AtomicFile::AtomicFile(const std::string& path) : path_(path) {
  reportFileSizeLimitAsError();
  if (path.empty()) throw Error("an output file name is empty");
  refuseDirectory(path);
  std::filesystem::path folder = std::filesystem::path(path).parent_path();
  if (folder.empty()) folder = ".";
  temp_ = (folder / (".kdswap-tmp-" + std::to_string(::getpid()) + "-XXXXXX")).string();
  fd_ = ::mkstemp(temp_.data());
  if (fd_ < 0) throw Error(path + ": cannot create a file in " + folder.string() + ": " + why());
  // mkstemp makes the file private (0600); an output file gets the usual permissions.
  const mode_t mask = ::umask(0);
  ::umask(mask);
  ::fchmod(fd_, 0666 & ~mask);
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!temp_.empty()) ::unlink(temp_.c_str());
}

void AtomicFile::fail(const std::string& what) {
  const std::string message = path_ + ": " + what;
  if (fd_ >= 0) ::close(fd_);
  fd_ = -1;
  ::unlink(temp_.c_str());
  temp_.clear();
  throw Error(message);
}

void AtomicFile::write(std::string_view bytes) {
  if (fd_ < 0) throw Error(path_ + ": written after it was finished");
  if (!writeAll(fd_, bytes)) fail("write failed: " + why());
}

void AtomicFile::commit() {
  if (fd_ < 0) throw Error(path_ + ": finished twice");
  if (::fsync(fd_) != 0 && errno != EINVAL && errno != EROFS)  // EINVAL: a file that cannot sync
    fail("write failed when flushing to disk: " + why());
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) fail("write failed when closing: " + why());
  if (::rename(temp_.c_str(), path_.c_str()) != 0) fail("cannot move the finished file into place: " + why());
  temp_.clear();
}

void writeFileAtomically(const std::string& path, std::string_view bytes) {
  AtomicFile file(path);
  file.write(bytes);
  file.commit();
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
