// RawReader: headerless voxel files. The layout comes from the command line (RawLayout) or, for
// what it leaves out, from a file name NAME_WxHxD_TYPE.raw (foot_256x256x256_uint8.raw).
#pragma once

#include "core/volume/reader.h"

namespace kdswap {

class RawReader : public Reader {
 public:
  std::string_view name() const override { return "raw"; }
  bool accepts(const std::string& path) const override;
  std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const override;
};

}  // namespace kdswap
