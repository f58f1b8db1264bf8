// MetaImageReader: ITK/VTK MetaImage volumes, .mhd (header + ElementDataFile) and .mha (one
// file, ElementDataFile = LOCAL); NDims 3, one channel, binary, optionally zlib-compressed.
#pragma once

#include "core/volume/reader.h"

namespace kdswap {

class MetaImageReader : public Reader {
 public:
  std::string_view name() const override { return "metaimage"; }
  bool accepts(const std::string& path) const override;
  std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const override;
};

}  // namespace kdswap
