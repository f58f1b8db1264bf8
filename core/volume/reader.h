// Reader: one volume file format. Each format is one file under core/volume/readers/ and one
// line in reader_registry.cpp, the only list of them.
#pragma once

#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <glm/vec3.hpp>

#include "core/volume/volume_source.h"

namespace kdswap {

//! Layout of a headerless raw file, from the command line (overrides the file-name pattern).
struct RawLayout {
  std::optional<glm::ivec3> dims;
  std::optional<std::string> type;  //!< int8 uint8 int16 uint16 int32 uint32 float32 float64
  std::optional<bool> bigEndian;
  std::optional<glm::vec3> spacing;
  std::uint64_t headerBytes = 0;    //!< bytes to skip at the start
  //! The command has --raw-dims and --raw-type: a missing layout names them, else only the file-name
  //! pattern and a header describe a raw file. Not part of the layout itself.
  bool rawOptions = false;
  bool operator==(const RawLayout&) const = default;
};

class Reader {
 public:
  virtual ~Reader() = default;
  virtual std::string_view name() const = 0;  //!< "nrrd", "raw", ...
  //! True when this reader handles `path` (by extension or name pattern).
  virtual bool accepts(const std::string& path) const = 0;
  //! Opens the file: validates the header and sizes; for uncompressed data keeps only the file
  //! open (read() fetches a brick's bytes); compressed data is decoded once. Throws kdswap::Error
  //! naming the file and the problem.
  virtual std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const = 0;
};

//! Picks the reader for `path` and opens it. Throws kdswap::Error (missing file, unknown format).
std::unique_ptr<VolumeSource> openVolumeFile(const std::string& path, const RawLayout& layout = {});

}  // namespace kdswap
