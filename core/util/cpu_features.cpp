// CPU feature and KDSWAP_SIMD queries, cached.
#include "core/util/cpu_features.h"

#include <cstdlib>
#include <cstring>
#include <string>

namespace kdswap {

bool cpuHasAvx2() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") != 0;
  }();
  return has;
#else
  return false;
#endif
}

bool cpuHasAvx512vl() {
#if defined(__x86_64__) && defined(__GNUC__)
  // libgcc's answer includes the OS check (XCR0 saves the opmask and upper vector registers).
  static const bool has = [] {
    __builtin_cpu_init();
    return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("avx512f") &&
           __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq") &&
           __builtin_cpu_supports("avx512bw");
  }();
  return has;
#else
  return false;
#endif
}

bool cpuRunsWideVectorsAtFullSpeed() {
#if defined(__x86_64__) && defined(__GNUC__)
  static const bool fast = [] {
    __builtin_cpu_init();
    return cpuHasAvx512vl() && __builtin_cpu_is("amd");
  }();
  return fast;
#else
  return false;
#endif
}

const char* simdRequest() {
  static const std::string request = [] {
    const char* simd = std::getenv("KDSWAP_SIMD");
    return std::string(simd != nullptr ? simd : "");
  }();
  return request.c_str();
}

namespace {
bool simdRequested(const char* name) { return std::strcmp(simdRequest(), name) == 0; }
}  // namespace

bool scalarRequested() {
  static const bool requested = simdRequested("scalar");
  return requested;
}

}  // namespace kdswap
