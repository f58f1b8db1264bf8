// What the running CPU offers the SIMD kernels, and whether the user asked for the scalar
// reference instead; each is asked once. One place, so every kernel chooses the same way.
#pragma once

namespace kdswap {

//! The CPU runs AVX2 (false where this build cannot ask: not x86-64 with GCC or Clang).
bool cpuHasAvx2();
//! KDSWAP_SIMD=scalar: use the scalar reference paths (to compare with, or to rule SIMD out).
bool scalarRequested();

}  // namespace kdswap
