// The registry of volume file formats: the only list of readers (STYLE.md's extension seam).
#include "core/volume/reader.h"

#include <filesystem>
#include <system_error>
#include <vector>

#include "core/util/error.h"
#include "core/volume/readers/metaimage_reader.h"
#include "core/volume/readers/nifti_reader.h"
#include "core/volume/readers/nrrd_reader.h"
#include "core/volume/readers/raw_reader.h"
#include "core/volume/readers/vtk_reader.h"

namespace kdswap {
namespace {

const std::vector<std::unique_ptr<Reader>>& readers() {
  static const std::vector<std::unique_ptr<Reader>> list = [] {
    std::vector<std::unique_ptr<Reader>> r;
    r.push_back(std::make_unique<NrrdReader>());
    r.push_back(std::make_unique<MetaImageReader>());
    r.push_back(std::make_unique<NiftiReader>());
    r.push_back(std::make_unique<VtkReader>());
    r.push_back(std::make_unique<RawReader>());
    return r;
  }();
  return list;
}

constexpr const char* kSupported =
    ".nrrd/.nhdr (NRRD), .mhd/.mha (MetaImage), .nii/.nii.gz (NIfTI-1), .vtk (legacy VTK), "
    ".raw (NAME_WxHxD_TYPE.raw or a layout on the command line)";

}  // namespace

std::unique_ptr<VolumeSource> openVolumeFile(const std::string& path, const RawLayout& layout) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw Error(path + ": no such file");
  if (std::filesystem::is_directory(status)) throw Error(path + ": is a directory: expected a volume file");
  // A layout given on the command line means "read this as raw", whatever the extension.
  if (layout.dims || layout.type) return RawReader().open(path, layout);
  for (const auto& reader : readers())
    if (reader->accepts(path)) return reader->open(path, layout);
  throw Error(path + ": unknown volume format: expected " + kSupported);
}

}  // namespace kdswap
