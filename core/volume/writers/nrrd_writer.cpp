// NRRD writer (teem's NRRD0004 header, attached raw data).
#include "core/volume/writers/nrrd_writer.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <vector>

#include "core/util/error.h"
#include "core/util/file_writer.h"

namespace kdswap {
namespace {

const char* typeName(NrrdSample s) {
  switch (s) {
    case NrrdSample::Uint8: return "uint8";
    case NrrdSample::Uint16: return "uint16";
    case NrrdSample::Float32: break;
  }
  return "float";
}

//! Slice values as the file's bytes (little endian, as x86 and ARM store them).
void encodeSlice(const std::vector<float>& values, NrrdSample sample, float lo, float hi, std::vector<unsigned char>& out) {
  if (sample == NrrdSample::Float32) {
    out.resize(values.size() * sizeof(float));
    std::memcpy(out.data(), values.data(), out.size());
    return;
  }
  const float levels = sample == NrrdSample::Uint8 ? 255.0f : 65535.0f;
  const float span = hi - lo;
  const std::size_t width = sample == NrrdSample::Uint8 ? 1 : 2;
  out.resize(values.size() * width);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const float level = span > 0.0f ? std::round((values[i] - lo) / span * levels) : 0.0f;
    const auto k = std::uint16_t(std::clamp(level, 0.0f, levels));  // NaN cannot reach here: sources write min
    if (width == 1)
      out[i] = static_cast<unsigned char>(k);
    else
      out[2 * i] = static_cast<unsigned char>(k & 0xFF), out[2 * i + 1] = static_cast<unsigned char>(k >> 8);
  }
}

}  // namespace

NrrdSample parseNrrdSample(const std::string& text, const std::string& option) {
  if (text == "float32" || text == "float") return NrrdSample::Float32;
  if (text == "uint8") return NrrdSample::Uint8;
  if (text == "uint16") return NrrdSample::Uint16;
  throw Error(option + " \"" + text + "\": expected float32, uint8 or uint16");
}

NrrdWritten writeNrrd(const std::string& path, const VolumeSource& source, NrrdSample sample,
                      const std::function<void(int, int)>& progress) {
  const VolumeInfo& info = source.info();
  // Beside the target, renamed into place at the end: a failure leaves no partial file, and the
  // volume being read may be the very file being replaced.
  AtomicFile file(path);
  auto fail = [&](const std::string& what) { throw Error(path + ": " + what); };
  char header[1024];
  int n = std::snprintf(header, sizeof header,
                        "NRRD0004\n# written by kdswap export from %s\ntype: %s\ndimension: 3\nsizes: %d %d %d\n"
                        "spacings: %.9g %.9g %.9g\nendian: little\nencoding: raw\n",
                        info.name.c_str(), typeName(sample), info.dims.x, info.dims.y, info.dims.z,
                        double(info.spacing.x), double(info.spacing.y), double(info.spacing.z));
  if (sample != NrrdSample::Float32 && n > 0 && n < int(sizeof header))
    n += std::snprintf(header + n, sizeof header - std::size_t(n), "old min: %.9g\nold max: %.9g\n",
                       double(info.minValue), double(info.maxValue));
  if (n <= 0 || n + 1 >= int(sizeof header)) fail("header too long (data set name?)");
  header[n++] = '\n';  // a blank line ends the header
  file.write(std::string_view(header, std::size_t(n)));
  std::vector<float> slice(std::size_t(info.dims.x) * std::size_t(info.dims.y));
  std::vector<unsigned char> bytes;
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  for (int z = 0; z < info.dims.z; ++z) {
    source.read(VoxelBox{glm::ivec3(0, 0, z), glm::ivec3(info.dims.x, info.dims.y, z + 1)}, slice.data());
    for (float v : slice) lo = std::min(lo, v), hi = std::max(hi, v);  // sources write NaN as min
    encodeSlice(slice, sample, info.minValue, info.maxValue, bytes);
    file.write(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
    if (progress) progress(z + 1, info.dims.z);
  }
  file.commit();
  NrrdWritten written{lo, hi, info.minValue, info.maxValue};
  if (sample != NrrdSample::Float32) {  // in levels, as encodeSlice stores them
    std::vector<float> ends{lo, hi, info.minValue, info.maxValue};
    std::vector<unsigned char> levels;
    encodeSlice(ends, sample, info.minValue, info.maxValue, levels);
    const bool wide = sample == NrrdSample::Uint16;
    auto level = [&](int i) { return wide ? float(levels[2 * i] | levels[2 * i + 1] << 8) : float(levels[i]); };
    written = NrrdWritten{level(0), level(1), level(2), level(3)};
  }
  return written;
}

}  // namespace kdswap
