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

bool scalarRequested() {
  static const bool requested = [] {
    const char* simd = std::getenv("KDSWAP_SIMD");
    return simd != nullptr && std::strcmp(simd, "scalar") == 0;
  }();
  return requested;
}

}  // namespace kdswap
