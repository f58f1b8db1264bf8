// zlib/gzip decoding of a file from an offset, with errors that name the file.
#include "core/volume/readers/inflate_stream.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

#include "core/util/error.h"

namespace kdswap {
namespace {

constexpr std::size_t kInputChunk = 1 << 18;
constexpr int kAutoDetectGzipOrZlib = 15 + 32;  // zlib's windowBits: max window, detect header

}  // namespace

InflateStream::InflateStream(const std::string& path, std::uint64_t offset, const std::string& label)
    : path_(label.empty() ? path : label), input_(kInputChunk) {
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(path_ + ": cannot open: " + std::strerror(errno));
  if (::lseek(fd_, off_t(offset), SEEK_SET) < 0) {
    ::close(fd_);
    throw Error(path_ + ": cannot seek to byte " + std::to_string(offset) + ": " + std::strerror(errno));
  }
  if (inflateInit2(&zs_, kAutoDetectGzipOrZlib) != Z_OK) {
    ::close(fd_);
    throw Error(path_ + ": cannot start zlib decoder");
  }
}

InflateStream::~InflateStream() {
  inflateEnd(&zs_);
  ::close(fd_);
}

bool InflateStream::refill() {
  if (fileEnded_) return false;
  for (;;) {
    const ssize_t got = ::read(fd_, input_.data(), input_.size());
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(path_ + ": read failed: " + std::strerror(errno));
    if (got == 0) {
      fileEnded_ = true;
      return false;
    }
    zs_.next_in = input_.data();
    zs_.avail_in = uInt(got);
    return true;
  }
}

std::size_t InflateStream::read(void* out, std::size_t n) {
  auto* dst = static_cast<unsigned char*>(out);
  std::size_t done = 0;
  while (done < n && !streamEnded_) {
    if (zs_.avail_in == 0 && !refill())
      throw Error(path_ + ": compressed data ends early: the file is truncated");
    const std::size_t want = std::min<std::size_t>(n - done, 1u << 30);
    zs_.next_out = dst + done;
    zs_.avail_out = uInt(want);
    const int rc = inflate(&zs_, Z_NO_FLUSH);
    done += want - zs_.avail_out;
    if (rc == Z_STREAM_END) {
      // A gzip file may hold several members back to back (as `cat a.gz b.gz` makes).
      if (zs_.avail_in == 0) refill();
      if (zs_.avail_in >= 2 && zs_.next_in[0] == 0x1f && zs_.next_in[1] == 0x8b)
        inflateReset(&zs_);
      else
        streamEnded_ = true;
    } else if (rc == Z_DATA_ERROR || rc == Z_NEED_DICT) {
      throw Error(path_ + ": corrupt compressed data: " + (zs_.msg ? zs_.msg : "invalid deflate stream"));
    } else if (rc == Z_MEM_ERROR) {
      throw Error(path_ + ": zlib ran out of memory while decoding");
    } else if (rc != Z_OK && rc != Z_BUF_ERROR) {
      throw Error(path_ + ": zlib error " + std::to_string(rc) + " while decoding");
    }
  }
  return done;
}

void InflateStream::readExactly(void* out, std::size_t n, const std::string& what) {
  const std::size_t got = read(out, n);
  if (got != n)
    throw Error(path_ + ": " + what + " ends early: decompressed " + std::to_string(got) + " of " +
                std::to_string(n) + " bytes");
}

void InflateStream::skip(std::uint64_t n, const std::string& what) {
  std::vector<unsigned char> scratch(std::min<std::uint64_t>(n, 1 << 16));
  while (n > 0) {
    const std::size_t want = std::size_t(std::min<std::uint64_t>(n, scratch.size()));
    const std::size_t got = read(scratch.data(), want);
    if (got != want) throw Error(path_ + ": " + what + " ends before the data starts");
    n -= got;
  }
}

}  // namespace kdswap
