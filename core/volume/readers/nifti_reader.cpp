// NIfTI-1 header parsing (nifti.nimh.nih.gov/nifti-1: the 348-byte nifti_1_header), done here
// rather than through libniftiio so uncompressed files stream and need no whole-volume buffer.
#include "core/volume/readers/nifti_reader.h"

#include <bit>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <glm/common.hpp>

#include "core/util/error.h"
#include "core/volume/readers/header_text.h"
#include "core/volume/readers/inflate_stream.h"
#include "core/volume/readers/stored_data.h"

namespace kdswap {
namespace {

constexpr std::size_t kHeaderBytes = 348;
// Byte offsets of the nifti_1_header fields used here.
constexpr std::size_t kDimAt = 40, kDatatypeAt = 70, kBitpixAt = 72, kPixdimAt = 76, kVoxOffsetAt = 108,
                      kSlopeAt = 112, kInterAt = 116, kMagicAt = 344;

bool endsWith(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

//! Reads a field of the header in the file's byte order.
class HeaderView {
 public:
  HeaderView(const unsigned char* bytes, bool swap) : bytes_(bytes), swap_(swap) {}
  template <typename T>
  T get(std::size_t at) const {
    unsigned char b[sizeof(T)];
    std::memcpy(b, bytes_ + at, sizeof(T));
    if (swap_)
      for (std::size_t i = 0; i < sizeof(T) / 2; ++i) std::swap(b[i], b[sizeof(T) - 1 - i]);
    T v;
    std::memcpy(&v, b, sizeof(T));
    return v;
  }

 private:
  const unsigned char* bytes_;
  bool swap_;
};

std::optional<ScalarType> niftiType(int datatype) {
  switch (datatype) {
    case 2: return ScalarType::Uint8;
    case 4: return ScalarType::Int16;
    case 8: return ScalarType::Int32;
    case 16: return ScalarType::Float32;
    case 64: return ScalarType::Float64;
    case 256: return ScalarType::Int8;
    case 512: return ScalarType::Uint16;
    case 768: return ScalarType::Uint32;
    default: return std::nullopt;
  }
}

}  // namespace

bool NiftiReader::accepts(const std::string& path) const {
  const std::string lower = lowercase(path);
  return endsWith(lower, ".nii") || endsWith(lower, ".nii.gz");
}

std::unique_ptr<VolumeSource> NiftiReader::open(const std::string& path, const RawLayout&) const {
  const bool compressed = endsWith(lowercase(path), ".gz");
  unsigned char header[kHeaderBytes];
  if (compressed) {
    InflateStream stream(path, 0);
    stream.readExactly(header, kHeaderBytes, "NIfTI-1 header (348 bytes)");
  } else {
    const std::string prefix = readFilePrefix(path, kHeaderBytes);
    if (prefix.size() < kHeaderBytes)
      throw Error(path + ": truncated: a NIfTI-1 header needs 348 bytes, the file has " + std::to_string(prefix.size()));
    std::memcpy(header, prefix.data(), kHeaderBytes);
  }

  // sizeof_hdr is 348 in the writer's byte order: that tells the order of the whole file.
  std::int32_t sizeofHdr = HeaderView(header, false).get<std::int32_t>(0);
  bool swap = false;
  if (sizeofHdr != 348) {
    swap = true;
    sizeofHdr = HeaderView(header, true).get<std::int32_t>(0);
  }
  if (sizeofHdr == 540 || HeaderView(header, false).get<std::int32_t>(0) == 540) throw Error(path + ": NIfTI-2 header: only NIfTI-1 is supported (sizeof_hdr 348)");
  if (sizeofHdr != 348) throw Error(path + ": not a NIfTI-1 file: sizeof_hdr is not 348 in either byte order");
  const bool bigEndian = (std::endian::native == std::endian::big) != swap;
  const HeaderView h(header, swap);

  if (std::memcmp(header + kMagicAt, "ni1\0", 4) == 0)
    throw Error(path + ": magic \"ni1\": separate .hdr/.img pairs are not supported (expected n+1, one .nii file)");
  if (std::memcmp(header + kMagicAt, "n+1\0", 4) != 0)
    throw Error(path + ": magic is not \"n+1\": expected a NIfTI-1 single file");

  std::int16_t dim[8];
  for (int i = 0; i < 8; ++i) dim[i] = h.get<std::int16_t>(kDimAt + 2 * i);
  if (dim[0] < 1 || dim[0] > 7) throw Error(path + ": dim[0] = " + std::to_string(dim[0]) + ": expected 3");
  std::string shape;
  for (int i = 1; i <= dim[0]; ++i) {
    if (i > 1) shape += 'x';
    shape += std::to_string(dim[i]);
  }
  if (dim[0] < 3) throw Error(path + ": dim[0] = " + std::to_string(dim[0]) + " (" + shape + "): only 3D volumes are supported");
  for (int i = 4; i <= dim[0]; ++i)
    if (dim[i] != 1)
      throw Error(path + ": dim[0] = " + std::to_string(dim[0]) + " (" + shape + "): only a single 3D volume is supported");

  VolumeInfo info;
  info.name = path;
  info.dims = dimsFromSizes({dim[1], dim[2], dim[3]}, path, "dim[1..3]");
  // pixdim[1..3] are the voxel sizes, positive by the NIfTI-1 standard; orientation lives in qfac
  // (pixdim[0]) and the qform/sform. A negative size is read as its magnitude, as nibabel's header
  // check repairs it and as every other format here does (kdswap ignores orientation). NaN, Inf,
  // 0 and sizes outside checkSpacing's bounds are refused.
  glm::dvec3 pixdim;
  for (int a = 0; a < 3; ++a) pixdim[a] = double(h.get<float>(kPixdimAt + 4 * (a + 1)));
  char text[96];
  std::snprintf(text, sizeof text, "pixdim[1..3] = %g %g %g", pixdim.x, pixdim.y, pixdim.z);
  checkSpacing(info.dims, glm::abs(pixdim), path, text);
  info.spacing = glm::vec3(glm::abs(pixdim));

  StoredData data;
  const int datatype = h.get<std::int16_t>(kDatatypeAt);
  const auto scalar = niftiType(datatype);
  if (!scalar)
    throw Error(path + ": datatype " + std::to_string(datatype) + ": unsupported (expected one of " + scalarTypeList() + ")");
  data.type = *scalar;
  const int bitpix = h.get<std::int16_t>(kBitpixAt);
  if (bitpix != int(8 * scalarTypeSize(data.type)))
    throw Error(path + ": bitpix " + std::to_string(bitpix) + " disagrees with datatype " +
                std::string(scalarTypeName(data.type)) + ": expected " + std::to_string(8 * scalarTypeSize(data.type)));
  data.bigEndian = bigEndian;

  const float voxOffset = h.get<float>(kVoxOffsetAt);
  if (!(voxOffset >= float(kHeaderBytes) && voxOffset < 1.0e12f && voxOffset == std::floor(voxOffset)))
    throw Error(path + ": vox_offset " + std::to_string(voxOffset) + ": expected a whole number >= 348");
  const float slope = h.get<float>(kSlopeAt), inter = h.get<float>(kInterAt);
  if (std::isfinite(slope) && slope != 0.0f) {  // slope 0 means "no scaling"
    data.scale = slope;
    data.shift = std::isfinite(inter) ? inter : 0.0f;
  }

  data.path = path;
  data.compressed = compressed;
  if (compressed)
    data.skipDecoded = std::uint64_t(voxOffset);
  else
    data.offset = std::uint64_t(voxOffset);
  return openStoredData(std::move(info), data);
}

}  // namespace kdswap
