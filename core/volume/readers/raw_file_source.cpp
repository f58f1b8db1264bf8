// Brick-by-brick reading of uncompressed voxel files.
#include "core/volume/readers/raw_file_source.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "core/util/check.h"
#include "core/util/error.h"

namespace kdswap {
namespace {

constexpr std::uint64_t kChunkVoxels = 1 << 20;  // one pread's worth: at most 8 MiB of bytes

}  // namespace

RawFileSource::RawFileSource(VolumeInfo info, StoredData data) : info_(std::move(info)), data_(std::move(data)) {
  label_ = dataLabel(data_, info_);
  fd_ = ::open(data_.path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(label_ + ": cannot open: " + std::strerror(errno));
  try {
    struct stat st {};
    if (::fstat(fd_, &st) != 0) throw Error(label_ + ": cannot stat: " + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) throw Error(label_ + ": not a regular file");
    const std::uint64_t size = std::uint64_t(st.st_size);
    const std::uint64_t need = std::uint64_t(info_.voxelCount()) * scalarTypeSize(data_.type);
    const std::string layout = dimsText(info_.dims) + " " + std::string(scalarTypeName(data_.type));
    // Compared without adding to the offset: a skip typed in the desktop app can be near 2^64.
    if (size < data_.offset || size - data_.offset < need)
      throw Error(label_ + ": truncated: " + layout + " needs " + std::to_string(need) + " bytes from byte " +
                  std::to_string(data_.offset) + ", the file has " + std::to_string(size));
    if (size - data_.offset > need && !data_.allowTrailing)
      throw Error(label_ + ": header and data size disagree: " + layout + " needs " + std::to_string(need) +
                  " bytes from byte " + std::to_string(data_.offset) + ", the file has " + std::to_string(size));
    scanRange();
  } catch (...) {
    ::close(fd_);
    throw;
  }
}

RawFileSource::~RawFileSource() { ::close(fd_); }

void RawFileSource::preadFully(void* dst, std::size_t bytes, std::uint64_t at) const {
  auto* p = static_cast<unsigned char*>(dst);
  while (bytes > 0) {
    const ssize_t got = ::pread(fd_, p, bytes, off_t(at));
    if (got < 0 && errno == EINTR) continue;
    if (got < 0) throw Error(label_ + ": read failed at byte " + std::to_string(at) + ": " + std::strerror(errno));
    if (got == 0)
      throw Error(label_ + ": file ended at byte " + std::to_string(at) + ": it shrank after it was opened");
    p += got;
    bytes -= std::size_t(got);
    at += std::uint64_t(got);
  }
}

void RawFileSource::scanRange() {
  const std::uint64_t total = std::uint64_t(info_.voxelCount());
  const std::size_t typeSize = scalarTypeSize(data_.type);
  std::vector<unsigned char> bytes(std::min(total, kChunkVoxels) * typeSize);
  std::vector<float> values(std::min(total, kChunkVoxels));
  float lo = std::numeric_limits<float>::max(), hi = std::numeric_limits<float>::lowest();
  std::uint64_t bad = 0;
  for (std::uint64_t first = 0; first < total; first += kChunkVoxels) {
    const std::uint64_t n = std::min(kChunkVoxels, total - first);
    preadFully(bytes.data(), n * typeSize, data_.offset + first * typeSize);
    convertToFloat(bytes.data(), n, data_.type, data_.bigEndian, values.data(), data_.scale, data_.shift);
    for (std::uint64_t i = 0; i < n; ++i) {
      const float v = values[i];
      if (!std::isfinite(v)) {
        ++bad;
        continue;
      }
      lo = std::min(lo, v);
      hi = std::max(hi, v);
    }
  }
  if (bad == total) lo = hi = 0.0f;
  info_.minValue = lo;
  info_.maxValue = hi;
  info_.nonFinite = bad;
}

void RawFileSource::readRun(std::uint64_t first, std::uint64_t count, float* out,
                            std::vector<unsigned char>& buffer) const {
  const std::size_t typeSize = scalarTypeSize(data_.type);
  while (count > 0) {
    const std::uint64_t n = std::min(count, kChunkVoxels);
    buffer.resize(n * typeSize);
    preadFully(buffer.data(), n * typeSize, data_.offset + first * typeSize);
    convertToFloat(buffer.data(), n, data_.type, data_.bigEndian, out, data_.scale, data_.shift);
    if (info_.nonFinite > 0)
      for (std::uint64_t i = 0; i < n; ++i)
        if (!std::isfinite(out[i])) out[i] = info_.minValue;
    first += n;
    count -= n;
    out += n;
  }
}

void RawFileSource::read(const VoxelBox& box, float* out) const {
  const glm::ivec3 d = info_.dims;
  KDSWAP_CHECK(box.lo.x >= 0 && box.lo.y >= 0 && box.lo.z >= 0);
  KDSWAP_CHECK(box.hi.x <= d.x && box.hi.y <= d.y && box.hi.z <= d.z);
  if (box.empty()) return;
  const glm::ivec3 s = box.size();
  auto index = [&](int x, int y, int z) { return (std::uint64_t(z) * std::uint64_t(d.y) + std::uint64_t(y)) * std::uint64_t(d.x) + std::uint64_t(x); };
  std::vector<unsigned char> buffer;
  const std::uint64_t row = std::uint64_t(s.x), slice = row * std::uint64_t(s.y);
  if (s.x == d.x && s.y == d.y) {  // whole slices: one contiguous run
    readRun(index(0, 0, box.lo.z), slice * std::uint64_t(s.z), out, buffer);
  } else if (s.x == d.x) {  // whole rows: one run per slice
    for (int z = 0; z < s.z; ++z) readRun(index(0, box.lo.y, box.lo.z + z), slice, out + z * slice, buffer);
  } else {
    for (int z = 0; z < s.z; ++z)
      for (int y = 0; y < s.y; ++y)
        readRun(index(box.lo.x, box.lo.y + y, box.lo.z + z), row, out + z * slice + y * row, buffer);
  }
}

}  // namespace kdswap
