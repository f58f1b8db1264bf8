// libFuzzer target: the input is a whole .mha file given to openVolumeFile (issue 9).
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kdswap::fuzz::openAndRead(kdswap::fuzz::writeScratch("input.mha", data, size));
  return 0;
}
