// RawReader: headerless voxel files. The layout comes from the command line (RawLayout) or, for
// what it leaves out, from a file name NAME_WxHxD_TYPE.raw (foot_256x256x256_uint8.raw).
#pragma once

#include "core/volume/reader.h"

namespace kdswap {

//! True when `path` ends in .raw (any case): the files this reader opens.
bool isRawFile(const std::string& path);
//! The layout the name NAME_WxHxD_TYPE.raw gives: the type as written (not checked) and the dims
//! (unset when a size does not fit an int: opening the file names that); both unset when the name
//! has no such part.
RawLayout rawLayoutFromName(const std::string& path);

class RawReader : public Reader {
 public:
  std::string_view name() const override { return "raw"; }
  bool accepts(const std::string& path) const override;
  std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const override;
};

}  // namespace kdswap
