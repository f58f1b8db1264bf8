// Interim: file formats arrive with the readers (issue 4); only built-in data sets until then.
#include "core/volume/reader.h"

#include "core/util/error.h"

namespace kdswap {

std::unique_ptr<VolumeSource> openVolumeFile(const std::string& path, const RawLayout&) {
  throw Error(path + ": volume files are not supported in this build yet");
}

}  // namespace kdswap
