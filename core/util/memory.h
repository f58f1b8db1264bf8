// Process memory figures (Linux /proc): peak and current resident set, and memory available.
#pragma once

#include <cstdint>
#include <string>

namespace kdswap {

std::uint64_t peakResidentBytes();     //!< VmHWM of this process
std::uint64_t currentResidentBytes();  //!< VmRSS of this process
std::uint64_t availableMemoryBytes();  //!< MemAvailable of the machine
std::string formatBytes(std::uint64_t bytes);  //!< "1.5 GiB"

//! Sets glibc's malloc up for frames of image buffers (elsewhere nothing); call first thing in main.
//! - One arena for the whole process. Virtual nodes are tasks on a thread pool and their buffers
//!   move between nodes, so one thread allocates what another frees; per-thread arenas then keep
//!   freed memory that the other threads cannot reuse (peak RSS of the phantom at P = 64 varied
//!   330-336 MB with them, 327-328 MB with one). The buffers are large and few per frame, so the
//!   shared arena's lock costs nothing measurable.
//! - Buffers up to 32 MiB come from the heap and freed heap memory stays mapped. By default glibc
//!   maps each buffer of more than 128 KiB-32 MiB (its threshold moves) on its own and unmaps it
//!   when freed, so every frame's partial images and composited halves were fresh pages: a page
//!   fault per 4 KiB and an unmap that flushes the other cores' TLBs (phantom at P = 64: 610 page
//!   faults a frame, 181 with these settings). Peak RSS is unchanged: a frame reuses what the last
//!   one freed.
void configureMalloc();

}  // namespace kdswap
