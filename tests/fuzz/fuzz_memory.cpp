// Stand-in for core/util/memory.cpp in the fuzz targets: reports a machine with 1 GiB available,
// so validateVolumeInfo refuses any declared size above 64 Mi voxels whatever the fuzzing host
// has. libFuzzer's -malloc_limit_mb (2 GiB) then catches a reader that allocates before validating.
#include "core/util/memory.h"

#include <cstdio>

namespace kdswap {

std::uint64_t peakResidentBytes() { return 0; }
std::uint64_t currentResidentBytes() { return 0; }
std::uint64_t availableMemoryBytes() { return std::uint64_t(1) << 30; }

std::string formatBytes(std::uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f MiB", double(bytes) / (1024.0 * 1024.0));
  return text;
}

}  // namespace kdswap
