// Process memory figures (Linux /proc): peak and current resident set, and memory available.
#pragma once

#include <cstdint>
#include <string>

namespace kdswap {

std::uint64_t peakResidentBytes();     //!< VmHWM of this process
std::uint64_t currentResidentBytes();  //!< VmRSS of this process
std::uint64_t availableMemoryBytes();  //!< MemAvailable of the machine
std::string formatBytes(std::uint64_t bytes);  //!< "1.5 GiB"

}  // namespace kdswap
