// VtkReader: legacy VTK files (.vtk) holding STRUCTURED_POINTS with one SCALARS array of point
// data, BINARY (big-endian, streamed) or ASCII (parsed once); version 1.0 ASPECT_RATIO or SPACING.
#pragma once

#include "core/volume/reader.h"

namespace kdswap {

class VtkReader : public Reader {
 public:
  std::string_view name() const override { return "vtk"; }
  bool accepts(const std::string& path) const override;
  std::unique_ptr<VolumeSource> open(const std::string& path, const RawLayout& layout) const override;
};

}  // namespace kdswap
