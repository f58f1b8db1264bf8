// NiftiReader: NIfTI-1 single-file volumes, .nii (streamed brick by brick) and .nii.gz (decoded
// once). Either header byte order, detected from sizeof_hdr == 348; scl_slope/scl_inter applied.
#pragma once

#include "core/volume/reader.h"

namespace kdswap {

class NiftiReader : public Reader {
 public:
  std::string_view name() const override { return "nifti"; }
  bool accepts(const std::string& path) const override;
  std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const override;
};

}  // namespace kdswap
