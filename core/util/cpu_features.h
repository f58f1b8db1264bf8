// What the running CPU offers the SIMD kernels, and whether the user asked for the scalar
// reference instead; each is asked once. One place, so every kernel chooses the same way.
#pragma once

namespace kdswap {

//! The CPU runs AVX2 (false where this build cannot ask: not x86-64 with GCC or Clang).
bool cpuHasAvx2();
//! The CPU runs AVX-512 F, VL, DQ and BW, and the OS saves their registers. The kernels still use
//! 256-bit vectors there, but compiled for it they get 32 registers and masked forms.
bool cpuHasAvx512vl();
//! The CPU has AVX-512 VL (cpuHasAvx512vl) and runs 512-bit vectors as fast as 256-bit ones, as
//! AMD's Zen 4 and Zen 5 do. Intel cores with AVX-512 close a vector port (and may lower the
//! clock) while 512-bit work is in flight: on an Intel Xeon of the Sapphire Rapids class the
//! march with 512-bit registers took 22% longer a frame than with 256-bit ones.
bool cpuRunsWideVectorsAtFullSpeed();
//! The value of KDSWAP_SIMD ("" when unset): scalar, avx2, avx512vl or avx512 ask for one build of
//! the kernels (ray_march.h: chooseMarch).
const char* simdRequest();
//! KDSWAP_SIMD=scalar: use the scalar reference paths (to compare with, or to rule SIMD out).
bool scalarRequested();

}  // namespace kdswap
