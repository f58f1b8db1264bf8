// CPU feature and KDSWAP_SIMD queries, cached.
#include "core/util/cpu_features.h"

#include <cstdlib>
#include <cstring>

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

namespace {
bool simdRequested(const char* name) {
  const char* simd = std::getenv("KDSWAP_SIMD");
  return simd != nullptr && std::strcmp(simd, name) == 0;
}
}  // namespace

bool scalarRequested() {
  static const bool requested = simdRequested("scalar");
  return requested;
}

bool avx2OnlyRequested() {
  static const bool requested = simdRequested("avx2");
  return requested;
}

}  // namespace kdswap
