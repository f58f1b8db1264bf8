// libFuzzer target: the input is a whole NIfTI-1 file given to openVolumeFile (issue 9); named
// .nii.gz when it starts with the gzip magic, so the compressed path is fuzzed too.
#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const bool gzip = size >= 2 && data[0] == 0x1f && data[1] == 0x8b;
  kdswap::fuzz::openAndRead(kdswap::fuzz::writeScratch(gzip ? "input.nii.gz" : "input.nii", data, size));
  return 0;
}
