// libFuzzer target: the input is a whole .nrrd file given to openVolumeFile (issue 9).
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  kdswap::fuzz::openAndRead(kdswap::fuzz::writeScratch("input.nrrd", data, size));
  return 0;
}
