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

//! How messages name a format.
std::string formatTitle(std::string_view name) {
  if (name == "nrrd") return "NRRD";
  if (name == "metaimage") return "MetaImage";
  if (name == "nifti") return "NIfTI-1";
  if (name == "vtk") return "legacy VTK";
  return std::string(name);
}

}  // namespace

std::unique_ptr<VolumeSource> openVolumeFile(const std::string& path, const RawLayout& layout) {
  std::error_code ec;
  const auto status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw Error(path + ": no such file");
  if (std::filesystem::is_directory(status)) throw Error(path + ": is a directory: expected a volume file");
  // A device or FIFO would be read without end or block the open.
  if (!std::filesystem::is_regular_file(status))
    throw Error(path + ": is not a regular file (a device, FIFO or socket): expected a volume file");
  const Reader* reader = nullptr;
  for (const auto& r : readers())
    if (r->accepts(path)) {
      reader = r.get();
      break;
    }
  // A layout given on the command line means "read this as raw", whatever the extension, except for
  // the formats whose header gives the layout: reading that header as voxels is never meant.
  if (layout.dims || layout.type || layout.bigEndian || layout.spacing || layout.headerBytes > 0) {
    if (reader && reader->name() != "raw")
      throw Error(path + ": a raw layout (dimensions, type, byte order, spacing or skip from the command line) applies only to raw "
                  "files: this is a " + formatTitle(reader->name()) + " file, whose header gives its own layout");
    if (layout.dims || layout.type) return RawReader().open(path, layout);
  }
  if (reader) return reader->open(path, layout);
  throw Error(path + ": unknown volume format: expected " + kSupported);
}

}  // namespace kdswap
