// The AVX-512 VL march (ray_march_avx512vl.cpp) with 512-bit registers where they pay: compact
// voxels are interpolated four samples to a register instead of two. Same operations, same bits.
// Chosen on CPUs that run 512-bit vectors at full speed (cpuRunsWideVectorsAtFullSpeed): on AMD
// Zen 5 the paper cell took 440 ms against 461; on an Intel Xeon of the Sapphire Rapids class
// turbulence with waves took 47 ms against 39.
#define KDSWAP_MARCH_AVX512VL 1
#define KDSWAP_MARCH_WIDE 1
#include "core/render/ray_march_avx2.cpp"
