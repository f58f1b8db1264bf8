// MachineInfo from /proc/cpuinfo, the thread count and the march dispatch.
#include "core/bench/machine_info.h"

#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>
#include <oneapi/tbb/info.h>

#include "core/render/ray_march.h"

namespace kdswap {
namespace {

//! The value of the first "key : value" line of /proc/cpuinfo's text whose key is `key`.
std::string cpuinfoField(const std::string& text, const std::string& key) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    const std::size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    while (!name.empty() && (name.back() == ' ' || name.back() == '\t')) name.pop_back();
    if (name != key) continue;
    std::size_t start = colon + 1;
    while (start < line.size() && line[start] == ' ') ++start;
    return line.substr(start);
  }
  return "";
}

std::string readCpuinfo() {
  std::ifstream in("/proc/cpuinfo");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

MachineInfo describeMachine(int threads) { return describeMachine(threads, readCpuinfo()); }

MachineInfo describeMachine(int threads, const std::string& cpuinfo) {
  MachineInfo m;
  m.cpu = cpuinfoField(cpuinfo, "model name");
  if (m.cpu.empty()) m.cpu = "unknown CPU";
  // Virtual machines often name only the vendor line ("AMD EPYC"); family and model tell the
  // generation apart.
  const std::string family = cpuinfoField(cpuinfo, "cpu family"), model = cpuinfoField(cpuinfo, "model");
  if (!family.empty() && !model.empty()) m.cpu += " (family " + family + " model " + model + ")";
  m.logicalCpus = int(std::thread::hardware_concurrency());
  m.threads = threads > 0 ? threads : tbb::info::default_concurrency();
  m.march = marchName(selectedMarchFunction());
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", &utc);
  m.startedUtc = text;
  return m;
}

std::string formatMachine(const MachineInfo& m) {
  return "machine: " + m.cpu + ", " + std::to_string(m.logicalCpus) + " logical CPUs, " + std::to_string(m.threads) +
         " worker threads, ray march " + m.march + ", started " + m.startedUtc + "\n";
}

nlohmann::json machineJson(const MachineInfo& m) {
  return {{"cpu", m.cpu},
          {"logical_cpus", m.logicalCpus},
          {"threads", m.threads},
          {"ray_march", m.march},
          {"started_utc", m.startedUtc}};
}

}  // namespace kdswap
