// NrrdReader: NRRD volumes (teem's format, NRRD0001..NRRD0005), attached (.nrrd) or detached
// (.nhdr + data file); 3 dimensions; encodings raw and gzip; spacings or space directions.
#pragma once

#include "core/volume/reader.h"

namespace kdswap {

class NrrdReader : public Reader {
 public:
  std::string_view name() const override { return "nrrd"; }
  bool accepts(const std::string& path) const override;
  std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const override;
};

}  // namespace kdswap
