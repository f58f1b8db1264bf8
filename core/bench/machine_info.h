// The machine a benchmark ran on, recorded with its figures: a shared machine's speed, and the
// machine itself, change between sessions, so a figure without its CPU, cores, kernel choice and
// time cannot be compared with another.
#pragma once

#include <string>

#include <nlohmann/json_fwd.hpp>

namespace kdswap {

struct MachineInfo {
  std::string cpu;          //!< model name, with x86 family and model where the OS tells them
  int logicalCpus = 0;      //!< what the OS offers this process
  int threads = 0;          //!< worker threads the run uses (--threads; 0 there means every core)
  std::string march;        //!< ray-march kernel chosen at run time: scalar, avx2 or avx2+avx512vl
  std::string startedUtc;   //!< ISO 8601, to the second
};

//! This machine, for a run with `threads` worker threads (0: every core), its CPU read from
//! /proc/cpuinfo.
MachineInfo describeMachine(int threads);
//! The same with /proc/cpuinfo's text given (empty, or without a model name: "unknown CPU").
MachineInfo describeMachine(int threads, const std::string& cpuinfo);

//! "machine: CPU, N logical CPUs, T worker threads, ray march K, started at UTC"
std::string formatMachine(const MachineInfo& machine);
nlohmann::json machineJson(const MachineInfo& machine);

}  // namespace kdswap
