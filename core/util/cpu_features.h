// What the running CPU offers the SIMD kernels, and whether the user asked for the scalar
// reference instead; each is asked once. One place, so every kernel chooses the same way.
#pragma once

namespace kdswap {

//! The CPU runs AVX2 (false where this build cannot ask: not x86-64 with GCC or Clang).
bool cpuHasAvx2();
//! The CPU runs AVX-512 F, VL, DQ and BW, and the OS saves their registers. The kernels still use
//! 256-bit vectors there, but compiled for it they get 32 registers and masked forms.
bool cpuHasAvx512vl();
//! KDSWAP_SIMD=scalar: use the scalar reference paths (to compare with, or to rule SIMD out).
bool scalarRequested();
//! KDSWAP_SIMD=avx2: use the AVX2 kernels compiled for AVX2 alone, even where AVX-512 exists.
bool avx2OnlyRequested();

}  // namespace kdswap
