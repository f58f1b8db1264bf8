// Reads /proc for memory figures; returns 0 where the kernel does not say.
#include "core/util/memory.h"

#include <cstdio>
#include <fstream>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <sstream>
#include <string>

namespace kdswap {
namespace {

std::uint64_t readKiBField(const char* path, const std::string& key) {
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size(), key) == 0) {
      std::istringstream fields(line.substr(key.size()));
      std::uint64_t kib = 0;
      fields >> kib;
      return kib * 1024;
    }
  }
  return 0;
}

}  // namespace

std::uint64_t peakResidentBytes() { return readKiBField("/proc/self/status", "VmHWM:"); }
std::uint64_t currentResidentBytes() { return readKiBField("/proc/self/status", "VmRSS:"); }
std::uint64_t availableMemoryBytes() { return readKiBField("/proc/meminfo", "MemAvailable:"); }

std::string formatBytes(std::uint64_t bytes) {
  const char* units[] = {"B", "KiB", "MiB", "GiB", "TiB"};
  double value = double(bytes);
  int unit = 0;
  while (value >= 1024.0 && unit < 4) {
    value /= 1024.0;
    ++unit;
  }
  char text[32];
  std::snprintf(text, sizeof text, unit == 0 ? "%.0f %s" : "%.1f %s", value, units[unit]);
  return text;
}

void configureMalloc() {
#if defined(__GLIBC__)
  mallopt(M_ARENA_MAX, 1);
  mallopt(M_MMAP_THRESHOLD, 32 << 20);   // glibc's largest; a larger brick or volume gets its own mapping
  mallopt(M_TRIM_THRESHOLD, 256 << 20);  // the top of the heap goes back only beyond 256 MiB free
#endif
}

}  // namespace kdswap
