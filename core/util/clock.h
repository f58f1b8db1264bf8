// Monotonic seconds, for per-node and per-phase timers.
#pragma once

#include <chrono>

namespace kdswap {

inline double nowSeconds() {
  using namespace std::chrono;
  return duration<double>(steady_clock::now().time_since_epoch()).count();
}

}  // namespace kdswap
