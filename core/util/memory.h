// Process memory figures (Linux /proc): peak and current resident set, and memory available.
#pragma once

#include <cstdint>
#include <string>

namespace kdswap {

std::uint64_t peakResidentBytes();     //!< VmHWM of this process
std::uint64_t currentResidentBytes();  //!< VmRSS of this process
std::uint64_t availableMemoryBytes();  //!< MemAvailable of the machine
std::string formatBytes(std::uint64_t bytes);  //!< "1.5 GiB"

//! One malloc arena for the whole process (glibc; elsewhere nothing). Virtual nodes are tasks on a
//! thread pool and their buffers move between nodes, so one thread allocates what another frees;
//! per-thread arenas then keep freed memory that the other threads cannot reuse (peak RSS of the
//! phantom at P = 64 varied 330-336 MB with them, 327-328 MB with one). The buffers are large and
//! few per frame, so the shared arena's lock costs nothing measurable. Call first thing in main.
void useOneMallocArena();

}  // namespace kdswap
