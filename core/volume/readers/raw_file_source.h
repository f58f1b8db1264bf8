// RawFileSource: a VolumeSource over an uncompressed voxel array in a file. Keeps only the file
// descriptor open; read() fetches exactly the bytes a box needs with pread, one run per row (or
// per slab when the box spans whole rows), and converts them to float.
#pragma once

#include <vector>

#include "core/volume/readers/stored_data.h"
#include "core/volume/volume_source.h"

namespace kdswap {

class RawFileSource : public VolumeSource {
 public:
  //! Opens `data.path`, checks its size against `info.dims` and computes the finite value range
  //! in one streaming pass (a few MiB at a time). `info` must already be validated.
  RawFileSource(VolumeInfo info, StoredData data);
  ~RawFileSource() override;
  RawFileSource(const RawFileSource&) = delete;
  RawFileSource& operator=(const RawFileSource&) = delete;

  const VolumeInfo& info() const override { return info_; }
  //! Thread-safe: pread on the shared descriptor, buffers local to the call.
  void read(const VoxelBox& box, float* out) const override;

 private:
  //! Reads `count` voxels starting at linear voxel index `first` into `out` as floats.
  void readRun(std::uint64_t first, std::uint64_t count, float* out, std::vector<unsigned char>& buffer) const;
  void preadFully(void* dst, std::size_t bytes, std::uint64_t at) const;
  void scanRange();

  VolumeInfo info_;
  StoredData data_;
  std::string label_;  //!< how errors name the data file
  int fd_ = -1;
};

}  // namespace kdswap
