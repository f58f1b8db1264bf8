// libFuzzer target: the raw reader's file-name pattern NAME_WxHxD_TYPE.raw (issue 9). The input's
// first line is the stem of the name ('/' and NUL become '_'), the rest the file's bytes.
#include <algorithm>

#include "tests/fuzz/fuzz_support.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::uint8_t* newline = std::find(data, data + size, std::uint8_t('\n'));
  std::string stem(reinterpret_cast<const char*>(data), std::size_t(newline - data));
  if (stem.empty() || stem.size() > 200) return 0;  // NAME_MAX is 255 with the ".raw"
  std::replace(stem.begin(), stem.end(), '/', '_');
  std::replace(stem.begin(), stem.end(), '\0', '_');
  const std::uint8_t* body = newline == data + size ? newline : newline + 1;
  kdswap::fuzz::openAndRead(kdswap::fuzz::writeScratch(stem + ".raw", body, std::size_t(data + size - body)));
  return 0;
}
