// InflateStream: sequential reading of zlib- or gzip-compressed bytes from a file, from a given
// byte offset (NRRD attached data, .nii.gz, MetaImage CompressedData). Uses zlib directly.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <zlib.h>

namespace kdswap {

class InflateStream {
 public:
  //! Opens `path` and starts decoding at byte `offset` (gzip or zlib header detected). Errors
  //! name the file as `label` (default: `path`). Throws kdswap::Error if it cannot be opened.
  InflateStream(const std::string& path, std::uint64_t offset, const std::string& label = {});
  ~InflateStream();
  InflateStream(const InflateStream&) = delete;
  InflateStream& operator=(const InflateStream&) = delete;

  //! Decodes up to `n` bytes into `out`; fewer only at the end of the compressed data.
  //! Throws kdswap::Error on corrupt or cut-off compressed data.
  std::size_t read(void* out, std::size_t n);
  //! Reads exactly `n` bytes or throws kdswap::Error saying `what` ended early.
  void readExactly(void* out, std::size_t n, const std::string& what);
  //! Discards `n` decoded bytes; throws kdswap::Error if the data ends first.
  void skip(std::uint64_t n, const std::string& what);

 private:
  bool refill();

  std::string path_;
  int fd_ = -1;
  z_stream zs_{};
  std::vector<unsigned char> input_;
  bool fileEnded_ = false;    //!< no more compressed input in the file
  bool streamEnded_ = false;  //!< zlib reported the end of the last member
};

}  // namespace kdswap
