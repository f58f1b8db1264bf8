// Writing output files so that a failure is always reported and never leaves a partial file:
// the bytes go to a temporary file beside the target, every write, the flush to disk and the
// close are checked (a full disk shows up at any of them), and only then is it renamed into place.
#pragma once

#include <string>
#include <string_view>

namespace kdswap {

//! An output file being written: bytes go to a temporary file beside `path`, which commit()
//! renames onto `path`. Destroyed without commit() (an error, an exception), it removes the
//! temporary file and leaves `path` as it was. Every failure is a kdswap::Error naming `path` and
//! the cause (for example "No space left on device").
class AtomicFile {
 public:
  explicit AtomicFile(const std::string& path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  void write(std::string_view bytes);
  //! Flushes to disk, closes and renames into place.
  void commit();

 private:
  [[noreturn]] void fail(const std::string& what);
  std::string path_, temp_;
  int fd_ = -1;
};

//! Replaces `path` with `bytes` through an AtomicFile.
void writeFileAtomically(const std::string& path, std::string_view bytes);

//! From the first call on, a write past the file-size limit (`ulimit -f`) fails with EFBIG, which
//! the writers report, instead of killing the process with SIGXFSZ. The writers here call it.
void reportFileSizeLimitAsError();

//! Appends `bytes` to `path` (created if missing), checking every write and the close.
void appendToFile(const std::string& path, std::string_view bytes);

}  // namespace kdswap
